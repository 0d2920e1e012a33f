"""delta-SPH density diffusion of weakly compressible fluids (Antuono et al. 2010): the
renormalised density gradient that its diffusion term needs (`density_gradient`); the term
itself is summed in `kernels.sph.rates.sph_rates` with the continuity equation.

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

Fourtakas, Dominguez, Vacondio & Rogers (2019), Comput. Fluids 190, eq. (17) (DualSPHysics'
default density diffusion) reach the same end without the gradients: the hydrostatic part
of each pair's density difference is taken out of psi,

    psi_ab = 2 (rho_ba - rho^H_ba) (x_b - x_a) / |x_ab|^2,   rho_ba = rho_b - rho_a,

so a fluid at rest under gravity diffuses nothing and the pass over the neighbours that
builds <grad rho> is not needed. Fourtakas et al. take rho^H_ba = rho0 [(1 + dp/C_B)^(1/gamma)
- 1] with dp = rho0 g z_ab, the Tait law linearised at the free surface. Here the pair's own
state is used instead: dp = dp/drho drho = c^2 drho, and dp = rho g . (x_b - x_a) at rest,
both at the pair's midpoint,

    rho^H_ba = -(q_a + q_b)/2 g . x_ab,   q = rho / c^2,

which is exact to third order in |x_ab| at any depth (the surface-linearised form is off by
a relative p/(gamma kappa) in a deep tank) and, being odd in (a, b), gives the same pair term
whichever end a half neighbour list puts first (the rank invariance of DESIGN.md §4).
"""
import numpy as np

from ...jit import njit
from ...codes import SPH
from .kernel_functions import pair_gradient

#: a row whose moment matrix has det M below this keeps the plain sum for its gradient: a
#: particle with few or collinear neighbours (a splash), whose M cannot be inverted safely;
#: at a plane free surface det M is about 1/2
DIFFUSION_MIN_DET = 0.1


@njit
def density_gradient(smoothing, pairs, x, mass, rho, method, mat, dcoef, M, grad):
    """<grad rho>_a of the owned rows [0, n_query) that diffuse (SPH rows of a material with
    dcoef[mat] > 0), over half neighbour lists (each pair once, both ends), from the SPH
    neighbours of the same material (walls and MPM points take no part in the diffusion).
    `M` is scratch of shape (>= n_query, 3, 3) (its symmetric part is filled); `grad` has a
    row per owned row. Row a's sums are kept in scalars over its list and the b ends
    written as they come (this pass costs a fraction of the rates' pair loop)."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
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
        va = mass[a] / rho[a]
        ra = rho[a]
        g0 = g1 = g2 = 0.0
        m00 = m01 = m02 = m11 = m12 = m22 = 0.0
        for k in range(start[a], start[a + 1]):
            b = index[k]
            if method[b] != SPH or mat[b] != mat[a]:
                continue
            xab0, xab1, xab2, fr = pair_gradient(kern, dim, x, a, b, h)
            if fr == 0.0:
                continue
            # grad_a W_ab = fr x_ab, grad_b W_ba = -fr x_ab; (x_b - x_a) (x) grad_a W_ab =
            # -fr x_ab (x) x_ab at both ends; (rho_a - rho_b) grad_b W_ba = drab fr x_ab
            wb = mass[b] / rho[b] * fr
            drab = rho[b] - ra
            g0 += wb * drab * xab0
            m00 -= wb * xab0 * xab0
            if dim > 1:
                g1 += wb * drab * xab1
                m01 -= wb * xab0 * xab1
                m11 -= wb * xab1 * xab1
            if dim > 2:
                g2 += wb * drab * xab2
                m02 -= wb * xab0 * xab2
                m12 -= wb * xab1 * xab2
                m22 -= wb * xab2 * xab2
            if b < n_query:
                wa = va * fr
                grad[b, 0] += wa * drab * xab0
                M[b, 0, 0] -= wa * xab0 * xab0
                if dim > 1:
                    grad[b, 1] += wa * drab * xab1
                    M[b, 0, 1] -= wa * xab0 * xab1
                    M[b, 1, 1] -= wa * xab1 * xab1
                if dim > 2:
                    grad[b, 2] += wa * drab * xab2
                    M[b, 0, 2] -= wa * xab0 * xab2
                    M[b, 1, 2] -= wa * xab1 * xab2
                    M[b, 2, 2] -= wa * xab2 * xab2
        grad[a, 0] += g0
        grad[a, 1] += g1
        grad[a, 2] += g2
        M[a, 0, 0] += m00
        M[a, 0, 1] += m01
        M[a, 0, 2] += m02
        M[a, 1, 1] += m11
        M[a, 1, 2] += m12
        M[a, 2, 2] += m22
    for a in range(n_query):  # the lower triangle of the symmetric M
        M[a, 1, 0] = M[a, 0, 1]
        M[a, 2, 0] = M[a, 0, 2]
        M[a, 2, 1] = M[a, 1, 2]
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

