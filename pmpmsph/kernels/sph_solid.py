"""Grid kernels of an SPH solid in an MPM fluid (`pmpmsph.physics.sph_solid`)."""
import numpy as np

from ..jit import njit
from .shapes import n_corners, node_counts, stencil


@njit
def gather_increment(dim_tag, kind_tag, lo_row, hi_row, x, v, lp, pfield, dvc, origin,
                     offset, inv_dx, strides):
    """v_p += sum_I N_I(x_p) dvc[field_p, I] for the rows [lo_row, hi_row): the change that
    the grid contact made to the velocity field of each particle's body, interpolated as
    G2P would. With sum_p N_I m_p = m_I (the P2G of these rows) the particles receive
    exactly the momentum sum_I m_I dvc_I that the contact took from the other fields.
    CPDI is not supported (the caller passes no domain deformation)."""
    dim = len(dim_tag)
    st = np.zeros(3, np.int64)
    st[:dim] = strides
    off = np.zeros(3, np.int64)
    off[:dim] = offset
    nax = node_counts(dim, strides, dvc.shape[1])
    dom = np.zeros((2, 3, 3))
    for p in range(lo_row, hi_row):
        fld = pfield[p]
        u0 = u1 = u2 = 0.0
        for c in range(n_corners(kind_tag, dim)):
            base, n0, n1, n2, w0, w1, w2, _, _, _ = stencil(
                kind_tag, dim, x, lp, None, dom, p, c, origin, inv_dx, st, off, nax)
            for i in range(n0):
                for j in range(n1):
                    wij = w0[i] * w1[j]
                    for k in range(n2):
                        N = wij * w2[k]
                        node = base + i * st[0] + j * st[1] + k * st[2]
                        u0 += N * dvc[fld, node, 0]
                        if dim > 1:
                            u1 += N * dvc[fld, node, 1]
                        if dim > 2:
                            u2 += N * dvc[fld, node, 2]
        v[p, 0] += u0
        if dim > 1:
            v[p, 1] += u1
        if dim > 2:
            v[p, 2] += u2
