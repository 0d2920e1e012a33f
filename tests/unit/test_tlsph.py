"""Corrected-kernel SPH kernels of seed 004 (pmpmsph.kernels.sph.tlsph), eqs. 1-9."""
import numpy as np
import pytest
from tlsph_reference import corrected_kernel_values, fd_kernel_gradient

from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.kernel_functions import kernel_dwdr, kernel_w
from pmpmsph.kernels.sph.smoothing.registry import kernel_code
from pmpmsph.kernels.sph.tlsph import (current_volume, deformation_gradient, energies, expm3,
                                   first_piola, internal_force, kernel_correction,
                                   material_stress, update_F_exp, velocity_gradient)
from pmpmsph.materials import material_from_table
from pmpmsph.materials.dispatch import material_tag

CUBIC, WENDLAND_C2 = kernel_code("cubic"), kernel_code("wendland")


def lattice(n, dim, jitter=0.0, seed=0):
    """n^dim points on [0, 1]^dim (nodes, spacing s), optionally jittered by jitter*s,
    with volumes s^dim scaled by a random factor in [0.8, 1.2] when jittered."""
    s = 1.0 / (n - 1)
    axes = np.meshgrid(*([np.linspace(0.0, 1.0, n)] * dim), indexing="ij")
    x = np.stack([a.ravel() for a in axes], axis=1)
    vol = np.full(len(x), s ** dim)
    if jitter:
        rng = np.random.default_rng(seed)
        x = x + rng.uniform(-jitter, jitter, x.shape) * s
        vol *= rng.uniform(0.8, 1.2, len(x))
    return x, vol, s


def pairs(x, vol, h, kind=CUBIC, corrected=True):
    start, index = neighbour_lists(x, len(x), 2.0 * h)
    wt = np.empty(len(index))
    gw = np.empty((len(index), x.shape[1]))
    bad = kernel_correction(x, vol, start, index, h, kind, x.shape[1], corrected, wt, gw)
    return start, index, wt, gw, bad


def rows(start):
    return np.repeat(np.arange(len(start) - 1), np.diff(start))


CASES = [(1, 12, 0.3), (2, 9, 0.25), (3, 5, 0.2)]


@pytest.mark.parametrize("kind", [CUBIC, WENDLAND_C2])
@pytest.mark.parametrize("dim,n,jitter", CASES)
def test_linear_completeness(dim, n, jitter, kind):
    """Eqs. 1-3: sum V W~ = 1, sum V x_b W~ = x, sum V G = 0, sum V x_b (x) G = I at every
    particle of an irregular cloud, corners and edges included, to round-off."""
    x, vol, s = lattice(n, dim, jitter, seed=dim)
    start, index, wt, gw, bad = pairs(x, vol, 1.3 * s, kind)
    assert bad == 0
    a = rows(start)
    b = index
    N = len(x)
    one = np.bincount(a, vol[b] * wt, N)
    first = np.stack([np.bincount(a, vol[b] * wt * x[b, i], N) for i in range(dim)], 1)
    g0 = np.stack([np.bincount(a, vol[b] * gw[:, j], N) for j in range(dim)], 1)
    I = np.zeros((N, dim, dim))
    for i in range(dim):
        for j in range(dim):
            I[:, i, j] = np.bincount(a, vol[b] * x[b, i] * gw[:, j], N)
    assert np.abs(one - 1).max() < 1e-13
    assert np.abs(first - x).max() < 1e-13
    assert np.abs(g0).max() * s < 1e-12
    assert np.abs(I - np.eye(dim)).max() < 1e-12


