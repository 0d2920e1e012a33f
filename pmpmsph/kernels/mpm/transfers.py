"""The three MPM loops (Taichi mpm88 style): P2G, grid update, G2P.

Thesis (seed 003) eqs. 65 (P2G of mass, momentum, force), 75-79 (lumped-mass grid solve with
damping f_d = alpha_d m v, eq. 76), 80-86 (G2P: velocity, position, F = (I + dt L) F, volume,
stress). Grid arrays are flat over nodes with a leading velocity-field axis: field 0 only for
single-velocity-field MPM, one field per body for multi-field contact.
"""
import numpy as np

from ...jit import njit
from ...materials.dispatch import compute_stress_tagged, wave_speed_tagged
from ...materials.fluid import stress_tait_of_jm1
from ..deformation import advance
from .shapes import cpdi_domain, cpdi_reach, n_corners, node_counts, stencil


@njit
def point_force(fext, p, dim):
    """The external force of particle p as three scalars: 0 beyond `dim`, and all 0 when
    `fext` is None (pruned at compile time; a separate function, not inlined by Numba, so that
    the pruning sees `fext` as its own argument)."""
    fe0 = fe1 = fe2 = 0.0
    if fext is not None:
        fe0 = fext[p, 0]
        if dim > 1:
            fe1 = fext[p, 1]
        if dim > 2:
            fe2 = fext[p, 2]
    return fe0, fe1, fe2


@njit(inline="always")
def add_to_node(grid, fld, node, dim, a0, a1, a2):
    """grid[fld, node, :dim] += (a0, a1, a2)[:dim]: one node's share of a vector (the
    components beyond `dim` are left out at compile time)."""
    grid[fld, node, 0] += a0
    if dim > 1:
        grid[fld, node, 1] += a1
    if dim > 2:
        grid[fld, node, 2] += a2


