"""Hourglass (zero-energy mode) control of SPH solids (`[sph] hourglass`), updated- and
total-Lagrangian (the total stage forms u = x - X0 at each evaluation and uses the
reference-configuration half lists: physics/sph/total_lagrangian.py).

With the corrected gradient of `correction` (Bonet & Lok), the velocity gradient of a
particle does not see a displacement that alternates in sign from particle to particle (on a
regular lattice the pair terms of such a field cancel: an odd-even, zero-energy mode of the
nodally integrated SPH solid, the one the tensile-instability and stress-point literature
discusses). In the interior of a smooth field nothing excites it; at a free surface the
nodal force is not exact (its boundary terms) and the error goes into that mode. Measured on
scene 11 (the plate with a hole, tests/verification/test_coupled_plate.py): in the static
equilibrium of the SPH disc with the exact Kirsch displacement prescribed 2 hole radii out,
the displacement error is a checkerboard (alternating row to row), and sigma_yy of
the hole's surface row is 23 % short while the corrected gradient of the exact field is
only 5 % short. With the control (kappa = 2) the coupled plate's surface row is 8 % short
(within the 10 % of scene 11). The same mode is the sawtooth of scene 9 with the seed's
h = cell size (tests/verification/test_coupled.py); with kappa = 2 its strains are within
1.3 % (tests/verification/test_sph_hourglass_scenes.py).

The control penalises, for every pair of a solid, the distance of particle b from the place
particle a's own fitted deformation gradient puts it (the idea of Ganzenmueller, "An
hourglass control algorithm for Lagrangian Smooth Particle Hydrodynamics", CMAME 2015, here
with the weights of the corrected gradient and written as an energy):

    e_ab = (x_b - x_a) - Fh_a (X_b - X_a),        X: reference (initial) positions X0,
    U_hg = kappa/2 sum_a V_a M_a sum_b V_b phi_ab |e_ab|^2,   phi_ab = -W'(R_ab)/R_ab >= 0,

R_ab = |X_b - X_a| (pairs within the kernel support in the reference configuration),
M_a = rho_a c_a^2 the particle's P-wave modulus (`sound_speeds`), kappa a dimensionless
factor, and Fh_a the least-squares fit of the pair vectors with the same weights
(`hourglass_fit`): Fh_a minimises sum_b V_b phi_ab |e_ab|^2. So (envelope theorem) the
derivative of U_hg through Fh_a vanishes, and the force -dU_hg/dx is the pair force

    f_a = kappa V_a V_b phi_ab (M_a e_ab - M_b e_ba) = -f_b      (e_ba with Fh_b),

exactly (V and M held fixed): it conserves momentum, is zero for every homogeneous
deformation (Fh is then the deformation gradient, at a free surface too), and for a smooth
field is of the order of its curvature times the spacing. The weights V_b phi_ab are those
of which the Bonet-Lok gradient is the weighted least-squares fit (M_a of
`correction_matrices` is sum_b V_b phi_ab x_ba (x) x_ba), so for a small strain Fh - 1 is
the corrected displacement gradient. A first version took the particle's integrated F for
Fh_a: not exactly conservative, it grew an instability at the corners of the pure SPH plate
of scene 11 (CFL 0.3 and 0.2); with the fit it is stable there.
Written in displacements u = x - X (the field `u`, integrated as u += dt v beside x):
x_ba - Fh_a X_ba = u_ba - (Fh_a - 1) X_ba, with Fh_a - 1 fitted from the u_ba. The two are
equal, but e_ab is a small residual of O(spacing) vectors, and positions carry an absolute
rounding of ulp(|x|) ~ 2e-16 per drift, which the residual amplifies: with positions the
one-rank and two-rank runs of the plate (whose sums run in different orders) drifted apart
by 9e-9 relative in 150 steps, with displacements they agree like the rest of the coupling
(tests/parallel/test_coupled_mpi.py).
The pairs are those of the current neighbour lists (support plus skin): the control is
meant for solids that stay near their reference configuration (small strain, any rotation).
The hourglass stiffness adds to the wave speed, and the time step is not reduced for it:
the checkerboard mode of a lattice gets omega^2 = 3.4 kappa c^2/dp^2 (m omega^2 =
3.4 kappa M V/dp^2; tests/unit/test_sph_hourglass.py, h = 1.3 dp) on top of its elastic
stiffness, and an explicit step needs omega dt < 2. Scene 11 (dt = 0.39 dp/c at CFL 0.3):
kappa = 1, 2, 4 stable, kappa = 10 not.
"""
import numpy as np

from ...jit import njit
from ...materials.tensor import block_inverse
from ...codes import SPH
from .kernel_functions import kernel_dwdr


@njit(inline="always")
def pair_weight(dim, kern, h, X0, a, b):
    """phi = -W'(R)/R at R = |X_b - X_a| (0 outside the support)."""
    R2 = 0.0
    for i in range(dim):
        d = X0[b, i] - X0[a, i]
        R2 += d * d
    if R2 >= 4.0 * h * h or R2 == 0.0:
        return 0.0
    R = np.sqrt(R2)
    return -kernel_dwdr(kern, dim, R, h) / R


