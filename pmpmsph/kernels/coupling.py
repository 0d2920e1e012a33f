"""Kernels of the conservative MPM-SPH interface (`physics.coupling`).

`grid_force_kick`: the SPH particles of the transition zone take part in P2G with their
mass and momentum, so the grid velocity v_I = sum_q N_Iq m_q v_q / m_I from which an MPM
point's strain rate L_p = sum_I v_I (x) grad N_Ip is measured depends on their velocities
too. The force that is the adjoint of that dependence (the one whose work is the MPM
stress power) gives every P2G particle q its share m_q N_Iq / m_I of each node's force f_I
(thesis, seed 003, eq. 65): dv_q = dt sum_I N_Iq f_I / m_I. G2P gives it to the MPM points
(inside dv, with gravity and damping); this gives it to the transition SPH particles, which
get gravity and damping from their own SPH rates.
"""
import numpy as np

from ..jit import njit
from .shapes import cpdi_domain, n_corners, node_counts, stencil


@njit
def grid_force_kick(dim_tag, kind_tag, x, v, lp, Fdom, pfield, gmass, gforce, origin, offset,
                    inv_dx, strides, dt, mass_cutoff):
    """v_q += dt sum_I N_Iq f_I / m_I for the rows of x (positions unchanged); nodes
    lighter than `mass_cutoff` are at rest in the grid solve and give nothing. `lp`, `Fdom`,
    `pfield` as in `kernels.mpm.p2g` (None when the scene has none). The grid's velocity
    boundary conditions are not applied: the transition zone lies inside the body, between
    the MPM and the SPH region."""
    dim = len(dim_tag)
    st = np.zeros(3, np.int64)
    st[:dim] = strides
    off = np.zeros(3, np.int64)
    off[:dim] = offset
    nax = node_counts(dim, strides, gmass.shape[1])
    dom = np.zeros((2, 3, 3))
    fld = 0
    for p in range(x.shape[0]):
        if pfield is not None:
            fld = pfield[p]
        if Fdom is not None:
            cpdi_domain(dim, Fdom, lp, p, dom)
        a0 = a1 = a2 = 0.0
        for c in range(n_corners(kind_tag, dim)):
            base, n0, n1, n2, w0, w1, w2, _, _, _ = stencil(
                kind_tag, dim, x, lp, Fdom, dom, p, c, origin, inv_dx, st, off, nax)
            for i in range(n0):
                for j in range(n1):
                    for k in range(n2):
                        node = base + i * st[0] + j * st[1] + k * st[2]
                        m = gmass[fld, node]
                        if m <= 0.0 or m < mass_cutoff:
                            continue
                        s = w0[i] * w1[j] * w2[k] / m
                        a0 += s * gforce[fld, node, 0]
                        if dim > 1:
                            a1 += s * gforce[fld, node, 1]
                        if dim > 2:
                            a2 += s * gforce[fld, node, 2]
        v[p, 0] += dt * a0
        if dim > 1:
            v[p, 1] += dt * a1
        if dim > 2:
            v[p, 2] += dt * a2
