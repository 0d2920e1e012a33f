"""The hourglass control of `kernels.sph.hourglass` with a quadratic fit
(`[sph] hourglass_fit = "quadratic"`).

The linear control penalises e_ab = u_ba - (Fh_a - 1) X_ba, the distance of b from where a's
fitted linear field puts it. In bending the displacement is quadratic, the residual of a
linear fit is of the order of the curvature times the spacing squared, and the control
resists bending itself: an updated-Lagrangian plate 2 particles thick, clamped at both ends,
sagged 2.83 mm under its own weight with no control and 0.73 mm with kappa = 2
(docs/plate.md; a linear fit over a few rows also reads the rows' mean bending strain, as
Bonet and Lok's gradient does). Here each row a fits a quadratic field instead,

    u_b - u_a = Q_a P(X_ba),   P(X) = (X/h, (X_i/h)^2/2, X_i X_j/h^2 for i < j),

5 coefficients a component in 2D, 9 in 3D, by the same weighted least squares (weights
V_b phi(|X_ba|)), and the residual e_ab = u_ba - Q_a P(X_ba) takes the place of the linear
one in the energy U_hg = kappa/2 sum_a V_a M_a sum_b V_b phi_ab |e_ab|^2. Every quadratic
field is fitted exactly, so bending costs nothing, while the odd-even mode, which no smooth
field fits, is resisted as before. Q_a minimises a's own residuals, so the force is still
exactly -dU_hg/dx (envelope theorem),

    f_a = kappa V_a V_b phi_ab (M_a e_ab - M_b e_ba) = -f_b,   e_ba = u_ab - Q_b P(X_ab),

conservative and momentum-conserving. A row whose neighbours do not determine a quadratic
(two particle layers: X_y^2 and X_y are proportional over them) takes the least-norm
minimiser (the moment matrix's pseudo-inverse), which is still a minimiser, so the force
stays the energy's gradient. The moment matrix depends on the reference positions and the
volumes only. Measured (docs/plate.md): the same plate with kappa = 2 sags 2.63 mm, and under
SPH water with mirror clamps it stays sound where without a control its columns pair up.
"""
from typing import Callable, NamedTuple

import numpy as np

from ...codes import SPH
from ...jit import njit
from .hourglass import control_pairs, hourglass_fit, hourglass_forces

#: coefficients of the quadratic fit a component (3D; 2D uses the first 5)
QUADRATIC_TERMS = 9
#: eigenvalues of the moment matrix below this fraction of its largest are left out
PSEUDO_INVERSE_RCOND = 1e-8


@njit(inline="always")
def quadratic_basis(dim, h, d, sign, P):
    """P(sign * d) (module docstring) into P; d = X_b - X_a."""
    k = 0
    for i in range(dim):
        P[k] = sign * d[i] / h
        k += 1
    for i in range(dim):
        P[k] = 0.5 * (d[i] / h) ** 2
        k += 1
    for i in range(dim):
        for j in range(i + 1, dim):
            P[k] = d[i] * d[j] / (h * h)
            k += 1


@njit
def quadratic_pairs(dim, kern, h, n_query, X0, method, mat, fluid, start, index):
    """The pairs of the control (`kernels.sph.hourglass.control_pairs`) with their bases:
    (a, b) rows, phi_ab, P(X_ba) and P(X_ab)."""
    rows, phi = control_pairs(dim, kern, h, n_query, X0, method, mat, fluid, start, index)
    nb = dim + dim * (dim + 1) // 2
    P = np.empty((len(phi), nb))
    Pb = np.empty((len(phi), nb))
    d = np.zeros(3)
    for m in range(len(phi)):
        for i in range(dim):
            d[i] = X0[rows[m, 1], i] - X0[rows[m, 0], i]
        quadratic_basis(dim, h, d, 1.0, P[m])
        quadratic_basis(dim, h, d, -1.0, Pb[m])
    return rows, phi, P, Pb


@njit
def symmetric_pseudo_inverse(A, n, Ainv, work, vectors):
    """Moore-Penrose inverse of the leading n x n block of the symmetric A into Ainv, by
    cyclic Jacobi rotations (eigenvalues below PSEUDO_INVERSE_RCOND of the largest in
    magnitude are dropped); `work`, `vectors`: n x n scratch."""
    for i in range(n):
        for j in range(n):
            work[i, j] = A[i, j]
            vectors[i, j] = 1.0 if i == j else 0.0
    for _ in range(60):
        off = 0.0
        for p in range(n):
            for q in range(p + 1, n):
                off += work[p, q] * work[p, q]
        if off < 1e-30:
            break
        for p in range(n):
            for q in range(p + 1, n):
                if work[p, q] == 0.0:
                    continue
                theta = (work[q, q] - work[p, p]) / (2.0 * work[p, q])
                t = (1.0 if theta >= 0.0 else -1.0) / (abs(theta) + np.sqrt(theta * theta + 1.0))
                c = 1.0 / np.sqrt(t * t + 1.0)
                s = t * c
                for k in range(n):
                    wkp, wkq = work[k, p], work[k, q]
                    work[k, p] = c * wkp - s * wkq
                    work[k, q] = s * wkp + c * wkq
                for k in range(n):
                    wpk, wqk = work[p, k], work[q, k]
                    work[p, k] = c * wpk - s * wqk
                    work[q, k] = s * wpk + c * wqk
                for k in range(n):
                    vkp, vkq = vectors[k, p], vectors[k, q]
                    vectors[k, p] = c * vkp - s * vkq
                    vectors[k, q] = s * vkp + c * vkq
    largest = 0.0
    for k in range(n):
        largest = max(largest, abs(work[k, k]))
    for i in range(n):
        for j in range(n):
            Ainv[i, j] = 0.0
    for k in range(n):
        e = work[k, k]
        if abs(e) > PSEUDO_INVERSE_RCOND * largest:
            for i in range(n):
                for j in range(n):
                    Ainv[i, j] += vectors[i, k] * vectors[j, k] / e


