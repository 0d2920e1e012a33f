"""Hourglass control of the updated SPH solid (kernels/sph/hourglass.py, `[sph] hourglass`),
with the linear fit and the quadratic one (kernels/sph/hourglass_quadratic.py,
`[sph] hourglass_fit = "quadratic"`)."""
import numpy as np
import pytest

from pmpmsph import ConfigError, load_case_text
from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.views import pair_lists, smoothing_of
from pmpmsph.kernels.sph.hourglass_quadratic import (HOURGLASS_FITS, quadratic_basis,
                                                     symmetric_pseudo_inverse)
from pmpmsph.kernels.sph.kernel_functions import kernel_dwdr

DP = 0.1
H = 1.3 * DP
RHO = 1000.0
C = 30.0   # wave speed: M = rho c^2


def _disc(radius=0.75):
    """A lattice disc: particles of a free surface all round."""
    g = (np.arange(-10, 10) + 0.5) * DP
    X = np.array([(a, b) for a in g for b in g if a * a + b * b < radius * radius])
    return np.ascontiguousarray(X)


def _evaluate(X, x, kappa=2.0, fit="linear"):
    """(fitted coefficients, acc, mass) of the control at positions x with reference X (all
    rows SPH, one solid), with the linear fit (Fh) or the quadratic one
    (kernels/sph/hourglass_quadratic.py)."""
    n = len(X)
    start, index = neighbour_lists(X, n, 2.0 * H, half=True)
    mass = np.full(n, RHO * DP * DP)
    rho = np.full(n, RHO)
    method = np.ones(n, np.int8)
    mat = np.zeros(n, np.int32)
    fluid = np.zeros(1, np.bool_)
    fit_pairs, fit_rows, forces, shape, scratch = HOURGLASS_FITS[fit]
    Fh = np.zeros((n,) + shape)
    u = np.ascontiguousarray(x - X)  # the kernels work on displacements
    smoothing, pairs = smoothing_of((0, 0), (0,), H), pair_lists(n, start, index)
    control = fit_pairs(2, 0, H, n, X, method, mat, fluid, start, index)
    fit_rows(smoothing, pairs, control, u, X, mass, rho, method, mat, fluid,
             np.zeros((n,) + scratch), Fh)
    acc = np.zeros((n, 2))
    forces(smoothing, pairs, control, u, X, Fh, mass, rho, np.full(n, C), kappa, acc)
    return Fh, acc, mass


def _basis(d, fit):
    """The fit's basis at the pair vector d: d itself (linear) or P(d) (quadratic)."""
    if fit == "linear":
        return d
    P = np.zeros(5)
    quadratic_basis(2, H, np.array([d[0], d[1], 0.0]), 1.0, P)
    return P


def _energy(X, x, kappa=2.0, fit="linear"):
    """U_hg of the module docstrings, written out over all ordered pairs (numpy; each row's
    fit by weighted least squares, the least-norm one where it is not unique)."""
    V, M, U = DP * DP, RHO * C * C, 0.0
    for a in range(len(X)):
        dX = X - X[a]
        R = np.hypot(dX[:, 0], dX[:, 1])
        nb = (R > 0) & (R < 2 * H)
        w = V * np.array([-kernel_dwdr(0, 2, r, H) / r for r in R[nb]])
        P = np.array([_basis(d, fit) for d in dX[nb]])
        du = x[nb] - x[a] - dX[nb]
        sw = np.sqrt(w)[:, None]
        coef = np.linalg.lstsq(sw * P, sw * du, rcond=None)[0]
        e = du - P @ coef
        U += 0.5 * kappa * V * M * np.sum(w * np.sum(e * e, axis=1))
    return U


def test_homogeneous_deformation_is_fitted_exactly_and_takes_no_force():
    """Stretch, shear and a 30 degree rotation of the whole disc: every particle's fit,
    surface particles included, is the applied F, and the control exerts no force."""
    X = _disc()
    c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    F = np.array([[c, -s], [s, c]]) @ np.array([[1.05, 0.02], [-0.01, 0.97]])
    x = np.ascontiguousarray(X @ F.T + np.array([0.3, -0.2]))
    Fh, acc, _ = _evaluate(X, x)
    assert np.abs(Fh[:, :2, :2] - F).max() < 1e-12
    assert np.abs(acc).max() < 1e-9 * C * C / DP


BEAM = np.array([((i + 0.5) * DP, (j - 0.5) * DP) for i in range(-5, 5) for j in (0, 1)])