@pytest.mark.parametrize("dim,n,jitter", CASES)
@pytest.mark.parametrize("kind", [CUBIC, WENDLAND_C2])
def test_analytic_gradient_matches_eq4(dim, n, jitter, kind):
    """The analytic gradient of the fully corrected kernel (alpha, beta differentiated)
    against the finite difference of eq. 4 at every particle, boundary ones included."""
    x, vol, s = lattice(n, dim, jitter, seed=10 + dim)
    h = 1.2 * s
    start, index, wt, gw, _ = pairs(x, vol, h, kind)
    worst_fwd = worst_cen = 0.0
    for a in range(len(x)):
        b = index[start[a]:start[a + 1]]
        g = gw[start[a]:start[a + 1]]
        scale = np.abs(g).max()
        fwd = fd_kernel_gradient(x, vol, a, h, kind, dim, dh=1e-8 * h)
        cen = fd_kernel_gradient(x, vol, a, h, kind, dim, dh=1e-5 * h, central=True)
        # outside the list the kernel and its FD gradient vanish
        mask = np.ones(len(x), bool)
        mask[b] = False
        assert np.abs(cen[mask]).max(initial=0.0) < 1e-8 * scale
        worst_fwd = max(worst_fwd, np.abs(fwd[b] - g).max() / scale)
        worst_cen = max(worst_cen, np.abs(cen[b] - g).max() / scale)
        vals = np.empty(len(x))
        corrected_kernel_values(x[a], x, vol, h, kind, dim, True, vals)
        assert np.allclose(vals[b], wt[start[a]:start[a + 1]], rtol=1e-12, atol=1e-12 * scale)
    assert worst_fwd < 1e-6
    assert worst_cen < 1e-8


def test_frozen_correction_is_not_the_gradient():
    """Differentiating only W_b and (x - x_b) with alpha and beta frozen at x_a (a
    'simplified' gradient), or the plain kernel gradient, misses eq. 4 by O(1) at a corner
    and breaks sum_b V_b x_b (x) grad W~_b = 1: the full derivative is needed."""
    x, vol, s = lattice(7, 2, 0.2, seed=3)
    h = 1.2 * s
    corner = 0
    fd = fd_kernel_gradient(x, vol, corner, h, CUBIC, 2, dh=1e-5 * h, central=True)
    start, index, _, gw, _ = pairs(x, vol, h)
    b = index[start[corner]:start[corner + 1]]
    scale = np.abs(fd[b]).max()
    assert np.abs(gw[start[corner]:start[corner + 1]] - fd[b]).max() < 1e-8 * scale
    r = x[corner] - x[b]
    rn = np.linalg.norm(r, axis=1)
    w = np.array([kernel_w(CUBIC, 2, q, h) for q in rn])
    dw = np.array([kernel_dwdr(CUBIC, 2, q, h) for q in rn])
    gW = np.where(rn[:, None] > 0, dw[:, None] * r / np.where(rn > 0, rn, 1)[:, None], 0.0)
    M = np.einsum("b,bi,bj->ij", vol[b] * w, r, r)
    beta = -np.linalg.solve(M, (vol[b] * w) @ r)
    alpha = 1.0 / ((vol[b] * w) @ (1.0 + r @ beta))
    frozen = alpha * (gW * (1.0 + r @ beta)[:, None] + w[:, None] * beta)
    for g in (frozen, gW):
        assert np.abs(g - fd[b]).max() > 0.3 * scale
        ident = np.einsum("b,bi,bj->ij", vol[b], x[b], g)
        assert np.abs(ident - np.eye(2)).max() > 0.1


def test_uncorrected_is_plain_kernel():
    x, vol, s = lattice(6, 2, 0.2, seed=4)
    h = 1.1 * s
    start, index, wt, gw, _ = pairs(x, vol, h, corrected=False)
    a = rows(start)
    r = x[a] - x[index]
    rn = np.linalg.norm(r, axis=1)
    w = np.array([kernel_w(CUBIC, 2, q, h) for q in rn])
    dw = np.array([kernel_dwdr(CUBIC, 2, q, h) for q in rn])
    g = np.where(rn[:, None] > 0, dw[:, None] * r / np.where(rn > 0, rn, 1)[:, None], 0.0)
    assert np.allclose(wt, w, rtol=1e-14)
    assert np.allclose(gw, g, rtol=1e-13, atol=1e-13 * np.abs(g).max())


def test_degenerate_row_falls_back_to_shepard():
    """Points on a line in 2D: M of eq. 2 is singular; the row uses W / sum V W."""
    x = np.stack([np.linspace(0, 1, 6), np.zeros(6)], 1)
    vol = np.full(6, 0.2)
    start, index, wt, gw, bad = pairs(x, vol, 0.25)
    assert bad == 6
    assert np.allclose(np.bincount(rows(start), vol[index] * wt), 1.0)
    assert np.isfinite(gw).all()


def linear_map(dim, seed):
    rng = np.random.default_rng(seed)
    return rng.normal(size=(dim, dim)) * 0.3 + np.eye(dim), rng.normal(size=dim)


