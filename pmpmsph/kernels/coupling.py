"""Grid-to-particle kicks of the coupling: `add_gathered`, v_p += scale sum_I N_Ip g_I, and
its two uses.

`gather_increment` (an SPH solid in an MPM fluid, `physics.sph.solid_in_fluid`): the change the grid
contact made to the velocity field of each particle's body, interpolated as G2P would. With
sum_p N_I m_p = m_I (the P2G of these rows) the particles receive exactly the momentum
sum_I m_I dv_I that the contact took from the other fields.

`grid_force_kick` (the conservative MPM-SPH interface, `physics.coupling`): the SPH
particles of the transition zone take part in P2G with their mass and momentum, so the grid
velocity v_I = sum_q N_Iq m_q v_q / m_I from which an MPM point's strain rate L_p = sum_I
v_I (x) grad N_Ip is measured depends on their velocities too. The force that is the adjoint
of that dependence (the one whose work is the MPM stress power) gives every P2G particle q
its share m_q N_Iq / m_I of each node's force f_I (thesis, seed 003, eq. 65): dv_q = dt
sum_I N_Iq f_I / m_I. G2P gives it to the MPM points (inside dv, with gravity and damping);
this gives it to the transition SPH particles, which get gravity and damping from their own
SPH rates.
"""
import numpy as np

from ..jit import njit
from .mpm.shapes import cpdi_domain, n_corners, node_counts, stencil


@njit
def add_gathered(tags, lo_row, hi_row, x, v, layout, gvec, scale, gmass=None, mass_cutoff=0.0,
                 lp=None, Fdom=None, pfield=None):
    """v_p += scale sum_I N_Ip g_I for the rows [lo_row, hi_row), g_I = gvec[field_p, I], or
    gvec[field_p, I] / m_I when `gmass` is given (nodes lighter than `mass_cutoff` then give
    nothing: the grid solve keeps them at rest). `tags`, `layout`, `lp`, `Fdom`, `pfield` as
    in `kernels.mpm.transfers.p2g` (None when the scene has none); positions are
    unchanged."""
    dim_tag, kind_tag = tags
    origin, offset, inv_dx, strides, _, _ = layout
    dim = len(dim_tag)
    st = np.zeros(3, np.int64)
    st[:dim] = strides
    off = np.zeros(3, np.int64)
    off[:dim] = offset
    nax = node_counts(dim, strides, gvec.shape[1])
    dom = np.zeros((2, 3, 3))
    fld = 0
    for p in range(lo_row, hi_row):
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
                    wij = w0[i] * w1[j]
                    for k in range(n2):
                        node = base + i * st[0] + j * st[1] + k * st[2]
                        s = wij * w2[k]
                        if gmass is not None:
                            m = gmass[fld, node]
                            if m <= 0.0 or m < mass_cutoff:
                                continue
                            s /= m
                        a0 += s * gvec[fld, node, 0]
                        if dim > 1:
                            a1 += s * gvec[fld, node, 1]
                        if dim > 2:
                            a2 += s * gvec[fld, node, 2]
        v[p, 0] += scale * a0
        if dim > 1:
            v[p, 1] += scale * a1
        if dim > 2:
            v[p, 2] += scale * a2


@njit
def grid_force_kick(tags, x, v, layout, gmass, gforce, dt, mass_cutoff, lp=None, Fdom=None,
                    pfield=None):
    """v_q += dt sum_I N_Iq f_I / m_I for the rows of x (module doc). The grid's velocity
    boundary conditions are not applied: the transition zone lies inside the body, between
    the MPM and the SPH region."""
    add_gathered(tags, 0, x.shape[0], x, v, layout, gforce, dt, gmass, mass_cutoff, lp, Fdom,
                 pfield)


@njit
def gather_increment(tags, lo_row, hi_row, x, v, layout, dvc, lp=None, pfield=None):
    """v_p += sum_I N_I(x_p) dvc[field_p, I] for the rows [lo_row, hi_row) (module doc).
    CPDI is not supported (the caller passes no domain deformation)."""
    add_gathered(tags, lo_row, hi_row, x, v, layout, dvc, 1.0, None, 0.0, lp, None, pfield)
