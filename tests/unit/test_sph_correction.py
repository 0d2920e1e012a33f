"""Kernel gradient correction of the updated-Lagrangian SPH solid (`[sph] correction = true`;
kernels/sph/rates.py `correction_matrices` and `sph_rates`; Bonet & Lok, seed 004 §2.1 for the
linear completeness it restores): on a jittered disc with a free surface the corrected
velocity gradient is exact for linear velocity fields (the plain one is not, at the
surface), and the corrected forces conserve momentum and angular momentum and are the
adjoint of the corrected velocity gradient (stress power = minus the power of the forces)."""
import numpy as np
import pytest

from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.rates import sph_rates
from pmpmsph.kernels.sph.views import (pair_lists, pair_rows, rate_options, rate_terms, rates,
                                       smoothing_of)
from pmpmsph.kernels.sph.correction import correction_matrices

H_FACTOR = 1.3


def _disc(seed=0, dp=0.1, radius=1.0):
    rng = np.random.default_rng(seed)
    g = np.arange(-radius, radius + 1e-9, dp)
    X, Y = np.meshgrid(g, g, indexing="ij")
    x = np.stack([X.ravel(), Y.ravel()], 1)
    x = x[np.hypot(x[:, 0], x[:, 1]) <= radius]
    x += rng.uniform(-0.15, 0.15, x.shape) * dp
    n = len(x)
    rho = 1000.0 * (1.0 + 0.05 * rng.uniform(-1, 1, n))
    mass = 1000.0 * dp * dp * np.ones(n)
    return x, mass, rho, dp * H_FACTOR


def _rates(x, v, mass, rho, sigma, h, corr):
    n, dim = x.shape
    start, index = neighbour_lists(x, n, 2.0 * h, half=True)
    method = np.ones(n, np.int8)
    mat = np.zeros(n, np.int32)
    B = np.zeros((n, 3, 3))
    if corr:
        correction_matrices((0,) * dim, (0,), h, n, x, mass, rho, method, start, index,
                            np.zeros((n, 3, 3)), B)
    S = np.zeros((n, 6))
    r2 = 1.0 / rho ** 2
    S[:, 0], S[:, 1], S[:, 2] = sigma[:, 0, 0] * r2, sigma[:, 1, 1] * r2, sigma[:, 2, 2] * r2
    S[:, 3] = sigma[:, 0, 1] * r2
    acc, drho, L = np.zeros((n, dim)), np.zeros(n), np.zeros((n, 3, 3))
    sph_rates(smoothing_of((0,) * dim, (0,), h), pair_lists(n, start, index),
              pair_rows(x, v, v, mass, rho, S, np.ones(n), method, mat),
              rate_options((0,) if corr else (), np.zeros(1, np.bool_), np.zeros(3),
                          damping=0.0, av_alpha=0.0, av_beta=0.0, want_force=True,
                          want_L=True, want_fsi=False, split=False),
              rate_terms(as_n=4.0, B=B), rates(acc, drho, L))
    return acc, drho, L, B


def test_corrected_velocity_gradient_is_exact_for_linear_fields_at_a_free_surface():
    x, mass, rho, h = _disc()
    G = np.array([[0.3, -0.7], [1.1, 0.2]])
    v = x @ G.T + np.array([0.5, -0.25])
    sigma = np.zeros((len(x), 3, 3))
    _, drho, L, B = _rates(x, v, mass, rho, sigma, h, corr=True)
    assert np.abs(L[:, :2, :2] - G).max() < 1e-12
    assert np.allclose(drho, -rho * np.trace(G), rtol=1e-12)
    # B is symmetric; within the jitter of I inside, about 2 across the surface (the kernel
    # is cut in half there)
    assert np.abs(B - np.transpose(B, (0, 2, 1))).max() < 1e-12
    edge = np.hypot(x[:, 0], x[:, 1]) > 0.85
    assert np.abs(B[~edge, :2, :2] - np.eye(2)).max() < 0.35
    assert np.abs(B[edge, :2, :2] - np.eye(2)).max() > 0.8
    _, _, Lp, _ = _rates(x, v, mass, rho, sigma, h, corr=False)
    assert np.abs(Lp[edge, :2, :2] - G).max() > 0.3   # the truncated kernel at the surface


def test_corrected_forces_conserve_momentum_and_are_the_adjoint_of_L():
    x, mass, rho, h = _disc(seed=1)
    n = len(x)
    rng = np.random.default_rng(2)
    sigma = np.zeros((n, 3, 3))
    sigma[:, 0, 0], sigma[:, 1, 1], sigma[:, 2, 2] = rng.normal(size=(3, n)) * 1e3
    sigma[:, 0, 1] = sigma[:, 1, 0] = rng.normal(size=n) * 1e3
    v = rng.normal(size=(n, 2))
    acc, _, L, _ = _rates(x, v, mass, rho, sigma, h, corr=True)
    f = mass[:, None] * acc
    scale = np.abs(f).max()
    assert np.abs(f.sum(0)).max() < 1e-12 * scale * n
    torque = (x[:, 0] * f[:, 1] - x[:, 1] * f[:, 0]).sum()
    assert abs(torque) < 1e-12 * scale * n
    power = (v * f).sum()
    stress_power = (mass / rho * np.einsum("aij,aij->a", sigma[:, :2, :2], L[:, :2, :2])).sum()
    assert power == pytest.approx(-stress_power, rel=1e-10)



def test_correction_matrix_inverts_the_moment_matrix_in_3d():
    """B_a = (M_a^T)^-1 on a jittered 3D lattice (the 3D inverse goes through the cofactor
    matrix): B_a M_a^T = I for every row whose M_a is invertible enough to be corrected."""
    from pmpmsph.kernels.sph.correction import CORRECTION_MIN_DET

    rng = np.random.default_rng(0)
    g = np.arange(5) * 0.1
    x = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    x += rng.uniform(-0.01, 0.01, x.shape)
    n = len(x)
    start, index = neighbour_lists(x, n, 0.26, half=True)
    M, B = np.zeros((n, 3, 3)), np.zeros((n, 3, 3))
    correction_matrices((0, 0, 0), (0,), 0.13, n, x, np.ones(n), np.full(n, 1000.0),
                        np.ones(n, np.int8), start, index, M, B)
    ok = np.linalg.det(M) > CORRECTION_MIN_DET
    assert ok.sum() > n // 2
    assert np.abs(B[ok] @ np.transpose(M[ok], (0, 2, 1)) - np.eye(3)).max() < 1e-12