@pytest.mark.parametrize("fit", ["linear", "quadratic"])
def test_force_is_the_gradient_of_the_energy_and_conserves_momentum(fit):
    """A random displacement: sum m acc = 0 to round-off, and m_a acc_a = -dU/dx_a (central
    differences of U with the fit recomputed: the envelope argument of the docstrings), for
    interior and surface particles alike, of a disc and of a beam two particles thick (whose
    rows the quadratic fit leaves undetermined: its least-norm fit)."""
    rng = np.random.default_rng(1)
    for X in (_disc(0.55), BEAM):
        x = np.ascontiguousarray(X + 0.01 * DP * rng.standard_normal(X.shape))
        _, acc, mass = _evaluate(X, x, fit=fit)
        f = mass[:, None] * acc
        scale = np.abs(f).max()
        assert scale > 0
        assert np.abs(f.sum(axis=0)).max() < 1e-12 * scale * len(X)
        r = np.hypot(X[:, 0], X[:, 1])
        for a in (int(np.argmin(r)), int(np.argmax(r))):
            for i in range(2):
                d = 1e-6 * DP
                xp, xm = x.copy(), x.copy()
                xp[a, i] += d
                xm[a, i] -= d
                grad = (_energy(X, xp, fit=fit) - _energy(X, xm, fit=fit)) / (2 * d)
                assert f[a, i] == pytest.approx(-grad, rel=1e-5, abs=1e-6 * scale)


@pytest.mark.parametrize("fit, stiffness", [("linear", 3.41), ("quadratic", 2.445)])
def test_the_odd_even_mode_is_resisted(fit, stiffness):
    """A checkerboard displacement (the mode the corrected gradient does not see in the
    interior of a lattice, and which no linear or quadratic field fits): the control pushes
    every interior particle back, along its own displacement, with the stiffness
    `stiffness` kappa M / (rho dp^2) (h = 1.3 dp, cubic spline; the measured values: 3.41
    with the linear fit, 2.43-2.46 with the quadratic one, the rows within 2h of the
    surface left out)."""
    X = _disc()
    i = np.rint(X / DP - 0.5).astype(int)
    sign = np.where((i[:, 0] + i[:, 1]) % 2 == 0, 1.0, -1.0)
    u = 1e-4 * DP * np.stack([sign, 0.5 * sign], axis=1)
    _, acc, _ = _evaluate(X, np.ascontiguousarray(X + u), fit=fit)
    inner = np.hypot(X[:, 0], X[:, 1]) < 0.75 - 2 * H
    k = -np.sum(acc[inner] * u[inner], axis=1) / np.sum(u[inner] ** 2, axis=1)
    cos = -np.sum(acc[inner] * u[inner], axis=1) / (
        np.linalg.norm(acc[inner], axis=1) * np.linalg.norm(u[inner], axis=1))
    assert np.all(cos > 1 - 1e-9)
    assert np.all(np.abs(k / (2.0 * C * C / DP ** 2) - stiffness) < 0.02)


CASE = """
dimension = 2
[domain]
min = [-1.0, -1.0]
max = [2.0, 2.0]
[sph]
correction = true
hourglass = 2.0
integrator = "verlet"
[materials.steel]
model = "linear_elastic"
E = 1.0e6
nu = 0.3
rho = 1000.0
[[bodies]]
name = "plate"
method = "sph"
material = "steel"
shape = "box"
min = [0.0, 0.0]
max = [1.0, 1.0]
spacing = 0.1
[time]
end = 0.1
cfl = 0.3
"""


@pytest.mark.parametrize("old,new", [("hourglass = 2.0", "hourglass = -1.0"),
                                     ('integrator = "verlet"', 'integrator = "rk3"')])
def test_the_option_and_its_bad_values(old, new):
    """`[sph] hourglass` (default 0: off) takes kappa >= 0; in the updated formulation with
    the Verlet integrator (whose drifts carry the control's displacements), in the total one
    with any (it forms them as x - X0)."""
    assert load_case_text(CASE).sph.hourglass == 2.0
    assert load_case_text(CASE.replace("hourglass = 2.0\n", "")).sph.hourglass == 0.0
    total = CASE.replace('[sph]', '[sph]\nformulation = "total"').replace('"verlet"', '"rk3"')
    assert load_case_text(total).sph.hourglass == 2.0
    with pytest.raises(ConfigError) as err:
        load_case_text(CASE.replace(old, new))
    assert err.value.key == "sph.hourglass"


def _bending(X, kappa_b=0.4):
    """Pure bending of a beam along x: u_x = -k x y, u_y = k x^2 / 2 (a quadratic field)."""
    u = np.stack([-kappa_b * X[:, 0] * X[:, 1], 0.5 * kappa_b * X[:, 0] ** 2], axis=1)
    return np.ascontiguousarray(X + u)


