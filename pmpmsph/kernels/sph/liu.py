"""Liu's corrected kernel (seed 004, eqs. 1-3), split into the per-row coefficients and the
per-pair gradient, so that a pair loop over half neighbour lists can form the corrected
gradients of both ends from the rows' coefficients (`[sph] correction = "liu"` of the
updated formulation) as the total formulation forms them from full lists
(`tlsph.kernel_correction`).

    W~_b(x) = W_b(x) alpha(x) [1 + beta(x) . (x - x_b)],   W_b(x) = W(|x - x_b|),

with, over the neighbours b of the evaluation point x (r_b = x - x_b), m0 = sum V W,
m1 = sum V W r, M = sum V W r (x) r: beta = -M^-1 m1 and 1 / alpha = m0 + beta . m1. The
gradient at x = x_a differentiates W_b, alpha and beta (the full correction):

    G_ab = grad W~_b(x_a) = alpha c grad W_b + W_b c grad alpha + W_b alpha (beta + dbeta^T r),

c = 1 + beta . r, r = x_a - x_b, with M dbeta[:, j] = -d_j m1 - (d_j M) beta and
d_j alpha = -alpha^2 d_j (m0 + beta . m1). A row whose M is singular (DEGENERATE: its
neighbours on a line or plane) takes Shepard's kernel W_b / m0 (beta = 0), exact for
constants only.

A row's coefficients (`COEF` values): [0] 1 where set (0: none, the plain gradient),
[1] alpha, [2:5] grad alpha, [5:8] beta, [8:17] dbeta (row-major, dbeta[i, j] = d beta_i /
d x_j).
"""
import numpy as np

from ...jit import njit
from ...materials.tensor import block_inverse
from .kernel_functions import kernel_dwdr, kernel_w

#: values per row of the coefficients
COEF = 17
#: M (eq. 2) is treated as singular when det(M) < DEGENERATE * (tr M / dim)^dim
DEGENERATE = 1e-10


@njit
def liu_solve(dim, m0, g0, m1, M, D1, D2, coef):
    """The coefficients (module docstring) from a row's sums: m0, g0 = sum V grad W, m1, M,
    D1[i, j] = sum V r_i (grad W)_j and D2[i, k, j] = sum V r_i r_k (grad W)_j (the
    kernel-gradient parts of d m1 / dx and d M / dx; the W-derivative parts are added
    here). Writes coef[:COEF]; returns False where the Shepard fallback was taken."""
    for i in range(COEF):
        coef[i] = 0.0
    coef[0] = 1.0
    for i in range(dim):
        D1[i, i] += m0
        for k in range(dim):
            D2[i, k, i] += m1[k]
            D2[i, k, k] += m1[i]
    tr = 0.0
    for i in range(dim):
        tr += M[i, i] / dim
    Minv = np.zeros((3, 3))
    det = block_inverse(M, dim, Minv)
    if not (det > DEGENERATE * tr ** dim) or not (m0 > 0.0):
        if m0 > 0.0:
            coef[1] = 1.0 / m0
            for j in range(dim):
                coef[2 + j] = -g0[j] / (m0 * m0)
        return False
    beta = np.zeros(3)
    for i in range(dim):
        s = 0.0
        for j in range(dim):
            s -= Minv[i, j] * m1[j]
        beta[i] = s
    A = m0
    for i in range(dim):
        A += beta[i] * m1[i]
    alpha = 1.0 / A
    rhs = np.zeros(3)
    for j in range(dim):
        for i in range(dim):  # M dbeta[:, j] = -D1[:, j] - D2[:, :, j] beta
            s = -D1[i, j]
            for k in range(dim):
                s -= D2[i, k, j] * beta[k]
            rhs[i] = s
        dA = g0[j]
        for i in range(dim):
            s = 0.0
            for k in range(dim):
                s += Minv[i, k] * rhs[k]
            coef[8 + 3 * i + j] = s
            dA += s * m1[i] + beta[i] * D1[i, j]
        coef[2 + j] = -alpha * alpha * dA
    coef[1] = alpha
    for i in range(dim):
        coef[5 + i] = beta[i]
    return True