@njit
def quadratic_fit(smoothing, pairs, control, u, X0, mass, rho, method, mat, fluid, A, Q):
    """Q_a (module docstring) of the owned SPH rows [0, n_query) of a solid, over the SPH
    neighbours of a's material, the pairs `control` of `quadratic_pairs`; A: moment-matrix
    scratch (>= n_query rows of 9 x 9). As `kernels.sph.hourglass.hourglass_fit`."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
    dim = len(dim_tag)
    nb = dim + dim * (dim + 1) // 2
    rows, phi, P, Pb = control
    for a in range(n_query):
        A[a] = 0.0
        Q[a] = 0.0
    for m in range(len(phi)):
        a, b = rows[m, 0], rows[m, 1]
        wa = mass[b] / rho[b] * phi[m]
        wb = mass[a] / rho[a] * phi[m] if b < n_query else 0.0
        for s in range(nb):
            for t in range(nb):
                A[a, s, t] += wa * P[m, s] * P[m, t]
                if wb != 0.0:
                    A[b, s, t] += wb * Pb[m, s] * Pb[m, t]
        for i in range(dim):  # the right-hand sides in Q until the solve
            uba = u[b, i] - u[a, i]
            for s in range(nb):
                Q[a, i, s] += wa * uba * P[m, s]
                if wb != 0.0:
                    Q[b, i, s] -= wb * uba * Pb[m, s]
    Ainv = np.zeros((nb, nb))
    work = np.zeros((nb, nb))
    vectors = np.zeros((nb, nb))
    rhs = np.zeros(nb)
    for a in range(n_query):
        if method[a] != SPH or fluid[mat[a]]:
            continue
        symmetric_pseudo_inverse(A[a], nb, Ainv, work, vectors)
        for i in range(dim):
            for s in range(nb):
                rhs[s] = Q[a, i, s]
            for s in range(nb):
                acc = 0.0
                for t in range(nb):
                    acc += Ainv[s, t] * rhs[t]
                Q[a, i, s] = acc


@njit
def quadratic_forces(smoothing, pairs, control, u, X0, Q, mass, rho, cs, kappa, acc):
    """Adds the quadratic-fit hourglass control (module docstring) to acc of the owned SPH
    rows [0, n_query), over the pairs `control` of `quadratic_pairs` (a halo row b takes no
    force here, its owner adds it): pairs of two SPH rows of one solid material (Q
    refreshed in the halo)."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
    dim = len(dim_tag)
    nb = dim + dim * (dim + 1) // 2
    rows, phi, P, Pb = control
    for m in range(len(phi)):
        a, b = rows[m, 0], rows[m, 1]
        Ma = rho[a] * cs[a] * cs[a]
        Mb = rho[b] * cs[b] * cs[b]
        c = kappa * mass[a] / rho[a] * mass[b] / rho[b] * phi[m]
        for i in range(dim):
            uba = u[b, i] - u[a, i]
            fit_a = 0.0
            fit_b = 0.0
            for s in range(nb):
                fit_a += Q[a, i, s] * P[m, s]
                fit_b += Q[b, i, s] * Pb[m, s]
            f = c * (Ma * (uba - fit_a) - Mb * (-uba - fit_b))
            acc[a, i] += f / mass[a]
            if b < n_query:
                acc[b, i] -= f / mass[b]

class HourglassFit(NamedTuple):
    """One `[sph] hourglass_fit`: its pair list (made once per neighbour list: it depends on
    the reference positions only), fit and force kernels, the shape of a row of its fitted
    coefficients (the field Fh) and of its moment-matrix scratch."""
    pairs: Callable
    fit: Callable
    forces: Callable
    coefficients: tuple
    scratch: tuple


#: `[sph] hourglass_fit`: name -> HourglassFit
HOURGLASS_FITS = {"linear": HourglassFit(control_pairs, hourglass_fit, hourglass_forces,
                                         (3, 3), (3, 3)),
                  "quadratic": HourglassFit(quadratic_pairs, quadratic_fit, quadratic_forces,
                                            (3, QUADRATIC_TERMS),
                                            (QUADRATIC_TERMS, QUADRATIC_TERMS))}