@njit
def p2g(tags, points, layout, gmass, gmom, fext=None, lp=None, F=None, pfield=None,
        gforce=None, gmgrad=None, force_dt=None):
    """Scatter mass, momentum and (unless `gforce` is None) internal + external force (eq. 65)
    of the particles `points` (kernels/mpm/views.py `ScatterPoints`; C is not read) onto the
    nodes of `layout` (`grid_layout`).

    Internal force of node I: -sum_p vol_p sigma_p . grad N_I(x_p); external: sum_p N_I f_p.
    Gravity is added on the grid (m_I g is exactly sum_p N_I m_p g).
    Optional inputs are None when a scene lacks them, which Numba resolves at compile time:
    `fext` (particle forces), `lp` (GIMP/CPDI half-widths; None for other shapes), `F` (the
    deformation gradient that shapes a CPDI domain; None for other shapes), `pfield` (the
    velocity field of each particle for multi-field contact; None: field 0), `gmgrad` (mass
    gradients sum_p m_p grad N_I for contact normals). `tags` = (dim_tag,
    kind_tag) are the compile-time dimension and shape function (`static_tags`); in
    `layout`, `origin` is the position of global node 0 (`Grid.node0`) and `offset` the
    global index of local node 0 per axis.
    `force_dt` = dt folds the forces into the momentum (gmom receives p + dt f, gforce is
    None): the form of Taichi's mpm88, for PIC-USL without damping, where the grid needs only
    the updated velocity; None scatters them apart.
    """
    dim_tag, kind_tag = tags
    x, v, mass, vol, sigma, _ = points
    origin, offset, inv_dx, strides, _, _ = layout
    dim = len(dim_tag)
    st = np.zeros(3, np.int64)
    st[:dim] = strides
    off = np.zeros(3, np.int64)
    off[:dim] = offset
    # as scalars: the scatter's stores could alias an array, so array loads would be redone
    st0, st1, st2 = st[0], st[1], st[2]
    nax = node_counts(dim, strides, gmass.shape[1])
    dom = np.zeros((2, 3, 3))
    n = x.shape[0]
    fld = 0
    for p in range(n):
        if pfield is not None:
            fld = pfield[p]
        if F is not None:
            cpdi_domain(dim, F, lp, p, dom)
        m = mass[p]
        vo = vol[p] * inv_dx  # grad N = dw * inv_dx, folded in here
        mv0 = m * v[p, 0]
        mv1 = m * v[p, 1] if dim > 1 else 0.0
        mv2 = m * v[p, 2] if dim > 2 else 0.0
        s00 = vo * sigma[p, 0, 0]
        s01 = vo * sigma[p, 0, 1]
        s02 = vo * sigma[p, 0, 2]
        s11 = vo * sigma[p, 1, 1]
        s12 = vo * sigma[p, 1, 2]
        s22 = vo * sigma[p, 2, 2]
        fe0, fe1, fe2 = point_force(fext, p, dim)
        if force_dt is not None:  # scatter p + dt f: scale the force terms by dt once here
            s00 *= force_dt
            s01 *= force_dt
            s02 *= force_dt
            s11 *= force_dt
            s12 *= force_dt
            s22 *= force_dt
            mv0 += force_dt * fe0
            mv1 += force_dt * fe1
            mv2 += force_dt * fe2
        # The node values, factored axis by axis (sum factorisation of the tensor-product
        # shape functions, N = w0 w1 w2, grad N = (d0 w1 w2, w0 d1 w2, w0 w1 d2)): plain
        # terms N a (mass; momentum unless folded) and force-like terms
        # N b - (vol sigma) . grad N (the force, or the folded momentum p + dt f), built up
        # one axis at a time, so a node costs a few multiply-adds instead of forming N and
        # grad N and the stress product anew (with G2P's: 5 % of the 2D step, 40 % in 3D).
        a0, a1, a2 = (fe0, fe1, fe2) if force_dt is None else (mv0, mv1, mv2)
        for c in range(n_corners(kind_tag, dim)):
            base, n0, n1, n2, w0, w1, w2, d0, d1, d2 = stencil(
                kind_tag, dim, x, lp, F, dom, p, c, origin, inv_dx, st, off, nax)
            for i in range(n0):
                wi = w0[i]
                di = d0[i]
                mi = wi * m
                pi0, pi1, pi2 = wi * mv0, wi * mv1, wi * mv2
                # force-like: (w0 b_c - d0 s_c0, w0 s_c1, w0 s_c2) per component c
                xi0, xi1, xi2 = wi * a0 - di * s00, wi * a1 - di * s01, wi * a2 - di * s02
                yi0, yi1, yi2 = wi * s01, wi * s11, wi * s12
                zi0, zi1, zi2 = wi * s02, wi * s12, wi * s22
                for j in range(n1):
                    wj = w1[j]
                    mj = wj * mi
                    pj0, pj1, pj2 = wj * pi0, wj * pi1, wj * pi2
                    xj0, xj1, xj2 = wj * xi0, wj * xi1, wj * xi2
                    if dim > 1:  # (x * 0 is not folded under our fastmath flags)
                        dj = d1[j]
                        xj0, xj1, xj2 = xj0 - dj * yi0, xj1 - dj * yi1, xj2 - dj * yi2
                    zj0, zj1, zj2 = wj * zi0, wj * zi1, wj * zi2
                    for k in range(n2):
                        wk = w2[k]
                        node = base + i * st0 + j * st1 + k * st2
                        gmass[fld, node] += wk * mj
                        f0, f1, f2 = wk * xj0, wk * xj1, wk * xj2
                        if dim > 2:
                            dk = d2[k]
                            f0, f1, f2 = f0 - dk * zj0, f1 - dk * zj1, f2 - dk * zj2
                        if force_dt is not None:  # p + dt f
                            q0, q1, q2 = f0, f1, f2
                        else:
                            q0, q1, q2 = wk * pj0, wk * pj1, wk * pj2
                        add_to_node(gmom, fld, node, dim, q0, q1, q2)
                        if gforce is not None:
                            add_to_node(gforce, fld, node, dim, f0, f1, f2)
                        if gmgrad is not None:  # multi-field contact's normals
                            add_to_node(gmgrad, fld, node, dim,
                                        m * d0[i] * w1[j] * w2[k] * inv_dx,
                                        m * w0[i] * d1[j] * w2[k] * inv_dx,
                                        m * w0[i] * w1[j] * d2[k] * inv_dx)


