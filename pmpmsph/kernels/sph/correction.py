"""Kernel gradient correction of updated-Lagrangian SPH (`[sph] correction = true`): the
matrices B_a = (M_a^T)^-1 that `kernels.sph.rates.sph_rates` applies to the kernel gradient
(Bonet & Lok 1999; seed 004 §2.1 for the first-order completeness it restores).
"""
import numpy as np

from ...jit import njit
from ...materials.tensor import cofactor3
from ...codes import SPH, WALL
from .kernel_functions import pair_gradient


@njit(inline="always")
def _invert_transpose_block(dim, M, a, out):
    """out[a] <- (M_a^T)^-1 on the leading dim x dim block (identity elsewhere); returns
    det M_a (the block's)."""
    for i in range(3):
        for j in range(3):
            out[a, i, j] = 1.0 if i == j else 0.0
    if dim == 1:
        d = M[a, 0, 0]
        if d != 0.0:
            out[a, 0, 0] = 1.0 / d
        return d
    if dim == 2:
        m00, m01, m10, m11 = M[a, 0, 0], M[a, 0, 1], M[a, 1, 0], M[a, 1, 1]
        d = m00 * m11 - m01 * m10
        if d != 0.0:
            # inverse of the transpose [[m00, m10], [m01, m11]]
            out[a, 0, 0] = m11 / d
            out[a, 0, 1] = -m10 / d
            out[a, 1, 0] = -m01 / d
            out[a, 1, 1] = m00 / d
        return d
    # 3D: (M^T)^-1 = cof(M) / det M
    cof = cofactor3(M[a])
    d = M[a, 0, 0] * cof[0] + M[a, 0, 1] * cof[1] + M[a, 0, 2] * cof[2]
    if d != 0.0:
        for k in range(9):
            out[a, k // 3, k % 3] = cof[k] / d
    return d


#: a row whose moment matrix has det M below this keeps the plain gradient (B = I): a
#: particle with (nearly) collinear or no neighbours, whose M cannot be inverted safely
CORRECTION_MIN_DET = 1e-2


@njit
def correction_matrices(dim_tag, kern_tag, h, n_query, x, mass, rho, method, start, index,
                        M, B):
    """Kernel gradient correction of Bonet & Lok (1999) / Randles & Libersky (1996) for the
    owned rows [0, n_query), over half neighbour lists (each pair once, both ends):

        M_a = 1/rho_a sum_b m_b (x_b - x_a) (x) grad_a W_ab,   B_a = (M_a^T)^-1,

    so that the corrected gradient B_a grad_a W_ab makes the velocity gradient
    1/rho_a sum_b m_b (v_b - v_a) (x) B_a grad_a W_ab exact for every linear v, at a free
    surface too (M_a = I in the interior of a regular lattice up to the lattice error of the
    kernel). It is the first-order completeness that seed 004 builds into its corrected
    kernel (eqs. 1-3, here the gradient-only form: W itself is not corrected, the density
    comes from continuity). The weights m_b/rho_a are those of the velocity gradient of
    `sph_rates`, so that the two agree for any density field. Dummy wall rows and rows with
    det M < CORRECTION_MIN_DET keep B = I. M is symmetric (the kernel gradient lies along
    x_a - x_b), hence so is B.

    Only the rows whose B the rates use are computed: SPH rows and the rows listed with
    one (in a coupled scene, the MPM points around the SPH region); the others keep B = I.
    `M` is scratch of shape (>= n_query, 3, 3)."""
    dim = len(dim_tag)
    kern = len(kern_tag) - 1
    need = np.zeros(n_query, np.bool_)
    for a in range(n_query):
        for i in range(3):
            for j in range(3):
                M[a, i, j] = 0.0
        if method[a] == SPH:
            need[a] = True
            for k in range(start[a], start[a + 1]):
                b = index[k]
                if b < n_query:
                    need[b] = True
        else:
            for k in range(start[a], start[a + 1]):
                if method[index[k]] == SPH:
                    need[a] = True
                    break
    for a in range(n_query):
        for k in range(start[a], start[a + 1]):
            b = index[k]
            need_b = b < n_query and need[b]
            if not (need[a] or need_b):
                continue
            xab0, xab1, xab2, fr = pair_gradient(kern, dim, x, a, b, h)
            if fr == 0.0:
                continue
            # (x_b - x_a) (x) grad_a W_ab = -fr xab (x) xab: the same for both ends
            wa = -mass[b] / rho[a] * fr
            wb = -mass[a] / rho[b] * fr if need_b else 0.0
            for i in range(dim):
                xi = xab0 if i == 0 else (xab1 if i == 1 else xab2)
                for j in range(dim):
                    xj = xab0 if j == 0 else (xab1 if j == 1 else xab2)
                    M[a, i, j] += wa * xi * xj
                    if need_b:
                        M[b, i, j] += wb * xi * xj
    for a in range(n_query):
        d = _invert_transpose_block(dim, M, a, B)
        if method[a] == WALL or not need[a] or not d > CORRECTION_MIN_DET:
            for i in range(3):
                for j in range(3):
                    B[a, i, j] = 1.0 if i == j else 0.0
