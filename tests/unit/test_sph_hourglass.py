"""Hourglass control of the updated SPH solid (kernels/sph/hourglass.py, `[sph] hourglass`)."""
import numpy as np
import pytest

from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.hourglass import hourglass_fit, hourglass_forces
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


def _evaluate(X, x, kappa=2.0):
    """(Fh, acc) of the control at positions x with reference X (all rows SPH, one solid)."""
    n = len(X)
    start, index = neighbour_lists(X, n, 2.0 * H, half=True)
    mass = np.full(n, RHO * DP * DP)
    rho = np.full(n, RHO)
    method = np.ones(n, np.int8)
    mat = np.zeros(n, np.int32)
    fluid = np.zeros(1, np.bool_)
    Fh = np.zeros((n, 3, 3))
    u = np.ascontiguousarray(x - X)  # the kernels work on displacements
    hourglass_fit((0, 0), (0,), H, n, u, X, mass, rho, method, mat, fluid, start, index,
                  np.zeros((n, 3, 3)), Fh)
    acc = np.zeros((n, 2))
    hourglass_forces((0, 0), (0,), H, n, u, X, Fh, mass, rho, np.full(n, C), method, mat,
                     fluid, start, index, kappa, acc)
    return Fh, acc, mass


def _energy(X, x, kappa=2.0):
    """U_hg of the module docstring, written out over all ordered pairs (numpy)."""
    n = len(X)
    V = DP * DP
    M = RHO * C * C
    U = 0.0
    for a in range(n):
        dX = X - X[a]
        R = np.hypot(dX[:, 0], dX[:, 1])
        nb = (R > 0) & (R < 2 * H)
        phi = np.array([-kernel_dwdr(0, 2, r, H) / r for r in R[nb]])
        dx = x[nb] - x[a]
        w = V * phi
        A = np.einsum("k,ki,kj->ij", w, dX[nb], dX[nb])
        Cm = np.einsum("k,ki,kj->ij", w, dx, dX[nb])
        Fh = Cm @ np.linalg.inv(A)
        e = dx - dX[nb] @ Fh.T
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


def test_force_is_the_gradient_of_the_energy_and_conserves_momentum():
    """A random displacement: sum m acc = 0 to round-off, and m_a acc_a = -dU/dx_a (central
    differences of U with the fit recomputed: the envelope argument of the docstring), for
    interior and surface particles alike."""
    X = _disc(0.55)
    rng = np.random.default_rng(1)
    x = np.ascontiguousarray(X + 0.01 * DP * rng.standard_normal(X.shape))
    _, acc, mass = _evaluate(X, x)
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
            grad = (_energy(X, xp) - _energy(X, xm)) / (2 * d)
            assert f[a, i] == pytest.approx(-grad, rel=1e-5, abs=1e-6 * scale)


def test_the_odd_even_mode_is_resisted():
    """A checkerboard displacement (the mode the corrected gradient does not see in the
    interior of a lattice): the control pushes every interior particle back, along its own
    displacement, with the stiffness 3.41 kappa M / (rho dp^2) (h = 1.3 dp, cubic spline; the
    measured value)."""
    X = _disc()
    i = np.rint(X / DP - 0.5).astype(int)
    sign = np.where((i[:, 0] + i[:, 1]) % 2 == 0, 1.0, -1.0)
    u = 1e-4 * DP * np.stack([sign, 0.5 * sign], axis=1)
    _, acc, _ = _evaluate(X, np.ascontiguousarray(X + u))
    inner = np.hypot(X[:, 0], X[:, 1]) < 0.75 - 2 * H
    k = -np.sum(acc[inner] * u[inner], axis=1) / np.sum(u[inner] ** 2, axis=1)
    cos = -np.sum(acc[inner] * u[inner], axis=1) / (
        np.linalg.norm(acc[inner], axis=1) * np.linalg.norm(u[inner], axis=1))
    assert np.all(cos > 1 - 1e-9)
    assert np.all(np.abs(k / (2.0 * C * C / DP ** 2) - 3.41) < 0.02)


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
    from pmpmsph import ConfigError, load_case_text

    assert load_case_text(CASE).sph.hourglass == 2.0
    assert load_case_text(CASE.replace("hourglass = 2.0\n", "")).sph.hourglass == 0.0
    total = CASE.replace('[sph]', '[sph]\nformulation = "total"').replace('"verlet"', '"rk3"')
    assert load_case_text(total).sph.hourglass == 2.0
    with pytest.raises(ConfigError) as err:
        load_case_text(CASE.replace(old, new))
    assert err.value.key == "sph.hourglass"
