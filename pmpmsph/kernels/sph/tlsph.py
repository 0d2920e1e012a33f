"""Corrected-kernel SPH for solids after Shutov & Klyuchantsev (seed 004, eqs. 1-9).

Kernels over plain arrays, 1D/2D/3D (``dim``); positions ``(n, dim)``, tensors
``(n, 3, 3)`` (in 2D plane strain only the upper-left 2x2 block of L and of grad u is
filled, F[2, 2] = 1; in 1D uniaxial strain). Pairs come as CSR lists ``(start, index)`` from
`neighbour_lists(x, n_query, 2 h)`: pair ``k`` in row ``a`` is ``(a, b = index[k])``.

Notation and index conventions
------------------------------
For pair ``k = (a, b)`` `kernel_correction` stores

    wt[k]    = W~_b(x_a)                       (eq. 1: the kernel of particle b, corrected,
    gw[k, :] = grad_x W~_b(x) at x = x_a        evaluated at the point x_a)

where the correction factors alpha(x), beta(x) of eqs. 2-3 are sums over the particles
around the *evaluation point* x = x_a (its neighbour list), and the gradient is the full
analytic one: alpha(x) and beta(x) are differentiated too (not the "simplified" correction).
Call ``G_ab = gw[k]``. This is what eq. 4 of the seed differentiates: the evaluation point
x_a is moved, the particles stay. With this G:

* linear completeness: ``sum_b V_b W~_b(x) = 1`` and ``sum_b V_b x_b W~_b(x) = x`` for every
  x, hence ``sum_b V_b G_ab = 0`` and ``sum_b V_b x_b (x) G_ab = 1`` to round-off at every
  particle, boundary particles included (for any positive volumes V_b);
* eq. 6, velocity gradient: ``L_a = sum_b V_b v_b (x) G_ab`` -- exact for linear v;
* eq. 8, deformation gradient: ``F_a = 1 + sum_b V0_b (u_b - u_a) (x) G0_ab`` with G0 the
  gradient of the kernel corrected in the *reference* configuration (positions X0, volumes
  V0), computed once; exact for a homogeneous deformation;
* eq. 5, internal force density: ``T_a = -sum_b V_b sigma_b G_ba`` -- note the swapped pair:
  G_ba = gradient at x_b of the kernel of particle a (pair (b, a) in row b's list). The seed
  writes ``grad W~_ba = grad W~_b(x_a) != grad W~_ab`` in eq. 5 and ``grad W~_ab`` in eq. 6;
  read with the notation of eq. 4 (``grad W~_a(x_b)`` is the derivative with respect to x_a
  of ``W~(x_a - x_b)``, i.e. of the kernel of b at x_a), eq. 6 uses G_ab and eq. 5 uses G_ba.
  That reading is the one taken here, and it is also the only one of the candidate readings
  that is energy-consistent: eq. 5 is then exactly the adjoint of eq. 6,

      sum_a V_a v_a . T_a = - sum_b V_b sigma_b : L_b,

  the discrete form of ``int v . div sigma = - int sigma : grad v`` for a free surface. With
  ``V_b = J_b V0_b`` and F advanced by eq. 9 (``dF/dt = L F``) the rate of the stored energy
  ``sum_b V0_b dpsi_b/dt = sum_b V0_b J_b sigma_b : L_b`` cancels the power of the internal
  forces exactly, so the semi-discrete system conserves E = K + U (eq. 7) exactly, and the
  total momentum too (``sum_a V_a T_a = -sum_b V_b sigma_b sum_a V_a G_ba = 0`` by the
  partition of unity). With F from eq. 8 the stress power is only approximately that of eq. 6
  (the reference and current corrections differ), so energy is conserved to discretisation
  accuracy; that is the seed's main variant, and what scene 12 measures.
  The other reading, ``T_a = -sum_b V_b sigma_b G_ab``, is a collocation of div sigma that
  is neither momentum- nor energy-conserving and has the wrong sign (it approximates
  -div sigma). Our T_a approximates +div sigma (integration by parts of
  ``sum_b V_b sigma_b grad W~_a(x_b)``), so ``rho dv/dt = T_a`` (eq. 18) and a stretched body
  contracts; `internal_force` returns the particle force ``f_a = V_a T_a`` (~ V_a div sigma).
* With ``corrected=False`` G_ab is the plain kernel gradient ``W'(r) (x_a - x_b)/r`` and
  the same formulas are used (L and F are then not exact for linear fields; eq. 6 is kept in
  its literal ``v_b`` form so that the force stays its adjoint).

Stability of the seed's combination, and the total-Lagrangian alternative
------------------------------------------------------------------------
The seed corrects the kernel in the current configuration for eqs. 5-6 and in the reference
configuration for eq. 8. Measured on the plate of section 6.1 (tests/verification): that mix
is not energy-consistent, and a mode localised at the free edges grows exponentially until
the run blows up; the onset comes earlier as the particles get finer and as k_h gets smaller
(energy off by 1 %: 41 x 41 with k_h = 1.2 at t ~ 1.0 s, with k_h = 1.4 at t ~ 2.3 s; 81 x 81
with k_h = 1.3 / 1.4 at t ~ 0.8 / 1.0 s), independent of the time step. The consistent pairs
behave better: eq. 9 with eqs. 5-6 all in the current configuration (exactly conservative,
see above) stays bounded in energy, though at 81 x 81 with k_h = 1.2 its corner path departs
by ~0.02 from t ~ 0.8 s; eq. 8 with the total-Lagrangian force of Ganzenmueller et al. (the
seed's ref. [3]) is stable and converges at every resolution tried (81 x 81 to t = 1.2 s,
41 x 41 to t = 4 s).
That force is eq. 5 in the reference configuration with the first Piola-Kirchhoff stress,

    f_a = -V0_a sum_b V0_b P_b G0_ba,   P = J sigma F^-T   (`first_piola`),

which is `internal_force(start0, index0, gw0, vol0, P, dim, f)` and is exactly the adjoint
of eq. 8: ``sum_a v_a . f_a = -sum_a V0_a P_a : dF_a/dt`` (the ``-u_a`` term of eq. 8 drops
out since ``sum_b V0_b G0_ab = 0``), so eq. 8 with it conserves energy exactly.

The finite-difference gradient of eq. 4 that the tests check `kernel_correction` against is
tests/unit/tlsph_reference.py; `update_F_exp` is eq. 9 with a scaling-and-squaring Taylor
exponential (`expm3`); `energies` is eq. 7 with psi from the material dispatch (per unit
reference volume).
"""
import numpy as np

