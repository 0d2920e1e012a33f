"""Particle shifting of SPH fluids (Lind, Xu, Stansby & Rogers 2012, J. Comput. Phys. 231:
1499; the diffusion coefficient of Skillen et al. 2013) with free-surface detection
(Marrone et al. 2010): a fluid particle moves a little down the gradient of the particle
concentration, so the lattice stays regular where the flow would stretch it into lines and
voids (a tensile region, a vortex core, the tip of a surge), without changing the flow.

    delta x_a = -D grad C_a,   grad C_a = sum_b V_b grad_a W_ab,   D = A h |v_a| dt,

over every neighbour (fluid, wall, solid: a particle is not shifted into a wall), capped at
MAX_SHIFT spacings per step. Free surface: lambda_a, the smallest eigenvalue of
M_a = sum_b V_b (x_b - x_a) (x) grad_a W_ab (1 in a full support), tells the surface
(lambda < SURFACE) where the particle is not shifted, the region near it (lambda < NEAR)
where only the tangential part (I - n n) delta x is applied, n = -grad C / |grad C|, and
the interior. The velocity moves with the particle to first order, as Lind et al.'s
(2012) Taylor correction: v_a += (grad v)_a delta x_a, with the renormalised gradient
(grad v)_a = [sum_b V_b (v~_b - v_a) (x) grad_a W_ab] M_a^-1 (exact for a linear field;
v~ the ghost velocity of a wall), and likewise the density with delta-SPH's renormalised
gradient where it is on. Without that a shift carries momentum across the flow: with
D = A h |v| dt the shifts diffuse momentum like a viscosity A h |v|, several times water's
at the scales of a lid-driven cavity (measured: 12 % off Ghia's centre line instead of 2 %).
"""
import numpy as np

from ...jit import njit
from ...codes import MPM, SPH
from .kernel_functions import pair_gradient

#: lambda below this: a free-surface particle (Marrone et al. 2010 use 0.2 for the surface
#: proper and 0.75 for its neighbourhood in their eigenvalue test; Sun et al. 2017 0.55)
SURFACE = 0.55
#: lambda below this (and above SURFACE): near the surface, tangential shifting only
NEAR = 0.9
#: the largest shift of one step, in particle spacings
MAX_SHIFT = 0.2