@njit
def control_pairs(dim, kern, h, n_query, X0, method, mat, fluid, start, index):
    """The pairs of the control over half neighbour lists, (a, b) rows and phi_ab: every
    owned SPH row a of a solid with each neighbour b, an SPH row of a's material within the
    support in the reference configuration."""
    count = 0
    for a in range(n_query):
        if method[a] == SPH and not fluid[mat[a]]:
            count += start[a + 1] - start[a]
    rows = np.empty((count, 2), np.int64)
    phi = np.empty(count)
    m = 0
    for a in range(n_query):
        if method[a] != SPH or fluid[mat[a]]:
            continue
        for k in range(start[a], start[a + 1]):
            b = index[k]
            if method[b] != SPH or mat[b] != mat[a]:
                continue
            w = pair_weight(dim, kern, h, X0, a, b)
            if w != 0.0:
                rows[m, 0], rows[m, 1], phi[m] = a, b, w
                m += 1
    return rows[:m], phi[:m]


@njit
def hourglass_fit(smoothing, pairs, control, u, X0, mass, rho, method, mat, fluid, A, Fh):
    """Fh_a = 1 + C_a A_a^-1 for the owned SPH rows [0, n_query) of a solid: the weighted
    least-squares fit of u_b - u_a = (Fh_a - 1) (X_b - X_a) over the SPH neighbours b of a's
    material (u: displacements, module docstring), weights V_b phi(|X_ba|), with
    C_a = sum_b w u_ba (x) X_ba and A_a = sum_b w X_ba (x) X_ba (scratch, >= n_query rows).
    Over the pairs `control` = (rows, phi) of `control_pairs`. A row whose A is (nearly)
    singular gets Fh = 0 (its pair terms are then skipped)."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
    dim = len(dim_tag)
    for a in range(n_query):
        for i in range(3):
            for j in range(3):
                A[a, i, j] = 0.0
                Fh[a, i, j] = 0.0
    rows, phi = control
    for m in range(len(phi)):
        a, b = rows[m, 0], rows[m, 1]
        wa = mass[b] / rho[b] * phi[m]
        wb = mass[a] / rho[a] * phi[m] if b < n_query else 0.0
        for i in range(dim):
            xi = u[b, i] - u[a, i]
            Xi = X0[b, i] - X0[a, i]
            for j in range(dim):
                Xj = X0[b, j] - X0[a, j]
                # A in the upper-left block, C stored in Fh until the solve
                A[a, i, j] += wa * Xi * Xj
                Fh[a, i, j] += wa * xi * Xj
                if wb != 0.0:
                    A[b, i, j] += wb * Xi * Xj
                    Fh[b, i, j] += wb * xi * Xj
    Ai = np.zeros((3, 3))
    C = np.zeros((3, 3))
    for a in range(n_query):
        if method[a] != SPH or fluid[mat[a]]:
            continue
        d = block_inverse(A[a], dim, Ai)
        for i in range(dim):
            for j in range(dim):
                C[i, j] = Fh[a, i, j]
        ok = d > HOURGLASS_MIN_DET
        for i in range(dim):
            for j in range(dim):
                s = 0.0
                if ok:
                    for k in range(dim):
                        s += C[i, k] * Ai[k, j]
                    if i == j:
                        s += 1.0
                Fh[a, i, j] = s


#: a row whose (dimensionless, = 1 in a full lattice) moment matrix A has det below this
#: takes no hourglass control (a particle with collinear or almost no SPH neighbours)
HOURGLASS_MIN_DET = 1e-2


@njit
def hourglass_forces(smoothing, pairs, control, u, X0, Fh, mass, rho, cs, kappa, acc):
    """Adds the hourglass control (module docstring) to acc of the owned SPH rows
    [0, n_query), over the pairs `control` of `control_pairs` (each pair once, both ends; a
    halo row b takes no force here, its owner adds it): pairs of two SPH rows of one solid
    material, both with a fit (Fh != 0; `hourglass_fit`, refreshed in the halo)."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
    dim = len(dim_tag)
    rows, phi = control
    for m in range(len(phi)):
        a, b = rows[m, 0], rows[m, 1]
        if Fh[a, 0, 0] == 0.0 or Fh[b, 0, 0] == 0.0:
            continue
        Va = mass[a] / rho[a]
        Ma = rho[a] * cs[a] * cs[a]
        Vb = mass[b] / rho[b]
        Mb = rho[b] * cs[b] * cs[b]
        c = kappa * Va * Vb * phi[m]
        for i in range(dim):
            pa = 0.0  # ((Fh_a - 1) X_ba)_i
            pb = 0.0  # ((Fh_b - 1) X_ba)_i
            for j in range(dim):
                dX = X0[b, j] - X0[a, j]
                one = 1.0 if i == j else 0.0
                pa += (Fh[a, i, j] - one) * dX
                pb += (Fh[b, i, j] - one) * dX
            uba = u[b, i] - u[a, i]
            # e_ab = u_ba - (Fh_a - 1) X_ba, e_ba = -u_ba + (Fh_b - 1) X_ba
            f = c * (Ma * (uba - pa) - Mb * (pb - uba))
            acc[a, i] += f / mass[a]
            if b < n_query:
                acc[b, i] -= f / mass[b]