from ...jit import njit
from ...materials.dispatch import compute_stress_tagged, strain_energy_tagged
from ...materials.tensor import cofactor3, det3
from .kernel_functions import kernel_dwdr, kernel_w
from .liu import COEF, liu_gradient, liu_solve

__all__ = ["kernel_correction", "velocity_gradient", "deformation_gradient", "internal_force",
           "first_piola", "expm3", "update_F_exp", "material_stress", "current_volume", "energies"]



@njit(inline="always")
def _pair_kernel(x, a, b, dim, kind, h, r):
    """r = x_a - x_b (into `r`) and (W(|r|), W'(|r|)/|r|) of the plain kernel."""
    rn2 = 0.0
    for i in range(dim):
        r[i] = x[a, i] - x[b, i]
        rn2 += r[i] * r[i]
    rn = np.sqrt(rn2)
    w = kernel_w(kind, dim, rn, h)
    dw = kernel_dwdr(kind, dim, rn, h) / rn if rn > 0.0 else 0.0
    return w, dw


@njit
def kernel_correction(x, vol, start, index, h, kind, dim, corrected, wt, gw):
    """Corrected kernel W~_b(x_a) (seed 004, eqs. 1-3) and its analytic gradient.

    For every CSR pair k = (a, b = index[k]) of the rows a < len(start) - 1 writes
    ``wt[k] = W~_b(x_a)`` and ``gw[k, :dim] = grad_x W~_b(x)|_{x = x_a}`` with
    ``W~_b(x) = W_b(x) alpha(x) [1 + beta(x) . (x - x_b)]``, beta and alpha from eqs. 2-3
    summed over the list of row a with volumes ``vol`` (``W_b(x) = kernel_w(kind, dim,
    |x - x_b|, h)``). The gradient differentiates W_b, alpha and beta (full correction):
    with r_b = x - x_b, m0 = sum V W, m1 = sum V W r, M = sum V W r (x) r,

        beta = -M^-1 m1,  1/alpha = m0 + beta . m1,
        M d_j beta = -d_j m1 - (d_j M) beta,  d_j alpha = -alpha^2 d_j(m0 + beta . m1).

    ``corrected=False`` gives the plain kernel and its gradient W'(r) r_b / r. A row whose
    M is singular (all neighbours on a line/plane, see liu.DEGENERATE) falls back to the
    Shepard kernel W_b / m0 (exact for constants only); the number of such rows is returned.
    """
    n_rows = start.shape[0] - 1
    M = np.zeros((3, 3))
    m1 = np.zeros(3)
    g0 = np.zeros(3)
    D1 = np.zeros((3, 3))       # D1[i, j] = d m1_i / d x_j
    D2 = np.zeros((3, 3, 3))    # D2[i, k, j] = d M_ik / d x_j
    coef = np.zeros(COEF)       # the row's alpha, beta and their gradients (liu.py)
    r = np.zeros(3)
    gW = np.zeros(3)
    n_bad = 0
    for a in range(n_rows):
        k0 = start[a]
        k1 = start[a + 1]
        if not corrected:
            for k in range(k0, k1):
                b = index[k]
                w, dw = _pair_kernel(x, a, b, dim, kind, h, r)
                wt[k] = w
                for i in range(dim):
                    gw[k, i] = dw * r[i]
            continue
        m0 = 0.0
        for i in range(3):
            m1[i] = 0.0
            g0[i] = 0.0
            for j in range(3):
                M[i, j] = 0.0
                D1[i, j] = 0.0
                for l in range(3):
                    D2[i, j, l] = 0.0
        for k in range(k0, k1):
            b = index[k]
            Vb = vol[b]
            w, dw = _pair_kernel(x, a, b, dim, kind, h, r)
            w *= Vb
            dw *= Vb
            m0 += w
            for i in range(dim):
                gW[i] = dw * r[i]
                g0[i] += gW[i]
                m1[i] += w * r[i]
            for i in range(dim):
                for j in range(dim):
                    D1[i, j] += r[i] * gW[j]
                    M[i, j] += w * r[i] * r[j]
                    for l in range(dim):
                        D2[i, j, l] += r[i] * r[j] * gW[l]
        if not liu_solve(dim, m0, g0, m1, M, D1, D2, coef):
            n_bad += 1
        for k in range(k0, k1):
            w, dw = _pair_kernel(x, a, index[k], dim, kind, h, r)
            wt[k] = liu_gradient(dim, coef, r, w, dw, gW)
            for i in range(dim):
                gw[k, i] = gW[i]
    return n_bad