def test_quadratic_fit_takes_no_force_in_bending():
    """Bending (and a stretch with a rotation on top) of a disc and of a beam two particles
    thick, whose rows cannot tell X_y^2 from X_y (the pseudo-inverse's case): no force, to
    round-off, where the linear fit pushes back with a force of the order of the bending."""
    c, s = np.cos(0.3), np.sin(0.3)
    Rot = np.array([[c, -s], [s, c]])
    for X in (_disc(), BEAM):
        x = _bending(X) @ (Rot @ np.diag([1.03, 0.98])).T
        _, acc, _ = _evaluate(X, np.ascontiguousarray(x), fit="quadratic")
        assert np.abs(acc).max() < 1e-8 * C * C / DP
    _, acc_linear, _ = _evaluate(BEAM, _bending(BEAM), fit="linear")
    assert np.abs(acc_linear).max() > 1e-3 * C * C / DP


def test_pseudo_inverse():
    """The Jacobi pseudo-inverse: A A+ A = A and A+ A A+ = A+ for a singular symmetric
    matrix (two equal rows and columns), the inverse for a regular one."""
    rng = np.random.default_rng(0)
    B = rng.standard_normal((6, 6))
    A = B @ B.T
    work, vec, out = np.zeros((6, 6)), np.zeros((6, 6)), np.zeros((6, 6))
    symmetric_pseudo_inverse(A, 6, out, work, vec)
    assert np.abs(out @ A - np.eye(6)).max() < 1e-10
    A[5], A[:, 5] = A[4], A[:, 4]
    A[5, 5] = A[4, 4]
    symmetric_pseudo_inverse(A, 6, out, work, vec)
    assert np.abs(A @ out @ A - A).max() < 1e-10 * np.abs(A).max()
    assert np.abs(out @ A @ out - out).max() < 1e-10 * np.abs(out).max()


def test_the_fit_option():
    """`[sph] hourglass_fit`: "linear" by default, "quadratic"; refused with the control off
    (it would do nothing) and for an unknown name."""
    assert load_case_text(CASE).sph.hourglass_fit == "linear"
    text = CASE.replace("hourglass = 2.0", 'hourglass = 2.0\nhourglass_fit = "quadratic"')
    assert load_case_text(text).sph.hourglass_fit == "quadratic"
    for bad in (text.replace("hourglass = 2.0\n", ""), text.replace('"quadratic"', '"cubic"')):
        with pytest.raises(ConfigError) as err:
            load_case_text(bad)
        assert err.value.key == "sph.hourglass_fit"


def test_quadratic_fit_in_3d():
    """3D (9 coefficients a component): a cube of 6^3 particles bent (u_x = -k x z,
    u_z = k x^2 / 2) and stretched takes no force to round-off; a checkerboard is pushed
    back along itself."""
    g = (np.arange(6) - 2.5) * DP
    X = np.ascontiguousarray([(a, b, c) for a in g for b in g for c in g])
    n = len(X)
    start, index = neighbour_lists(X, n, 2.0 * H, half=True)
    mass, rho = np.full(n, RHO * DP**3), np.full(n, RHO)
    method, mat, fluid = np.ones(n, np.int8), np.zeros(n, np.int32), np.zeros(1, np.bool_)
    fit_pairs, fit_rows, forces, shape, scratch = HOURGLASS_FITS["quadratic"]
    control = fit_pairs(3, 0, H, n, X, method, mat, fluid, start, index)

    def acc_of(u):
        Q = np.zeros((n,) + shape)
        smoothing, pairs = smoothing_of((0, 0, 0), (0,), H), pair_lists(n, start, index)
        fit_rows(smoothing, pairs, control, u, X, mass, rho, method, mat, fluid,
                 np.zeros((n,) + scratch), Q)
        acc = np.zeros((n, 3))
        forces(smoothing, pairs, control, u, X, Q, mass, rho, np.full(n, C), 2.0, acc)
        return acc

    k = 0.4
    bend = np.stack([-k * X[:, 0] * X[:, 2] + 0.02 * X[:, 1], 0.01 * X[:, 1],
                     0.5 * k * X[:, 0] ** 2], axis=1)
    assert np.abs(acc_of(np.ascontiguousarray(bend))).max() < 1e-8 * C * C / DP
    i = np.rint(X / DP + 2.5).astype(int)
    sign = np.where(i.sum(axis=1) % 2 == 0, 1.0, -1.0)
    u = np.ascontiguousarray(1e-4 * DP * np.stack([sign, 0.5 * sign, -sign], axis=1))
    acc = acc_of(u)
    inner = np.all(np.abs(X) < 1.0 * DP, axis=1)
    assert np.all(np.sum(acc[inner] * u[inner], axis=1) < 0)
