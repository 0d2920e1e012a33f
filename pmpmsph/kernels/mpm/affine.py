"""Affine velocity transfers: APIC (Jiang et al. 2015) and MLS-MPM (Hu et al. 2018).

Each particle carries, besides v_p, an affine velocity matrix C_p (the field "C"), so the
velocity it hands the grid is v_p + C_p (x_I - x_p) and not a constant. With

  B_p = sum_I N_I v_I (x_I - x_p)^T,   D_p = sum_I N_I (x_I - x_p)(x_I - x_p)^T

(Jiang 2015, eqs. 10-11), G2P sets v_p = sum_I N_I v_I and C_p = B_p D_p^-1, and P2G scatters
m_I v_I = sum_p N_I m_p (v_p + C_p (x_I - x_p)) (eq. 12). Both transfers conserve linear and
angular momentum and, unlike PIC, keep rotation and shear; unlike FLIP they add no noise.
D_p is dx^2/4 I for the quadratic and dx^2/3 I for the cubic B-spline (Jiang 2015, §5.1);
for the linear hat B_p D_p^-1 = sum_I v_I grad N_I^T exactly (§5.3; D_p itself vanishes on a
node), and for GIMP and CPDI D_p is summed per particle.

MLS-MPM (Hu 2018, eqs. 16-19, quadratic and cubic B-splines): the gradient of N_I is taken as
its moving-least-squares approximation D^-1 N_I (x_I - x_p), so the internal force of a node
is -vol_p sigma_p D^-1 N_I (x_I - x_p), and the particle's velocity gradient is C_p itself
(F <- (I + dt C_p) F): the force and the deformation use the same gradient.

These kernels are the plain per-node loops (not sum-factorised like `kernels.mpm.transfers`):
the transfer, not the speed, is what they are for. The deformation update is
`kernels.mpm.transfers.g2p`'s, given the velocity gradient gathered here.
"""
import numpy as np

from ...jit import njit
from ...materials.tensor import block_inverse
from .shapes import (LINEAR, apic_d_inverse, cpdi_domain, local_layout, n_corners,
                     stencil)


@njit(inline="always")
def _first_nodes(base, st, off, dim, first):
    """Global index per axis of the stencil's first node, from its flat local index, into
    `first` (reused: an array made per particle and corner cost more than the stencil)."""
    rest = base
    for a in range(dim):
        q = rest // st[a]
        rest -= q * st[a]
        first[a] = q + off[a]


@njit(inline="always")
def node_offset(first, i, j, k, X, dx, r):
    """r = x_I - x_p for the node (i, j, k) of a stencil whose first node is `first` (global
    indices per axis), the particle at X (cell units from global node 0)."""
    r[0] = (first[0] + i - X[0]) * dx
    r[1] = (first[1] + j - X[1]) * dx
    r[2] = (first[2] + k - X[2]) * dx


@njit
def _layout(dim_tag, kind_tag, strides, offset, n_nodes, inv_dx):
    """(dim, shape kind, strides, offset, nodes per axis, dx, D^-1 of a B-spline or 0)."""
    dim = len(dim_tag)
    kind = len(kind_tag) - 1
    st, off, nax = local_layout(dim, strides, offset, n_nodes)
    dx = 1.0 / inv_dx
    # D^-1, a multiple of I for the B-splines (Jiang 2015 §5.1); 0 for the other shapes
    return dim, kind, st, off, nax, dx, apic_d_inverse(kind) / (dx * dx)


@njit
def p2g_affine(tags, mls, points, layout, gmass, gmom, fext=None, lp=None, F=None, pfield=None,
               gforce=None, gmgrad=None, force_dt=None):
    """P2G with the affine momentum m_p C_p (x_I - x_p) (Jiang 2015 eq. 12).

    The force of node I is sum_p N_I f_p - vol_p sigma_p g_I with g_I = grad N_I (APIC) or
    D^-1 N_I (x_I - x_p) (`mls`, Hu 2018 eq. 18). Arguments as `kernels.mpm.transfers.p2g`
    (`points` with C): `gforce` None and `force_dt` = dt fold the force into the momentum
    (p + dt f).
    """
    dim_tag, kind_tag = tags
    x, v, mass, vol, sigma, C = points
    origin, offset, inv_dx, strides, _, _ = layout
    dim, kind, st, off, nax, dx, dinv = _layout(dim_tag, kind_tag, strides, offset,
                                                 gmass.shape[1], inv_dx)
    dom = np.zeros((2, 3, 3))  # (CPDI's domain; scratch)
    X = np.zeros(3)  # the particle, in cell units from global node 0
    r = np.zeros(3)  # x_I - x_p
    first = np.zeros(3)  # global indices of the stencil's first node
    g = np.zeros(3)
    fe = np.zeros(3)
    mom = np.zeros(3)
    fld = 0
    for p in range(x.shape[0]):
        if pfield is not None:
            fld = pfield[p]
        if F is not None:
            cpdi_domain(dim, F, lp, p, dom)
        m = mass[p]
        for a in range(dim):
            X[a] = (x[p, a] - origin[a]) * inv_dx
            fe[a] = fext[p, a] if fext is not None else 0.0
        for c in range(n_corners(kind_tag, dim)):
            base, n0, n1, n2, w0, w1, w2, d0, d1, d2 = stencil(
                kind_tag, dim, x, lp, F, dom, p, c, origin, inv_dx, st, off, nax)
            _first_nodes(base, st, off, dim, first)
            for i in range(n0):
                for j in range(n1):
                    for k in range(n2):
                        node = base + i * st[0] + j * st[1] + k * st[2]
                        N = w0[i] * w1[j] * w2[k]
                        node_offset(first, i, j, k, X, dx, r)
                        if mls:
                            for b in range(3):
                                g[b] = dinv * N * r[b]
                        else:
                            g[0] = d0[i] * w1[j] * w2[k] * inv_dx
                            g[1] = w0[i] * d1[j] * w2[k] * inv_dx
                            g[2] = w0[i] * w1[j] * d2[k] * inv_dx
                        gmass[fld, node] += N * m
                        for a in range(dim):
                            mom[a] = v[p, a]
                            for b in range(dim):
                                mom[a] += C[p, a, b] * r[b]
                            force = N * fe[a]
                            for b in range(dim):
                                force -= vol[p] * sigma[p, a, b] * g[b]
                            if force_dt is not None:
                                gmom[fld, node, a] += N * m * mom[a] + force_dt * force
                            else:
                                gmom[fld, node, a] += N * m * mom[a]
                            if gforce is not None:
                                gforce[fld, node, a] += force
                            if gmgrad is not None:
                                gmgrad[fld, node, a] += m * (d0[i] * w1[j] * w2[k] if a == 0
                                                             else w0[i] * d1[j] * w2[k] if a == 1
                                                             else w0[i] * w1[j] * d2[k]) * inv_dx