@njit
def shifting_state(smoothing, pairs, x, vg, mass, rho, method, mat, fluid, M, state):
    """grad C_a, lambda_a and the renormalised velocity gradient (grad v)_a (row i: grad of
    v_i) of the owned fluid SPH rows [0, n_query) (module docstring), into `state`
    (`shift_fields`), over half neighbour lists (each pair once, both ends); `vg` is v, or
    the ghost velocity on walls. `M` is scratch of shape (>= n_query, 3, 3); rows that do
    not shift get gradc = 0, lam = 1."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
    gradc, lam, gradv = state
    dim = len(dim_tag)
    kern = len(kern_tag) - 1
    for a in range(n_query):
        lam[a] = 1.0
        for i in range(3):
            gradc[a, i] = 0.0
            for j in range(3):
                M[a, i, j] = 0.0
                gradv[a, i, j] = 0.0
    for a in range(n_query):
        sa = method[a] == SPH and fluid[mat[a]]
        for k in range(start[a], start[a + 1]):
            b = index[k]
            sb = b < n_query and method[b] == SPH and fluid[mat[b]]
            if not (sa or sb) or method[b] == MPM and not sa:
                continue
            xab0, xab1, xab2, fr = pair_gradient(kern, dim, x, a, b, h)
            if fr == 0.0:
                continue
            va = mass[a] / rho[a]
            vb = mass[b] / rho[b]
            for i in range(dim):
                xi = xab0 if i == 0 else (xab1 if i == 1 else xab2)
                dvi = vg[b, i] - vg[a, i]
                if sa:  # grad_a W_ab = fr x_ab
                    gradc[a, i] += vb * fr * xi
                if sb:  # grad_b W_ba = -fr x_ab
                    gradc[b, i] -= va * fr * xi
                for j in range(dim):
                    xj = xab0 if j == 0 else (xab1 if j == 1 else xab2)
                    if sa:
                        M[a, i, j] -= vb * fr * xi * xj
                        gradv[a, i, j] += vb * dvi * fr * xj
                    if sb:  # (v_a - v_b) (x) grad_b W_ba = dvi fr x_ab
                        M[b, i, j] -= va * fr * xi * xj
                        gradv[b, i, j] += va * dvi * fr * xj
    for a in range(n_query):
        if not (method[a] == SPH and fluid[mat[a]]):
            continue
        if dim == 1:
            lam[a] = M[a, 0, 0]
        elif dim == 2:
            m00, m01, m11 = M[a, 0, 0], M[a, 0, 1], M[a, 1, 1]
            half = 0.5 * (m00 + m11)
            lam[a] = half - np.sqrt(0.25 * (m00 - m11) ** 2 + m01 * m01)
        else:
            lam[a] = _smallest_eigenvalue3(M[a])
        if lam[a] >= SURFACE:  # (grad v) M^-1 where M can be inverted safely
            _times_inverse(dim, gradv[a], M[a])


@njit(inline="always")
def _times_inverse(dim, g, m):
    """g <- g m^-1 on the leading dim x dim block (m symmetric positive definite)."""
    inv = np.zeros((3, 3))
    if dim == 1:
        inv[0, 0] = 1.0 / m[0, 0]
    elif dim == 2:
        d = m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0]
        inv[0, 0], inv[0, 1] = m[1, 1] / d, -m[0, 1] / d
        inv[1, 0], inv[1, 1] = -m[1, 0] / d, m[0, 0] / d
    else:
        c00 = m[1, 1] * m[2, 2] - m[1, 2] * m[2, 1]
        c01 = m[0, 2] * m[2, 1] - m[0, 1] * m[2, 2]
        c02 = m[0, 1] * m[1, 2] - m[0, 2] * m[1, 1]
        d = m[0, 0] * c00 + m[1, 0] * c01 + m[2, 0] * c02
        inv[0, 0], inv[0, 1], inv[0, 2] = c00 / d, c01 / d, c02 / d
        inv[1, 0] = (m[1, 2] * m[2, 0] - m[1, 0] * m[2, 2]) / d
        inv[1, 1] = (m[0, 0] * m[2, 2] - m[0, 2] * m[2, 0]) / d
        inv[1, 2] = (m[0, 2] * m[1, 0] - m[0, 0] * m[1, 2]) / d
        inv[2, 0] = (m[1, 0] * m[2, 1] - m[1, 1] * m[2, 0]) / d
        inv[2, 1] = (m[0, 1] * m[2, 0] - m[0, 0] * m[2, 1]) / d
        inv[2, 2] = (m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0]) / d
    row = np.zeros(3)
    for i in range(dim):
        for j in range(dim):
            row[j] = g[i, j]
        for j in range(dim):
            s = 0.0
            for k in range(dim):
                s += row[k] * inv[k, j]
            g[i, j] = s


@njit(inline="always")
def _smallest_eigenvalue3(m):
    """Smallest eigenvalue of a symmetric 3x3 matrix (the trigonometric closed form)."""
    p1 = m[0, 1] ** 2 + m[0, 2] ** 2 + m[1, 2] ** 2
    q = (m[0, 0] + m[1, 1] + m[2, 2]) / 3.0
    if p1 == 0.0:
        return min(m[0, 0], m[1, 1], m[2, 2])
    p2 = (m[0, 0] - q) ** 2 + (m[1, 1] - q) ** 2 + (m[2, 2] - q) ** 2 + 2.0 * p1
    p = np.sqrt(p2 / 6.0)
    b00, b11, b22 = (m[0, 0] - q) / p, (m[1, 1] - q) / p, (m[2, 2] - q) / p
    b01, b02, b12 = m[0, 1] / p, m[0, 2] / p, m[1, 2] / p
    r = 0.5 * (b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02)
               + b02 * (b01 * b12 - b11 * b02))
    r = min(max(r, -1.0), 1.0)
    phi = np.arccos(r) / 3.0
    return q + 2.0 * p * np.cos(phi + 2.0 * np.pi / 3.0)


@njit
def shift_positions(dim_tag, n, method, mat, fluid, x, v, rho, gradrho, state, coef, dt,
                    spacing):
    """x_a += delta x_a of the owned fluid SPH rows (module docstring), v_a (and rho_a, when
    `gradrho` has rows: delta-SPH is on) by the Taylor correction, from `state`
    (`shift_fields`, of `shifting_state`); `coef` = A h. Returns the largest shift, in
    spacings."""
    gradc, lam, gradv = state
    dim = len(dim_tag)
    largest = 0.0
    cap = MAX_SHIFT * spacing
    for a in range(n):
        if not (method[a] == SPH and fluid[mat[a]]) or lam[a] < SURFACE:
            continue
        speed = 0.0
        g2 = 0.0
        for i in range(dim):
            speed += v[a, i] * v[a, i]
            g2 += gradc[a, i] * gradc[a, i]
        if g2 == 0.0:
            continue
        d = -coef * np.sqrt(speed) * dt
        s0 = d * gradc[a, 0]
        s1 = d * gradc[a, 1] if dim > 1 else 0.0
        s2 = d * gradc[a, 2] if dim > 2 else 0.0
        if lam[a] < NEAR:  # tangential part only: (I - n n) s, n along grad C
            sn = (s0 * gradc[a, 0] + (s1 * gradc[a, 1] if dim > 1 else 0.0)
                  + (s2 * gradc[a, 2] if dim > 2 else 0.0)) / g2
            s0 -= sn * gradc[a, 0]
            if dim > 1:
                s1 -= sn * gradc[a, 1]
            if dim > 2:
                s2 -= sn * gradc[a, 2]
        size = np.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
        if size > cap:
            s0 *= cap / size
            s1 *= cap / size
            s2 *= cap / size
            size = cap
        x[a, 0] += s0
        if dim > 1:
            x[a, 1] += s1
        if dim > 2:
            x[a, 2] += s2
        for i in range(dim):
            v[a, i] += gradv[a, i, 0] * s0 + gradv[a, i, 1] * s1 + gradv[a, i, 2] * s2
        if gradrho.shape[0] > 0:
            rho[a] += gradrho[a, 0] * s0 + gradrho[a, 1] * s1 + gradrho[a, 2] * s2
        largest = max(largest, size / spacing)
    return largest