MOMENTUM, WITH_FORCE, FOLDED = 0, 1, 2


@njit
def grid_velocity(dim, gmass, gmom, gforce, gvel, gdv, dt, gravity, damping, mass_cutoff,
                  mode, lo, hi):
    """Nodal velocity v = p/m (mode MOMENTUM) and, with forces (WITH_FORCE), the update of
    eqs. 77-79 (lumped mass): a = (f - alpha_d m v)/m + g,  v_new = v + a dt. `gvel` receives
    v_new (or v), `gdv` the change v_new - v (the FLIP increment). FOLDED: gmom holds
    p + dt f (`p2g` with `force_dt`), so v_new = gmom/m + g dt; there is no old velocity and
    gdv is left 0 (only PIC uses this mode). Nodes lighter than `mass_cutoff` stay at rest.
    Only the flat node range [lo, hi) is updated (`Grid.work_range`).
    """
    nf = gmass.shape[0]
    for fld in range(nf):
        for i in range(lo, hi):
            m = gmass[fld, i]
            if m < mass_cutoff:
                for a in range(dim):
                    gvel[fld, i, a] = 0.0
                    gdv[fld, i, a] = 0.0
                continue
            inv_m = 1.0 / m
            for a in range(dim):
                vi = gmom[fld, i, a] * inv_m
                if mode == FOLDED:
                    gvel[fld, i, a] = vi + gravity[a] * dt
                    gdv[fld, i, a] = 0.0
                elif mode == WITH_FORCE:
                    acc = gforce[fld, i, a] * inv_m + gravity[a] - damping * vi
                    gvel[fld, i, a] = vi + acc * dt
                    gdv[fld, i, a] = acc * dt
                else:
                    gvel[fld, i, a] = vi
                    gdv[fld, i, a] = 0.0