@njit
def g2p_affine(tags, mls, x, v, C, layout, gvel, dt, lp=None, Fdom=None, pfield=None,
               Lout=None):
    """G2P of APIC / MLS-MPM: v_p = sum N_I v_I, C_p = B_p D_p^-1 (see the module),
    x_p += dt v_p. `Lout` (None, or n x 3 x 3) receives the velocity gradient the deformation
    is to use, evaluated before the move: sum v_I grad N_I^T (APIC) or C_p (`mls`);
    `kernels.mpm.transfers.g2p` with `Lp = Lout` then updates F and the stress. Returns the index of
    the first particle that left the box [lo, hi] of `layout` (or -1).
    """
    dim_tag, kind_tag = tags
    origin, offset, inv_dx, strides, lo, hi = layout
    dim, kind, st, off, nax, dx, dinv = _layout(dim_tag, kind_tag, strides, offset,
                                                 gvel.shape[1], inv_dx)
    dom = np.zeros((2, 3, 3))  # (CPDI's domain; scratch)
    X = np.zeros(3)  # the particle, in cell units from global node 0
    r = np.zeros(3)  # x_I - x_p
    first = np.zeros(3)  # global indices of the stencil's first node
    vp = np.zeros(3)
    B = np.zeros((3, 3))
    G = np.zeros((3, 3))
    D = np.zeros((3, 3))
    Dinv = np.zeros((3, 3))
    fld = 0
    bad = -1
    for p in range(x.shape[0]):
        if pfield is not None:
            fld = pfield[p]
        if Fdom is not None:
            cpdi_domain(dim, Fdom, lp, p, dom)
        vp[:] = 0.0
        B[:] = 0.0
        G[:] = 0.0
        D[:] = 0.0
        for a in range(dim):
            X[a] = (x[p, a] - origin[a]) * inv_dx
        for c in range(n_corners(kind_tag, dim)):
            base, n0, n1, n2, w0, w1, w2, d0, d1, d2 = stencil(
                kind_tag, dim, x, lp, Fdom, dom, p, c, origin, inv_dx, st, off, nax)
            _first_nodes(base, st, off, dim, first)
            for i in range(n0):
                for j in range(n1):
                    for k in range(n2):
                        node = base + i * st[0] + j * st[1] + k * st[2]
                        N = w0[i] * w1[j] * w2[k]
                        gN0 = d0[i] * w1[j] * w2[k] * inv_dx
                        gN1 = w0[i] * d1[j] * w2[k] * inv_dx
                        gN2 = w0[i] * w1[j] * d2[k] * inv_dx
                        node_offset(first, i, j, k, X, dx, r)
                        for a in range(dim):
                            u = gvel[fld, node, a]
                            vp[a] += N * u
                            G[a, 0] += u * gN0
                            G[a, 1] += u * gN1
                            G[a, 2] += u * gN2
                            for b in range(dim):
                                B[a, b] += N * u * r[b]
                                D[a, b] += N * r[a] * r[b]
        # C_p = B_p D_p^-1 (Jiang 2015 eq. 10)
        if kind == LINEAR:
            for a in range(dim):
                for b in range(dim):
                    C[p, a, b] = G[a, b]
        elif dinv > 0.0:
            for a in range(dim):
                for b in range(dim):
                    C[p, a, b] = B[a, b] * dinv
        else:  # GIMP, CPDI: D_p per particle (symmetric positive definite)
            block_inverse(D, dim, Dinv)
            for a in range(dim):
                for b in range(dim):
                    s = 0.0
                    for e in range(dim):
                        s += B[a, e] * Dinv[e, b]
                    C[p, a, b] = s
        if Lout is not None:
            for a in range(3):
                for b in range(3):
                    Lout[p, a, b] = C[p, a, b] if (mls and a < dim and b < dim) else G[a, b]
        inside = True
        for a in range(dim):
            v[p, a] = vp[a]
            xa = x[p, a] + dt * vp[a]
            x[p, a] = xa
            inside &= (xa >= lo[a]) & (xa <= hi[a])
        if not inside and bad < 0:
            bad = p
    return bad
