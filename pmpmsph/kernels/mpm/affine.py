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
from .transfers import add_to_node, point_force


@njit(inline="always")
def _first_nodes(base, st, off, dim, first):
    """Global index per axis of the stencil's first node, from its flat local index, into
    `first` (reused: an array made per particle and corner cost more than the stencil)."""
    rest = base
    for a in range(dim):
        q = rest // st[a]
        rest -= q * st[a]
        first[a] = q + off[a]


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
    (p + dt f). The particle's values are held in scalars, not scratch arrays: the scatter's
    stores could alias an array, so its loads would be redone at every node (with the
    scratch arrays this kernel took 1.3x the time it takes now on the floats of
    tests/verification/test_floats_mpm_water.py). Components beyond `dim` are left out at
    compile time, and each sum keeps the order of the per-component loops it replaces.
    """
    dim_tag, kind_tag = tags
    dim = len(dim_tag)
    x, v, mass, vol, sigma, C = points
    origin, offset, inv_dx, strides, _, _ = layout
    _, kind, st, off, nax, dx, dinv = _layout(dim_tag, kind_tag, strides, offset,
                                               gmass.shape[1], inv_dx)
    dom = np.zeros((2, 3, 3))  # (CPDI's domain; scratch)
    first = np.zeros(3)  # global indices of the stencil's first node
    fld = 0
    v1 = v2 = X1 = X2 = 0.0
    c01 = c02 = c10 = c11 = c12 = c20 = c21 = c22 = 0.0
    mom1 = mom2 = force1 = force2 = 0.0  # (components beyond dim: never written)
    for p in range(x.shape[0]):
        if pfield is not None:
            fld = pfield[p]
        if F is not None:
            cpdi_domain(dim, F, lp, p, dom)
        m = mass[p]
        vo = vol[p]
        # the particle in cell units from global node 0, its velocity, C and vol sigma
        X0 = (x[p, 0] - origin[0]) * inv_dx
        v0 = v[p, 0]
        c00 = C[p, 0, 0]
        s00, s01, s02 = vo * sigma[p, 0, 0], vo * sigma[p, 0, 1], vo * sigma[p, 0, 2]
        s10, s11, s12 = vo * sigma[p, 1, 0], vo * sigma[p, 1, 1], vo * sigma[p, 1, 2]
        s20, s21, s22 = vo * sigma[p, 2, 0], vo * sigma[p, 2, 1], vo * sigma[p, 2, 2]
        if dim > 1:
            X1 = (x[p, 1] - origin[1]) * inv_dx
            v1 = v[p, 1]
            c01, c10, c11 = C[p, 0, 1], C[p, 1, 0], C[p, 1, 1]
        if dim > 2:
            X2 = (x[p, 2] - origin[2]) * inv_dx
            v2 = v[p, 2]
            c02, c12, c20, c21, c22 = C[p, 0, 2], C[p, 1, 2], C[p, 2, 0], C[p, 2, 1], C[p, 2, 2]
        fe0, fe1, fe2 = point_force(fext, p, dim)
        for c in range(n_corners(kind_tag, dim)):
            base, n0, n1, n2, w0, w1, w2, d0, d1, d2 = stencil(
                kind_tag, dim, x, lp, F, dom, p, c, origin, inv_dx, st, off, nax)
            _first_nodes(base, st, off, dim, first)
            for i in range(n0):
                r0 = (first[0] + i - X0) * dx  # x_I - x_p
                for j in range(n1):
                    r1 = (first[1] + j - X1) * dx
                    for k in range(n2):
                        r2 = (first[2] + k - X2) * dx
                        node = base + i * st[0] + j * st[1] + k * st[2]
                        N = w0[i] * w1[j] * w2[k]
                        if mls:
                            g0, g1, g2 = dinv * N * r0, dinv * N * r1, dinv * N * r2
                        else:
                            g0 = d0[i] * w1[j] * w2[k] * inv_dx
                            g1 = w0[i] * d1[j] * w2[k] * inv_dx
                            g2 = w0[i] * w1[j] * d2[k] * inv_dx
                        gmass[fld, node] += N * m
                        # component 0 (and 1, 2): the momentum v + C r, the force
                        # N f - vol sigma g, summed over b < dim in order
                        mom0 = v0 + c00 * r0
                        force0 = N * fe0 - s00 * g0
                        if dim > 1:
                            mom0 += c01 * r1
                            force0 -= s01 * g1
                            mom1 = v1 + c10 * r0 + c11 * r1
                            force1 = N * fe1 - s10 * g0 - s11 * g1
                        if dim > 2:
                            mom0 += c02 * r2
                            force0 -= s02 * g2
                            mom1 += c12 * r2
                            force1 -= s12 * g2
                            mom2 = v2 + c20 * r0 + c21 * r1 + c22 * r2
                            force2 = N * fe2 - s20 * g0 - s21 * g1 - s22 * g2
                        Nm = N * m
                        if force_dt is not None:
                            add_to_node(gmom, fld, node, dim, Nm * mom0 + force_dt * force0,
                                        Nm * mom1 + force_dt * force1,
                                        Nm * mom2 + force_dt * force2)
                        else:
                            add_to_node(gmom, fld, node, dim, Nm * mom0, Nm * mom1, Nm * mom2)
                        if gforce is not None:
                            add_to_node(gforce, fld, node, dim, force0, force1, force2)
                        if gmgrad is not None:
                            add_to_node(gmgrad, fld, node, dim,
                                        m * (d0[i] * w1[j] * w2[k]) * inv_dx,
                                        m * (w0[i] * d1[j] * w2[k]) * inv_dx,
                                        m * (w0[i] * w1[j] * d2[k]) * inv_dx)


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
    dim = len(dim_tag)
    origin, offset, inv_dx, strides, lo, hi = layout
    _, kind, st, off, nax, dx, dinv = _layout(dim_tag, kind_tag, strides, offset,
                                               gvel.shape[1], inv_dx)
    dom = np.zeros((2, 3, 3))  # (CPDI's domain; scratch)
    first = np.zeros(3)  # global indices of the stencil's first node
    vp = np.zeros(3)
    B = np.zeros((3, 3))
    G = np.zeros((3, 3))
    D = np.zeros((3, 3))
    Dinv = np.zeros((3, 3))
    fld = 0
    bad = -1
    need_D = kind != LINEAR and not dinv > 0.0  # (GIMP, CPDI: D_p summed per particle)
    X1 = X2 = 0.0
    for p in range(x.shape[0]):
        if pfield is not None:
            fld = pfield[p]
        if Fdom is not None:
            cpdi_domain(dim, Fdom, lp, p, dom)
        # the sums in scalars (the registers), not in the scratch arrays: a store to those
        # could alias gvel, so each would be a memory round trip per node. Components
        # beyond dim are left out at compile time; entries of B, G, D beyond dim stay 0.
        vp0 = vp1 = vp2 = 0.0
        B00 = B01 = B02 = B10 = B11 = B12 = B20 = B21 = B22 = 0.0
        G00 = G01 = G02 = G10 = G11 = G12 = G20 = G21 = G22 = 0.0
        D00 = D01 = D02 = D10 = D11 = D12 = D20 = D21 = D22 = 0.0
        X0 = (x[p, 0] - origin[0]) * inv_dx  # the particle, in cell units from node 0
        if dim > 1:
            X1 = (x[p, 1] - origin[1]) * inv_dx
        if dim > 2:
            X2 = (x[p, 2] - origin[2]) * inv_dx
        for c in range(n_corners(kind_tag, dim)):
            base, n0, n1, n2, w0, w1, w2, d0, d1, d2 = stencil(
                kind_tag, dim, x, lp, Fdom, dom, p, c, origin, inv_dx, st, off, nax)
            _first_nodes(base, st, off, dim, first)
            for i in range(n0):
                r0 = (first[0] + i - X0) * dx  # x_I - x_p
                for j in range(n1):
                    r1 = (first[1] + j - X1) * dx
                    for k in range(n2):
                        r2 = (first[2] + k - X2) * dx
                        node = base + i * st[0] + j * st[1] + k * st[2]
                        N = w0[i] * w1[j] * w2[k]
                        gN0 = d0[i] * w1[j] * w2[k] * inv_dx
                        gN1 = w0[i] * d1[j] * w2[k] * inv_dx
                        gN2 = w0[i] * w1[j] * d2[k] * inv_dx
                        u0 = gvel[fld, node, 0]
                        vp0 += N * u0
                        G00 += u0 * gN0
                        B00 += N * u0 * r0
                        if need_D:
                            D00 += N * r0 * r0
                        if dim > 1:
                            u1 = gvel[fld, node, 1]
                            vp1 += N * u1
                            G01 += u0 * gN1
                            G10 += u1 * gN0
                            G11 += u1 * gN1
                            B01 += N * u0 * r1
                            B10 += N * u1 * r0
                            B11 += N * u1 * r1
                            if need_D:
                                D01 += N * r0 * r1
                                D10 += N * r1 * r0
                                D11 += N * r1 * r1
                        if dim > 2:
                            u2 = gvel[fld, node, 2]
                            vp2 += N * u2
                            G02 += u0 * gN2
                            G12 += u1 * gN2
                            G20 += u2 * gN0
                            G21 += u2 * gN1
                            G22 += u2 * gN2
                            B02 += N * u0 * r2
                            B12 += N * u1 * r2
                            B20 += N * u2 * r0
                            B21 += N * u2 * r1
                            B22 += N * u2 * r2
                            if need_D:
                                D02 += N * r0 * r2
                                D12 += N * r1 * r2
                                D20 += N * r2 * r0
                                D21 += N * r2 * r1
                                D22 += N * r2 * r2
        vp[0], B[0, 0], G[0, 0], D[0, 0] = vp0, B00, G00, D00
        if dim > 1:
            vp[1] = vp1
            B[0, 1], B[1, 0], B[1, 1] = B01, B10, B11
            G[0, 1], G[1, 0], G[1, 1] = G01, G10, G11
            D[0, 1], D[1, 0], D[1, 1] = D01, D10, D11
        if dim > 2:
            vp[2] = vp2
            B[0, 2], B[1, 2], B[2, 0], B[2, 1], B[2, 2] = B02, B12, B20, B21, B22
            G[0, 2], G[1, 2], G[2, 0], G[2, 1], G[2, 2] = G02, G12, G20, G21, G22
            D[0, 2], D[1, 2], D[2, 0], D[2, 1], D[2, 2] = D02, D12, D20, D21, D22
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