@pytest.mark.parametrize("dim,n,jitter", CASES)
def test_velocity_gradient_exact_for_linear_field(dim, n, jitter):
    """Eq. 6 with the corrected kernel: L = A for v = A x + c, at every particle."""
    x, vol, s = lattice(n, dim, jitter, seed=20 + dim)
    start, index, _, gw, _ = pairs(x, vol, 1.2 * s)
    A, c = linear_map(dim, dim)
    v = x @ A.T + c
    L = np.full((len(x), 3, 3), np.nan)
    velocity_gradient(np.arange(len(x)), start, index, gw, vol, v, dim, L)
    assert np.abs(L[:, :dim, :dim] - A).max() < 1e-12
    assert (L[:, dim:, :] == 0).all() and (L[:, :, dim:] == 0).all()


@pytest.mark.parametrize("dim,n,jitter", CASES)
def test_deformation_gradient_exact_for_homogeneous_deformation(dim, n, jitter):
    """Eq. 8 with reference-configuration gradients: F = A for x = A X + c."""
    X0, vol0, s = lattice(n, dim, jitter, seed=30 + dim)
    start, index, _, gw0, _ = pairs(X0, vol0, 1.2 * s)
    A, c = linear_map(dim, 7 + dim)
    x = X0 @ A.T + c
    F = np.empty((len(x), 3, 3))
    deformation_gradient(np.arange(len(x)), start, index, gw0, vol0, x, X0, dim, F)
    expect = np.eye(3)
    expect[:dim, :dim] = A
    assert np.abs(F - expect).max() < 1e-12


def stress_field(N, dim, seed):
    rng = np.random.default_rng(seed)
    S = rng.normal(size=(N, 3, 3))
    S = S + S.transpose(0, 2, 1)
    S[:, dim:, :] = 0.0
    S[:, :, dim:] = 0.0
    return S


@pytest.mark.parametrize("corrected", [True, False])
@pytest.mark.parametrize("dim,n,jitter", CASES)
def test_force_is_adjoint_of_velocity_gradient(dim, n, jitter, corrected):
    """Eqs. 5 and 6: sum_a v_a . f_a = -sum_b V_b sigma_b : L_b for any v and sigma (the
    discrete int v . div sigma = -int sigma : grad v; energy conservation with eq. 9), and
    the total force vanishes (momentum), corrected kernel or not."""
    x, vol, s = lattice(n, dim, jitter, seed=40 + dim)
    start, index, _, gw, _ = pairs(x, vol, 1.3 * s, corrected=corrected)
    rng = np.random.default_rng(dim)
    v = rng.normal(size=x.shape)
    sigma = stress_field(len(x), dim, dim)
    f = np.empty_like(x)
    internal_force(start, index, gw, vol, sigma, dim, f)
    L = np.empty((len(x), 3, 3))
    velocity_gradient(np.arange(len(x)), start, index, gw, vol, v, dim, L)
    power = (v * f).sum()
    work = -(vol[:, None, None] * sigma * L).sum()
    assert power == pytest.approx(work, rel=1e-12, abs=1e-12 * np.abs(v * f).sum())
    if corrected:
        assert np.abs(f.sum(axis=0)).max() < 1e-13 * np.abs(f).sum()


