"""Time-integration kernels of the SPH stages (DESIGN.md §3, step 4): the stage update
shared by Euler, predictor-corrector and TVD-RK3 (`advance`), the velocity-Verlet pieces
(`add_scaled` for the kick and the drift, `cayley_update`), and the per-step checks
(`max_signal`, `first_outside`). Only owned SPH rows move: walls and MPM points are left alone.
"""
import numpy as np

from ...codes import SPH
from ...jit import njit


@njit
def advance(dim_tag, n, method, step_start, state, rates, c0, c1, dtc, save, with_F):
    """y <- c0 y0 + c1 y + dtc f(y) for y = (x, v, log rho, F), f = (v, acc, drho/rho, L F),
    y0 and y the `sph_state` bundles `step_start` and `state`, f from `rates`
    (kernels/sph/views.py), on owned SPH rows (walls stay put). One formula covers Euler,
    predictor-corrector and TVD-RK3 stages. Positions move with the velocity at the start
    of the stage. With `save` the current y is first copied to y0 (the step start) in the
    same pass; without `with_F` F is left alone (fluids: F follows from the density)."""
    x0, v0, r0, F0 = step_start
    x, v, rho, F = state
    acc, drho, L, _, _ = rates
    dim = len(dim_tag)
    LF = np.zeros((3, 3))
    for a in range(n):
        if method[a] != SPH:
            continue
        if save:
            for d in range(dim):
                x0[a, d] = x[a, d]
                v0[a, d] = v[a, d]
            r0[a] = rho[a]
            if with_F:
                for i in range(3):
                    for j in range(3):
                        F0[a, i, j] = F[a, i, j]
        for d in range(dim):
            xn = c0 * x0[a, d] + c1 * x[a, d] + dtc * v[a, d]
            v[a, d] = c0 * v0[a, d] + c1 * v[a, d] + dtc * acc[a, d]
            x[a, d] = xn
        # the same stage combination of log rho, whose rate is drho/rho = -div v (seed 000
        # eq. 2.5 over rho): to first order the linear update, but positive whatever the step
        # (a splashing particle whose neighbours fly apart cannot reach rho <= 0)
        lr = c1 * np.log(rho[a]) + dtc * drho[a] / rho[a]
        if c0 != 0.0:
            lr += c0 * np.log(r0[a])
        rho[a] = np.exp(lr)
        if not with_F:
            continue
        for i in range(dim):
            for j in range(dim):
                s = 0.0
                for k in range(dim):
                    s += L[a, i, k] * F[a, k, j]
                LF[i, j] = s
        for i in range(dim):
            for j in range(dim):
                F[a, i, j] = c0 * F0[a, i, j] + c1 * F[a, i, j] + dtc * LF[i, j]


@njit
def add_scaled(dim_tag, n, method, c, y, f):
    """y += c f on owned SPH rows: Verlet's kick (v += dt/2 acc) and drift (x += dt v)."""
    dim = len(dim_tag)
    for a in range(n):
        if method[a] == SPH:
            for d in range(dim):
                y[a, d] += c * f[a, d]


@njit
def cayley_update(dim_tag, n, method, dt, rho, F, drho, L):
    """rho <- rho + dt drho and F <- (I - dt/2 L')^-1 (I + dt/2 L') F with drho and L taken
    at the mid-step positions and half-step velocities, L' = L rho/rho_mid (L was computed
    with 1/rho at the step start; rho_mid = rho + dt/2 drho): the implicit midpoint rule
    for dF/dt = L F. Every input is symmetric in the step's two ends, so reversing the
    velocities retraces the step exactly and the Verlet step stays time-reversible."""
    dim = len(dim_tag)
    A = np.zeros((3, 3))
    B = np.zeros((3, 3))
    inv = np.zeros((3, 3))
    for a in range(n):
        if method[a] != SPH:
            continue
        scale = rho[a] / (rho[a] + 0.5 * dt * drho[a])
        rho[a] += dt * drho[a]
        for i in range(3):
            for j in range(3):
                e = 1.0 if i == j else 0.0
                l = 0.5 * dt * scale * L[a, i, j] if (i < dim and j < dim) else 0.0
                A[i, j] = e - l
                B[i, j] = e + l
        # A^-1 by cofactors (A is near the identity)
        c00 = A[1, 1] * A[2, 2] - A[1, 2] * A[2, 1]
        c01 = A[1, 2] * A[2, 0] - A[1, 0] * A[2, 2]
        c02 = A[1, 0] * A[2, 1] - A[1, 1] * A[2, 0]
        det = A[0, 0] * c00 + A[0, 1] * c01 + A[0, 2] * c02
        inv[0, 0] = c00 / det
        inv[1, 0] = c01 / det
        inv[2, 0] = c02 / det
        inv[0, 1] = (A[0, 2] * A[2, 1] - A[0, 1] * A[2, 2]) / det
        inv[1, 1] = (A[0, 0] * A[2, 2] - A[0, 2] * A[2, 0]) / det
        inv[2, 1] = (A[0, 1] * A[2, 0] - A[0, 0] * A[2, 1]) / det
        inv[0, 2] = (A[0, 1] * A[1, 2] - A[0, 2] * A[1, 1]) / det
        inv[1, 2] = (A[0, 2] * A[1, 0] - A[0, 0] * A[1, 2]) / det
        inv[2, 2] = (A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]) / det
        for i in range(dim):       # M = A^-1 B (in A)
            for j in range(dim):
                acc_ = 0.0
                for k in range(dim):
                    acc_ += inv[i, k] * B[k, j]
                A[i, j] = acc_
        for j in range(dim):       # F <- M F, column by column (B as scratch)
            for i in range(dim):
                acc_ = 0.0
                for k in range(dim):
                    acc_ += A[i, k] * F[a, k, j]
                B[i, 0] = acc_
            for i in range(dim):
                F[a, i, j] = B[i, 0]


@njit
def max_signal(dim_tag, n, cs, v):
    """max over rows [0, n) of c + |v| (the CFL signal speed from the evaluation's c)."""
    dim = len(dim_tag)
    m = 0.0
    for a in range(n):
        s = 0.0
        for d in range(dim):
            s += v[a, d] * v[a, d]
        c = cs[a] + np.sqrt(s)
        if not c <= m:  # NaN propagates
            m = c
    return m


@njit
def first_outside(dim, n, x, lo, hi):
    """First owned row outside the box [lo, hi] or with a NaN position; -1 if none."""
    for a in range(n):
        for d in range(dim):
            if not (x[a, d] >= lo[d] and x[a, d] <= hi[d]):
                return a
    return -1