@njit
def g2p(tags, points, materials, layout, options, gvel, gdv=None, F=None, lp=None, Fdom=None,
        pfield=None, prestress=None, Lp=None, stress_later=None):
    """Gather from the grid (eqs. 80-86) for every particle of `points` (kernels/mpm/views.py
    `gather_points`), with `materials` (`material_table`), the nodes of `layout` (`grid_layout`)
    and the step's `options` (`gather_options`); the names below are the bundles' members.

    Kinematics: v_p <- flip (v_p + sum N dv) + (1 - flip) sum N v_new (FLIP/PIC blend),
    x_p <- x_p + dt sum N v_new. Deformation: L = sum v_new (x) grad N, F <- (I + dt L) F
    (eq. 82), vol = det F vol0 (eq. 85), sigma from the material (eq. 86) plus any pre-stress.
    L is evaluated at the position before this step's move. Returns (bad, signal): bad is
    the index of the first particle that left the box [lo, hi], became NaN or inverted
    (det F <= 0), or -1; signal is max_p (c_p + |v_p|) of the CFL condition at the new J and
    the velocity after this pass, computed with F when `want_signal` (0 otherwise; the same
    numbers as `kernels.diagnostics.max_signal_speed`, without another pass over F).
    `F` is the stored motion, F (n, 3, 3) or, in a scene of fluids, J (n,) (`advance`).
    Passing `gdv = None` skips the kinematics, `F = None` the deformation (USF/MUSL passes);
    `lp`, `pfield`, `prestress` are None when the scene has none (see `p2g`); `Fdom` is the
    deformation gradient shaping CPDI domains (the same array as `F` when that is updated
    here: each particle's domain is read before its F changes), None for other shapes; a
    CPDI domain that grows beyond `max_reach` cells is reported like an inversion.
    `origin` and `offset` place the local grid as in `p2g`.
    `mat_tag` (the `materials.tag`) fixes the material type at compile time when all
    particles share it (`material_tag`); `pic_tag` = (0,) when flip = 0 (PIC: the
    increments are not gathered and v_p is sum N v_new itself), () otherwise, also fixed at
    compile time.
    `Lp` (n, 3, 3), when given with `gdv = None`, is each particle's velocity gradient,
    gathered already (`kernels.mpm.affine.g2p_affine`): the grid is not read.
    `stress_later` (a flag per material, or None: every stress here) leaves the stress and
    the material state of the flagged materials' particles to a later pass (F-bar,
    `kernels.mpm.fbar`: their F and vol are updated here, then averaged).
    """
    dim_tag, kind_tag = tags
    x, v, sigma, vol, vol0, mat, mstate = points
    mat_tag, mtypes, mparams = materials
    origin, offset, inv_dx, strides, lo, hi = layout
    dt, flip, pic_tag, max_reach, want_signal = options
    dim = len(dim_tag)
    st = np.zeros(3, np.int64)
    st[:dim] = strides
    off = np.zeros(3, np.int64)
    off[:dim] = offset
    st0, st1, st2 = st[0], st[1], st[2]
    nax = node_counts(dim, strides, gvel.shape[1])
    dom = np.zeros((2, 3, 3))
    L = np.zeros((3, 3))
    Fn = np.eye(3)  # J storage leaves all but Fn[0, 0] at the identity (`advance`)
    sig = np.zeros((3, 3))
    n = x.shape[0]
    fld = 0
    bad = -1
    signal = 0.0
    lo0, hi0 = lo[0], hi[0]  # the box as scalars: no array loads per particle
    lo1 = lo[1] if dim > 1 else 0.0
    hi1 = hi[1] if dim > 1 else 0.0
    lo2 = lo[2] if dim > 2 else 0.0
    hi2 = hi[2] if dim > 2 else 0.0
    corners = n_corners(kind_tag, dim)
    if Lp is not None:  # (pruned at compile time when None)
        corners = 0
    for p in range(n):
        if pfield is not None:
            fld = pfield[p]
        if Fdom is not None:
            cpdi_domain(dim, Fdom, lp, p, dom)
        vp0 = vp1 = vp2 = 0.0  # sum N v_new
        dv0 = dv1 = dv2 = 0.0  # sum N dv
        L00 = L01 = L02 = L10 = L11 = L12 = L20 = L21 = L22 = 0.0
        for c in range(corners):
            base, n0, n1, n2, w0, w1, w2, d0, d1, d2 = stencil(
                kind_tag, dim, x, lp, Fdom, dom, p, c, origin, inv_dx, st, off, nax)
            # sum factorisation (see `p2g`): the sums over the last axis first, then the
            # middle one, then the first, so a node costs a few multiply-adds. Components
            # and axes beyond `dim` are left out at compile time (x * 0 is not folded).
            for i in range(n0):
                # sums over j, k of w1 w2 u (a), d1 w2 u (b), w1 d2 u (e), w1 w2 dv (h)
                a0 = a1 = a2 = b0 = b1 = b2 = e0 = e1 = e2 = h0 = h1 = h2 = 0.0
                for j in range(n1):
                    # sums over k of w2 u (s), d2 u (t), w2 dv (r)
                    s0 = s1 = s2 = t0 = t1 = t2 = r0 = r1 = r2 = 0.0
                    for k in range(n2):
                        wk = w2[k]
                        node = base + i * st0 + j * st1 + k * st2
                        u0 = gvel[fld, node, 0]
                        s0 += wk * u0
                        if dim > 1:
                            u1 = gvel[fld, node, 1]
                            s1 += wk * u1
                        if dim > 2:
                            u2 = gvel[fld, node, 2]
                            s2 += wk * u2
                            if F is not None:
                                dk = d2[k]
                                t0 += dk * u0
                                t1 += dk * u1
                                t2 += dk * u2
                        if gdv is not None and len(pic_tag) == 0:  # PIC needs no increments
                            r0 += wk * gdv[fld, node, 0]
                            if dim > 1:
                                r1 += wk * gdv[fld, node, 1]
                            if dim > 2:
                                r2 += wk * gdv[fld, node, 2]
                    wj = w1[j]
                    a0 += wj * s0
                    h0 += wj * r0
                    if dim > 1:
                        a1 += wj * s1
                        h1 += wj * r1
                        if F is not None:
                            dj = d1[j]
                            b0 += dj * s0
                            b1 += dj * s1
                            if dim > 2:
                                b2 += dj * s2
                    if dim > 2:
                        a2 += wj * s2
                        h2 += wj * r2
                        if F is not None:
                            e0 += wj * t0
                            e1 += wj * t1
                            e2 += wj * t2
                wi = w0[i]
                if gdv is not None:
                    vp0 += wi * a0
                    dv0 += wi * h0
                    if dim > 1:
                        vp1 += wi * a1
                        dv1 += wi * h1
                    if dim > 2:
                        vp2 += wi * a2
                        dv2 += wi * h2
                if F is not None:  # L_ca = sum u_c grad_a N
                    di = d0[i]
                    L00 += di * a0
                    if dim > 1:
                        L10 += di * a1
                        L01 += wi * b0
                        L11 += wi * b1
                    if dim > 2:
                        L20 += di * a2
                        L21 += wi * b2
                        L02 += wi * e0
                        L12 += wi * e1
                        L22 += wi * e2
        if gdv is not None:
            x0 = x[p, 0] + dt * vp0
            x[p, 0] = x0
            v[p, 0] = vp0 if len(pic_tag) else flip * (v[p, 0] + dv0) + (1.0 - flip) * vp0
            inside = (x0 >= lo0) & (x0 <= hi0)  # no short circuit: fewer branches
            if dim > 1:
                x1 = x[p, 1] + dt * vp1
                x[p, 1] = x1
                v[p, 1] = vp1 if len(pic_tag) else flip * (v[p, 1] + dv1) + (1.0 - flip) * vp1
                inside &= (x1 >= lo1) & (x1 <= hi1)
            if dim > 2:
                x2 = x[p, 2] + dt * vp2
                x[p, 2] = x2
                v[p, 2] = vp2 if len(pic_tag) else flip * (v[p, 2] + dv2) + (1.0 - flip) * vp2
                inside &= (x2 >= lo2) & (x2 <= hi2)
            if not inside and bad < 0:
                bad = p
        if F is not None:
            if Lp is None:
                L[0, 0] = L00 * inv_dx
                L[0, 1] = L01 * inv_dx
                L[0, 2] = L02 * inv_dx
                L[1, 0] = L10 * inv_dx
                L[1, 1] = L11 * inv_dx
                L[1, 2] = L12 * inv_dx
                L[2, 0] = L20 * inv_dx
                L[2, 1] = L21 * inv_dx
                L[2, 2] = L22 * inv_dx
            else:  # gathered already (an affine transfer)
                for a in range(3):
                    for b in range(3):
                        L[a, b] = Lp[p, a, b]
            J = advance(F, p, dim, dt, L, Fn)  # eq. 82 (or J alone, for fluids)
            vol[p] = J * vol0[p]
            if not (J > 0.0) and bad < 0:
                bad = p
            if Fdom is not None and bad < 0 and cpdi_reach(dim, Fn, lp, p) > max_reach:
                bad = p
            mi = mat[p]
            if want_signal:  # (only a CFL time step reads it)
                speed = v[p, 0] * v[p, 0]
                for a in range(1, dim):
                    speed += v[p, a] * v[p, a]
                c = wave_speed_tagged(mat_tag, mtypes[mi], mparams[mi], J) + np.sqrt(speed)
                if not (c <= signal):  # NaN propagates (no finite dt from a broken state)
                    signal = c
            if stress_later is not None and stress_later[mi]:  # (F-bar: after the volume
                continue                                       # average, `kernels.mpm.fbar`)
            # straight into the particle's row unless a pre-stress is added (the models
            # only write their output)
            out = sig if prestress is not None else sigma[p]
            if F.ndim == 1:  # J alone: every particle a Tait fluid (`Case.tracks_J_only`)
                stress_tait_of_jm1(J - 1.0, L, mparams[mi], out)
            else:
                compute_stress_tagged(mat_tag, mtypes[mi], Fn, L, dt, mstate[p], mparams[mi],
                                      out)
            if prestress is not None:
                for a in range(3):
                    for b in range(3):
                        sigma[p, a, b] = sig[a, b] + prestress[p, a, b]
    return bad, signal