@pytest.mark.parametrize("dim,n,jitter", CASES)
def test_total_lagrangian_force_is_adjoint_of_eq8(dim, n, jitter):
    """Eq. 5 on the reference pairs with P = J sigma F^-T is the exact adjoint of eq. 8:
    sum_a v_a . f_a = -sum_a V0_a P_a : dF_a/dt, dF/dt = eq. 8 applied to v. The seed's
    current-configuration force (eq. 5 with the kernel corrected at x) is not: its power
    differs from the stress power of eq. 8 by a term that does not vanish for a
    non-homogeneous motion (the source of the edge instability of that combination)."""
    X0, vol0, s = lattice(n, dim, jitter, seed=50 + dim)
    h = 1.3 * s
    start0, index0, _, gw0, _ = pairs(X0, vol0, h)
    rng = np.random.default_rng(dim)
    x = X0 + 0.05 * np.sin(3 * X0[:, ::-1]) + 0.02 * rng.normal(size=X0.shape) * s
    v = rng.normal(size=X0.shape)
    F = np.empty((len(x), 3, 3))
    deformation_gradient(np.arange(len(x)), start0, index0, gw0, vol0, x, X0, dim, F)
    Fdot = np.empty_like(F)
    deformation_gradient(np.arange(len(x)), start0, index0, gw0, vol0, X0 + v, X0, dim,
                         Fdot)
    Fdot -= np.eye(3)
    sigma = stress_field(len(x), dim, 60 + dim)
    P = np.empty_like(sigma)
    first_piola(np.arange(len(x)), F, sigma, P)
    assert np.allclose(P, np.linalg.det(F)[:, None, None] * sigma
                       @ np.linalg.inv(F).transpose(0, 2, 1), rtol=1e-12, atol=1e-12)
    f = np.empty_like(x)
    internal_force(start0, index0, gw0, vol0, P, dim, f)
    power = (v * f).sum()
    stress_power = -(vol0[:, None, None] * P * Fdot).sum()
    assert power == pytest.approx(stress_power, rel=1e-11)
    # current-configuration force with V = J V0: a different number
    vol = np.empty(len(x))
    current_volume(F, vol0, vol)
    start, index, _, gw, _ = pairs(x, vol, h)
    internal_force(start, index, gw, vol, sigma, dim, f)
    assert abs((v * f).sum() - stress_power) > 1e-6 * abs(stress_power)


def test_uniform_stress_interior_free_and_stretched_body_contracts():
    """Uniform tension s 1 on a regular 2D plate: no force deeper than 4h inside, inward
    forces at the free surface whose sum over the right half is the traction -s * height."""
    n = 21
    x, vol, sp = lattice(n, 2)
    vol = vol.reshape(n, n)
    vol[[0, -1], :] *= 0.5
    vol[:, [0, -1]] *= 0.5
    vol = vol.ravel()
    h = 1.2 * sp
    start, index, _, gw, _ = pairs(x, vol, h)
    sig = 0.7
    sigma = np.zeros((len(x), 3, 3))
    sigma[:, 0, 0] = sigma[:, 1, 1] = sigma[:, 2, 2] = sig
    f = np.empty_like(x)
    internal_force(start, index, gw, vol, sigma, 2, f)
    d = np.minimum(x, 1 - x).min(axis=1)
    interior = d > 4 * h + 1e-9  # the rows b of eq. 5 feel the boundary within 2h
    assert np.abs(f[interior]).max() < 1e-13
    # the surface particles are pulled inwards with about the traction s times their
    # share of the edge (the next layers carry small corrections of either sign)
    edge = np.abs(x[:, 0] - 1.0) < 1e-12
    assert (f[edge, 0] < 0).all()
    mid = edge & (x[:, 1] > 2 * h) & (x[:, 1] < 1 - 2 * h)
    assert f[mid, 0] / sp == pytest.approx(-sig, rel=0.01)
    corner = np.argmin(np.abs(x - 1).sum(axis=1))
    assert (f[corner] < 0).all()
    right = x[:, 0] > 0.5
    assert f[right, 0].sum() == pytest.approx(-sig * 1.0, rel=1e-12)
    assert np.abs(f[right, 1].sum()) < 1e-13


def test_force_approximates_div_sigma():
    """T_a = f_a / V_a -> div sigma at interior particles for a smooth sigma field."""
    errs = []
    for n in (21, 41):
        x, vol, sp = lattice(n, 2, 0.0)
        start, index, _, gw, _ = pairs(x, vol, 1.3 * sp)
        X, Y = x[:, 0], x[:, 1]
        sigma = np.zeros((len(x), 3, 3))
        sigma[:, 0, 0] = np.sin(2 * X) * Y
        sigma[:, 1, 1] = X * X * np.cos(Y)
        sigma[:, 0, 1] = sigma[:, 1, 0] = np.exp(X + 0.5 * Y) * 0.1
        div = np.stack([2 * np.cos(2 * X) * Y + 0.05 * np.exp(X + 0.5 * Y),
                        0.1 * np.exp(X + 0.5 * Y) - X * X * np.sin(Y)], axis=1)
        f = np.empty_like(x)
        internal_force(start, index, gw, vol, sigma, 2, f)
        inner = np.minimum(x, 1 - x).min(axis=1) > 0.25
        errs.append(np.abs(f[inner] / vol[inner, None] - div[inner]).max())
    assert errs[0] < 0.02
    assert errs[1] < 0.3 * errs[0]  # second order in the interior