@njit(inline="always")
def liu_gradient(dim, coef, r, w, dw, out):
    """out[:dim] = G_ab, the corrected gradient of the pair with r = x_a - x_b, W = w and
    W'(|r|) / |r| = dw, from row a's coefficients `coef`; returns W~_b(x_a)."""
    c = 1.0
    for i in range(dim):
        c += coef[5 + i] * r[i]
    alpha = coef[1]
    for j in range(dim):
        s = coef[5 + j]
        for i in range(dim):
            s += coef[8 + 3 * i + j] * r[i]
        out[j] = coef[2 + j] * w * c + alpha * dw * r[j] * c + alpha * w * s
    return alpha * w * c


@njit
def liu_coefficients(smoothing, pairs, x, mass, rho, method, mat, need, sums, coef):
    """The coefficients of the rows [0, n_query) with need[a], over half neighbour lists
    (each pair once, both ends) of the same material, with the row itself (W(0)); volumes
    m / rho. `sums` is scratch (>= n_query rows of 52). Rows without need get coef[a, 0] = 0.
    Returns the number of rows that took the Shepard fallback."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
    dim = len(dim_tag)
    kern = len(kern_tag) - 1
    w0 = kernel_w(kern, dim, 0.0, h)
    for a in range(n_query):
        for k in range(52):
            sums[a, k] = 0.0
        sums[a, 0] = mass[a] / rho[a] * w0  # the row itself: W(0), no gradient
    r = np.zeros(3)
    for a in range(n_query):
        for k in range(start[a], start[a + 1]):
            b = index[k]
            if mat[b] != mat[a]:
                continue
            to_a = need[a]
            to_b = b < n_query and need[b]
            if not (to_a or to_b):
                continue
            r2 = 0.0
            for i in range(dim):
                r[i] = x[a, i] - x[b, i]
                r2 += r[i] * r[i]
            if r2 >= 4.0 * h * h or r2 == 0.0:
                continue
            rn = np.sqrt(r2)
            w = kernel_w(kern, dim, rn, h)
            dw = kernel_dwdr(kern, dim, rn, h) / rn
            for end in range(2):
                if end == 0:
                    if not to_a:
                        continue
                    row, V, sgn = a, mass[b] / rho[b], 1.0
                else:
                    if not to_b:
                        continue
                    row, V, sgn = b, mass[a] / rho[a], -1.0
                s = sums[row]
                s[0] += V * w
                for i in range(dim):
                    gi = sgn * dw * r[i]           # grad W at this end (r flips with it)
                    s[1 + i] += V * gi
                    s[4 + i] += V * w * sgn * r[i]
                    for j in range(dim):
                        gj = sgn * dw * r[j]
                        s[7 + 3 * i + j] += V * w * r[i] * r[j]
                        s[16 + 3 * i + j] += V * sgn * r[i] * gj
                        for k in range(dim):
                            gk = sgn * dw * r[k]
                            s[25 + 9 * i + 3 * j + k] += V * r[i] * r[j] * gk
    n_bad = 0
    g0 = np.zeros(3)
    m1 = np.zeros(3)
    M = np.zeros((3, 3))
    D1 = np.zeros((3, 3))
    D2 = np.zeros((3, 3, 3))
    for a in range(n_query):
        if not need[a]:
            for k in range(COEF):
                coef[a, k] = 0.0
            continue
        s = sums[a]
        for i in range(3):
            g0[i] = s[1 + i]
            m1[i] = s[4 + i]
            for j in range(3):
                M[i, j] = s[7 + 3 * i + j]
                D1[i, j] = s[16 + 3 * i + j]
                for k in range(3):
                    D2[i, j, k] = s[25 + 9 * i + 3 * j + k]
        if not liu_solve(dim, s[0], g0, m1, M, D1, D2, coef[a]):
            n_bad += 1
    return n_bad