@njit
def velocity_gradient(rows, start, index, gw, vol, v, dim, L):
    """Eq. 6: ``L_a = sum_b V_b v_b (x) G_ab`` (L[a, i, j] = d v_i / d x_j) for the `rows` a
    (the rows of the stage's own materials; other rows are not written).

    ``gw``, ``vol`` of the current configuration; entries beyond dim are zero."""
    for a in rows:
        for i in range(3):
            for j in range(3):
                L[a, i, j] = 0.0
        for k in range(start[a], start[a + 1]):
            b = index[k]
            Vb = vol[b]
            for i in range(dim):
                vi = Vb * v[b, i]
                for j in range(dim):
                    L[a, i, j] += vi * gw[k, j]


@njit
def deformation_gradient(rows, start, index, gw0, vol0, x, X0, dim, F):
    """Eq. 8 (referential): ``F_a = 1 + sum_b V0_b (u_b - u_a) (x) G0_ab``, u = x - X0, for
    the `rows` a (other rows are not written).

    ``start``, ``index``, ``gw0`` are the pairs and corrected-kernel gradients of the
    reference configuration (X0, V0), computed once. Components beyond dim stay identity."""
    for a in rows:
        for i in range(3):
            for j in range(3):
                F[a, i, j] = 1.0 if i == j else 0.0
        for k in range(start[a], start[a + 1]):
            b = index[k]
            Vb = vol0[b]
            for i in range(dim):
                du = Vb * ((x[b, i] - X0[b, i]) - (x[a, i] - X0[a, i]))
                for j in range(dim):
                    F[a, i, j] += du * gw0[k, j]


@njit
def volumes_from_F(rows, F, vol0, mass, J, vol, rho):
    """J = det F, the current volume V = J V0 and density m / V of the `rows` (one pass;
    numpy's batched determinant took 14 % of a plate-under-water step)."""
    for a in rows:
        Ja = det3(F[a])
        J[a] = Ja
        vol[a] = Ja * vol0[a]
        rho[a] = mass[a] / vol[a]


@njit
def internal_force(start, index, gw, vol, sigma, dim, f):
    """Eq. 5: particle force ``f_a = V_a T_a`` with ``T_a = -sum_b V_b sigma_b G_ba``.

    G_ba (gradient at x_b of the kernel of a) is the pair (b, a) of row b, so the sum is a
    scatter over the rows b: every row must be listed (serially: all particles). T_a
    approximates div sigma; f_a approximates V_a div sigma, and ``sum_a f_a = 0``."""
    n = f.shape[0]
    for a in range(n):
        for i in range(dim):
            f[a, i] = 0.0
    for b in range(start.shape[0] - 1):
        Vb = vol[b]
        for k in range(start[b], start[b + 1]):
            a = index[k]
            c = -Vb * vol[a]
            for i in range(dim):
                s = 0.0
                for j in range(dim):
                    s += sigma[b, i, j] * gw[k, j]
                f[a, i] += c * s


