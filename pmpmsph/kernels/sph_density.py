"""delta-SPH density diffusion of weakly compressible fluids (Antuono et al. 2010): the
renormalised density gradient that its diffusion term needs (`density_gradient`); the term
itself is summed in `kernels.sph.sph_rates` with the continuity equation.

Antuono, Colagrossi, Marrone & Molteni (2010), Comput. Phys. Commun. 181, eqs. (4)-(6):

    drho_a/dt += delta h c0 sum_b psi_ab . grad_a W_ab V_b,
    psi_ab = 2 (rho_b - rho_a) (x_b - x_a) / |x_ab|^2 - (<grad rho>_a + <grad rho>_b),
    <grad rho>_a = (M_a^T)^-1 sum_b (rho_b - rho_a) grad_a W_ab V_b,
    M_a = sum_b (x_b - x_a) (x) grad_a W_ab V_b,

with V_b = m_b / rho_b. The first part of psi alone is the diffusion of Molteni & Colagrossi
(2009): in a fluid at rest under gravity it does not vanish (rho grows with depth, and a
Laplacian of a field that is not linear in a truncated support is not zero), so it drives a
slow flow towards the free surface; the renormalised gradients make psi vanish to second
order for a linear density field, so the hydrostatic state stays at rest.
"""
import numpy as np

from ..jit import njit
from .sph import SPH
from .sph_kernels import pair_gradient

#: a row whose moment matrix has det M below this keeps the plain sum for its gradient: a
#: particle with few or collinear neighbours (a splash), whose M cannot be inverted safely;
#: at a plane free surface det M is about 1/2
DIFFUSION_MIN_DET = 0.1


@njit
def density_gradient(dim_tag, kern_tag, h, n_query, x, mass, rho, method, mat, dcoef, start,
                     index, M, grad):
    """<grad rho>_a of the owned rows [0, n_query) that diffuse (SPH rows of a material with
    dcoef[mat] > 0), over half neighbour lists (each pair once, both ends), from the SPH
    neighbours of the same material (walls and MPM points take no part in the diffusion).
    `M` is scratch of shape (>= n_query, 3, 3); `grad` has a row per owned row."""
    dim = len(dim_tag)
    kern = len(kern_tag) - 1
    for a in range(n_query):
        for i in range(3):
            grad[a, i] = 0.0
            for j in range(3):
                M[a, i, j] = 0.0
    for a in range(n_query):
        if method[a] != SPH or dcoef[mat[a]] == 0.0:
            continue
        for k in range(start[a], start[a + 1]):
            b = index[k]
            if method[b] != SPH or mat[b] != mat[a]:
                continue
            xab0, xab1, xab2, fr = pair_gradient(kern, dim, x, a, b, h)
            if fr == 0.0:
                continue
            both = b < n_query
            va = mass[a] / rho[a]
            vb = mass[b] / rho[b]
            drab = rho[b] - rho[a]
            # grad_a W_ab = fr x_ab; grad_b W_ba = -fr x_ab. (x_b - x_a) (x) grad_a W_ab =
            # -fr x_ab (x) x_ab, and the same at the b end.
            for i in range(dim):
                xi = xab0 if i == 0 else (xab1 if i == 1 else xab2)
                grad[a, i] += vb * drab * fr * xi
                if both:  # (rho_a - rho_b) grad_b W_ba = drab fr x_ab
                    grad[b, i] += va * drab * fr * xi
                for j in range(dim):
                    xj = xab0 if j == 0 else (xab1 if j == 1 else xab2)
                    M[a, i, j] -= vb * fr * xi * xj
                    if both:
                        M[b, i, j] -= va * fr * xi * xj
    g = np.zeros(3)
    for a in range(n_query):
        if method[a] != SPH or dcoef[mat[a]] == 0.0:
            continue
        # M is symmetric: (M^T)^-1 g = M^-1 g, solved on the leading dim x dim block
        if dim == 1:
            d = M[a, 0, 0]
            if d > DIFFUSION_MIN_DET:
                grad[a, 0] /= d
        elif dim == 2:
            m00, m01, m11 = M[a, 0, 0], M[a, 0, 1], M[a, 1, 1]
            d = m00 * m11 - m01 * m01
            if d > DIFFUSION_MIN_DET:
                g0, g1 = grad[a, 0], grad[a, 1]
                grad[a, 0] = (m11 * g0 - m01 * g1) / d
                grad[a, 1] = (m00 * g1 - m01 * g0) / d
        else:
            c00 = M[a, 1, 1] * M[a, 2, 2] - M[a, 1, 2] * M[a, 1, 2]
            c01 = M[a, 0, 2] * M[a, 1, 2] - M[a, 0, 1] * M[a, 2, 2]
            c02 = M[a, 0, 1] * M[a, 1, 2] - M[a, 0, 2] * M[a, 1, 1]
            c11 = M[a, 0, 0] * M[a, 2, 2] - M[a, 0, 2] * M[a, 0, 2]
            c12 = M[a, 0, 1] * M[a, 0, 2] - M[a, 0, 0] * M[a, 1, 2]
            c22 = M[a, 0, 0] * M[a, 1, 1] - M[a, 0, 1] * M[a, 0, 1]
            d = M[a, 0, 0] * c00 + M[a, 0, 1] * c01 + M[a, 0, 2] * c02
            if d > DIFFUSION_MIN_DET:
                for i in range(3):
                    g[i] = grad[a, i]
                grad[a, 0] = (c00 * g[0] + c01 * g[1] + c02 * g[2]) / d
                grad[a, 1] = (c01 * g[0] + c11 * g[1] + c12 * g[2]) / d
                grad[a, 2] = (c02 * g[0] + c12 * g[1] + c22 * g[2]) / d