def test_expm3():
    out = np.empty((3, 3))
    th = 0.9
    A = np.zeros((3, 3))
    A[0, 1], A[1, 0] = -th, th
    expm3(A, out)
    R = np.array([[np.cos(th), -np.sin(th), 0], [np.sin(th), np.cos(th), 0], [0, 0, 1]])
    assert np.abs(out - R).max() < 1e-15
    N = np.array([[0.0, 0.7, -0.2], [0, 0, 0.4], [0, 0, 0]])
    expm3(N, out)
    assert np.abs(out - (np.eye(3) + N + N @ N / 2)).max() < 1e-15
    rng = np.random.default_rng(5)
    for scale in (1e-3, 0.3, 1.0, 4.0):
        A = rng.normal(size=(3, 3)) * scale
        w, V = np.linalg.eig(A)
        ref = (V @ np.diag(np.exp(w)) @ np.linalg.inv(V)).real
        expm3(A, out)
        tol = 1e-14 if scale <= 1.0 else 1e-13
        assert np.abs(out - ref).max() < tol * np.abs(ref).max()
        assert np.linalg.det(out) == pytest.approx(np.exp(np.trace(A)), rel=1e-13)
        inv = np.empty((3, 3))
        expm3(-A, inv)
        assert np.abs(out @ inv - np.eye(3)).max() < 1e-13 * max(1.0, np.exp(2 * scale))


def test_update_F_exp_and_volume():
    rng = np.random.default_rng(6)
    L = rng.normal(size=(4, 3, 3))
    F = np.eye(3) + 0.1 * rng.normal(size=(4, 3, 3))
    Fn = np.empty_like(F)
    dt = 0.05
    update_F_exp(L, F, dt, Fn)
    E = np.empty((3, 3))
    for a in range(4):
        expm3(dt * L[a], E)
        assert np.allclose(Fn[a], E @ F[a], rtol=0, atol=1e-15)
        # det F_new = exp(dt tr L) det F: eq. 9 carries the volume change exactly
        assert np.linalg.det(Fn[a]) == pytest.approx(np.exp(dt * np.trace(L[a]))
                                                     * np.linalg.det(F[a]), rel=1e-13)
    vol0 = rng.uniform(1, 2, 4)
    vol = np.empty(4)
    current_volume(Fn, vol0, vol)
    assert np.allclose(vol, np.linalg.det(Fn) * vol0, rtol=1e-14)


def test_energies_and_material_stress():
    """Eq. 7 with the Hartmann-Neff potential (eq. 12), and the stress loop (eq. 11)."""
    mat = material_from_table({"model": "hartmann_neff", "mu": 1.25, "k": 5.833, "rho": 3.0},
                              "m", 2)
    par = mat.params(2)
    N = 3
    F = np.tile(np.eye(3), (N, 1, 1))
    F[1, 0, 0] = 1.1
    F[2, 0, 1] = 0.2
    state = np.zeros((N, 0))
    vol0 = np.array([0.5, 1.0, 2.0])
    mass = 3.0 * vol0
    v = np.array([[1.0, 0.0], [0.0, 2.0], [0.0, 0.0]])
    K, U = energies(mass, v, vol0, F, mat.type_code, state, par, 2,
                    material_tag((mat.type_code,)))
    assert K == pytest.approx(0.5 * (1.5 * 1 + 3.0 * 4))

    def psi(F):
        J = np.linalg.det(F)
        Bb = J ** (-2 / 3) * F @ F.T
        return 0.625 * (np.trace(Bb) - 3) + 5.833 / 50 * (J ** 5 + J ** -5 - 2)
    assert U == pytest.approx(sum(vol0[a] * psi(F[a]) for a in range(N)), rel=1e-12)
    sigma = np.empty((N, 3, 3))
    material_stress(mat.type_code, F, np.zeros_like(F), 0.0, state, par, sigma,
                    material_tag((mat.type_code,)))
    assert np.abs(sigma[0]).max() == 0.0
    J = np.linalg.det(F[1])
    Bb = J ** (-2 / 3) * F[1] @ F[1].T
    tau = 1.25 * (Bb - np.trace(Bb) / 3 * np.eye(3)) + 0.5833 * (J ** 5 - J ** -5) * np.eye(3)
    assert np.allclose(sigma[1], tau / J, rtol=1e-12, atol=1e-14)