@njit
def first_piola(rows, F, sigma, P):
    """``P_a = J_a sigma_a F_a^-T`` (first Piola-Kirchhoff stress) of the `rows`, for the
    total-Lagrangian form of eq. 5 with reference-configuration pairs (see the module
    docstring)."""
    for a in rows:
        # J F^-T is the cofactor matrix of F
        c00, c01, c02, c10, c11, c12, c20, c21, c22 = cofactor3(F[a])
        for i in range(3):
            s0 = sigma[a, i, 0]
            s1 = sigma[a, i, 1]
            s2 = sigma[a, i, 2]
            P[a, i, 0] = s0 * c00 + s1 * c10 + s2 * c20
            P[a, i, 1] = s0 * c01 + s1 * c11 + s2 * c21
            P[a, i, 2] = s0 * c02 + s1 * c12 + s2 * c22


@njit
def expm3(A, out):
    """exp(A) of a 3x3 matrix into out: scaling and squaring with a degree-12 Taylor
    polynomial (scaled norm <= 1/4, truncation < 1e-17 relative), for eq. 9."""
    nrm = 0.0
    for i in range(3):
        s = 0.0
        for j in range(3):
            s += abs(A[i, j])
        nrm = max(nrm, s)
    sq = 0
    scale = 1.0
    while nrm * scale > 0.25:
        scale *= 0.5
        sq += 1
    B = np.empty((3, 3))
    P = np.empty((3, 3))
    T = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            B[i, j] = A[i, j] * scale
            P[i, j] = 1.0 if i == j else 0.0
    # Horner: P = I + B/1 (I + B/2 (I + ... (I + B/12)))
    for m in range(12, 0, -1):
        for i in range(3):
            for j in range(3):
                s = 0.0
                for l in range(3):
                    s += B[i, l] * P[l, j]
                T[i, j] = s / m
        for i in range(3):
            for j in range(3):
                P[i, j] = T[i, j] + (1.0 if i == j else 0.0)
    for _ in range(sq):
        for i in range(3):
            for j in range(3):
                s = 0.0
                for l in range(3):
                    s += P[i, l] * P[l, j]
                T[i, j] = s
        for i in range(3):
            for j in range(3):
                P[i, j] = T[i, j]
    for i in range(3):
        for j in range(3):
            out[i, j] = P[i, j]


@njit
def update_F_exp(L, F, dt, Fout):
    """Eq. 9: ``Fout_a = exp(dt L_a) F_a`` for every particle (Fout may not alias F)."""
    A = np.empty((3, 3))
    E = np.empty((3, 3))
    for a in range(F.shape[0]):
        for i in range(3):
            for j in range(3):
                A[i, j] = dt * L[a, i, j]
        expm3(A, E)
        for i in range(3):
            for j in range(3):
                s = 0.0
                for l in range(3):
                    s += E[i, l] * F[a, l, j]
                Fout[a, i, j] = s


@njit
def material_stress(mtype, F, L, dt, state, par, sigma, mtag):
    """Cauchy stress of every particle (eqs. 11 / 14-17 via the material dispatch); a
    Maxwell state is advanced by eq. 16 over dt in place (pass a copy for trial stages).
    `mtag`: `material_tag((mtype,))`, so that only this model's law is compiled."""
    for a in range(F.shape[0]):
        compute_stress_tagged(mtag, mtype, F[a], L[a], dt, state[a], par, sigma[a])


@njit
def current_volume(F, vol0, vol):
    """``V_a = J_a V0_a`` with J = det F (the volumes of eqs. 5-6 in the current state)."""
    for a in range(F.shape[0]):
        vol[a] = det3(F[a]) * vol0[a]


@njit
def energies(mass, v, vol0, F, mtype, state, par, dim, mtag):
    """Eq. 7: ``K = 1/2 sum m_b |v_b|^2`` and ``U = sum V0_b psi(F_b)`` (psi per unit
    reference volume, eq. 12); returns (K, U). `mtag` as in `material_stress`."""
    K = 0.0
    U = 0.0
    for b in range(mass.shape[0]):
        s = 0.0
        for i in range(dim):
            s += v[b, i] * v[b, i]
        K += 0.5 * mass[b] * s
        U += vol0[b] * strain_energy_tagged(mtag, mtype, F[b], state[b], par)
    return K, U
