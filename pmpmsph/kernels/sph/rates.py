"""Updated-Lagrangian SPH kernels (Gray-Monaghan solids, weakly compressible fluids).

Each function loops over plain arrays; the stage (`pmpmsph.physics.sph.stage`) owns the order.
Rows [0, n_owned) are owned particles, the rest halo copies. `method` codes: 0 MPM,
1 SPH, 2 SPH wall (dummy particle). Neighbour lists are half CSR lists (`start`, `index`;
each pair once) from `kernels.neighbours`. The integrators are in `kernels.sph.integrate`.

* `sph_rates`: continuity (seed 000, eq. 2.5), momentum with stress (eq. 2.6), the
  Monaghan artificial viscosity (eqs. 2.7-2.8), Monaghan's artificial stress against the
  tensile instability (Gray, Monaghan & Swift 2001), and the velocity gradient whose
  symmetric part is the strain rate of eq. 2.9 (difference form of eq. 2.4).
* `wall_state` (kernels/sph/walls.py): dummy-particle walls (Adami, Hu & Adams 2012).
* the per-row inputs of the pair loop: `kernels.sph.stress` (stress, sound speeds,
  S = sigma / rho^2) and `kernels.sph.artificial_stress`.
"""
import numpy as np

from ...jit import njit
from ...codes import MPM, SPH, WALL
from .kernel_functions import kernel_dwdr, kernel_w
from .contact import contact_pair
from .liu import liu_gradient



@njit
def sph_rates(smoothing, pairs, rows, options, terms, out):
    """Rates of owned SPH rows [0, n_query), from the bundles of kernels/sph/views.py
    (`smoothing_of`, `pair_lists`, `pair_rows`, `rate_options`, `rate_terms`, written to
    `rates`; the names below are their members): acc = dv/dt (eq. 2.6 with -Pi_ab I and the
    artificial-stress term f_ab^n (R_a + R_b), f_ab = W(r_ab)/W(dp)), plus gravity and the
    damping -alpha v; drho = drho/dt (eq. 2.5); L_a = 1/rho_a sum_b m_b (v~_b - v_a) (x) grad_a W_ab
    (eq. 2.9 before symmetrisation, with 1/rho_a for m_b/rho_b: this is the velocity gradient
    whose stress power equals the work of the eq. 2.6 forces, so the semi-discrete energy is
    conserved, and tr L = -drho/rho so rho det F stays constant), v~ = `vg`: the velocity, or
    a wall neighbour's ghost velocity. With `want_force` False only drho and L are computed;
    with `want_L` False L is not (inviscid fluids need no velocity gradient).
    Pi_ab = (-alpha c_ab eta + beta eta^2)/rho_ab when approaching, eta = h v_ab.x_ab /
    (r^2 + 0.01 h^2) (eqs. 2.7-2.8, with the usual 0.01 h^2 against r -> 0).
    S = sigma/rho^2 and R are symmetric 6-vectors (xx, yy, zz, xy, yz, xz).
    `dim = len(dim_tag)` and `kern = len(kern_tag) - 1` are compile-time constants, so the
    unused components and the other kernel vanish from the machine code.

    Over half neighbour lists: every pair is evaluated once and its contribution added to
    both ends (grad_b W_ba = -grad_a W_ab, the pair term of eq. 2.6 is symmetric), halving
    the kernel evaluations.

    Across a material interface (mat_a != mat_b) the pair transmits only isotropic pressure,
    a frictionless contact. Between a fluid a (`fluid[mat_a]`, a Tait material) and a solid b
    (e.g. water against an elastic MPM block or obstacle) the solid point stands for a
    mirror of the fluid: it carries the fluid's density at its volume V_b = m_b/rho_b (mass
    rho_a V_b) and the fluid pressure p_w,b extrapolated to it from its fluid neighbours
    (`pw`, `kernels.sph.walls.mirror_pressure`: Adami et al. 2012 eq. 27, as a dummy wall),
    and it counts twice in the fluid's continuity equation, as a wall does for the fluid in
    contact with it:
        drho_a/dt += 2 rho_a V_b (v_a - v_b) . grad_a W_ab,
        dv_a/dt   += -V_b (max(p_a, 0) + max(p_w,b, 0))/rho_a grad_a W_ab   (minus the
                     artificial viscosity),
    the reaction acting on b. Without `pw` the solid point carries the fluid particle's own
    pressure, p_w,b = p_a (the plain mirror). Why this form:
    (i) Balance: in a fluid at uniform pressure next to a solid lattice that tiles with it,
    the two pressures make the solid points push the interface particle exactly as hard as
    the fluid behind it pushes it towards them; in a hydrostatic column the extrapolated
    p_w makes the interface row feel the same pressure gradient as a row inside the fluid
    (to round-off on a lattice, tests/unit/test_fsi_interface.py). The plain mirror gives
    that row half of it (the solid side pushes with the row's own, higher, pressure), so
    the water stood 1.25 spacings off a float's bottom and the float rode 0.4-0.6 spacings
    high (docs/floats.md).
    (ii) Energy: with the plain mirror the work of these pair forces,
    -2 m_a V_b p_a/rho_a (v_a - v_b) . grad W, is exactly the fluid's stress power
    m_a p_a/rho_a^2 drho_a/dt of the same pair (with p_a >= 0); with p_w it differs by
    m_a V_b (p_a - p_w,b)/rho_a (v_a - v_b) . grad W, which vanishes as p_w,b -> p_a.
    Measured on scene 7 (cases/coupled_float.toml, spacing 0.01, T = 2): the total energy
    falls from 123.72 to 123.08 J (viscous water), kinetic 0.0010 J at T (plain mirror 123.23,
    0.0039 J). Against the earlier contact pressure max(p_a, p_b, 0) on both ends, which took
    the MPM block's own surface pressure: with FLIP on the block the total energy rose by
    1.6 J in 0.5 s and the run failed at t = 1.98 s.
    The continuity and force of these pairs use the plain kernel gradient (also with the
    correction below). A solid's own drho and L (hence its F and
    stress) leave such a fluid neighbour out: the fluid acts on it by pressure alone (an SPH
    solid in MPM water sheared with the water's velocities and blew up;
    physics/sph/solid_in_fluid.py).
    A dummy wall (of a fluid material) and an SPH solid meet in the same pair form with the
    wall's pressure towards solids, `pws` (`kernels.sph.walls.wall_state`: Adami et al.'s
    eq. 27 over the solid's rows) and the solid's own pressure p_s:
        dv_s/dt += -V_w (max(p_s, 0) + max(pws_w, 0))/rho_s grad_s W_sw,
    Adami et al.'s (2012) wall force (their eq. 10 with the wall's pressure of eq. 27) with
    the wall's density taken as the solid's: the wall holds a resting solid up by the
    solid's own weight, whatever water stands beside it (whose pressure the same wall takes
    towards the fluid). Without walls (`pws` empty) such pairs do not occur.
    A contact wall (a wall body with `friction`) meets an SPH solid through
    `kernels.sph.contact.wall_contact` alone (a unilateral penalty on the overlap with the
    wall's surface, and Coulomb friction): such pairs are skipped here (no pressure push,
    no viscosity, the wall out of the solid's kinematics).
    Other material interfaces (two solids, two fluids) keep the contact pressure
    p_c = max(p_a, p_b, 0) on both ends, -p_c (1/rho_a^2 + 1/rho_b^2) I: the full sigma/rho^2
    term would let a solid in tension pull the other body's particles into it; within one
    material (the coupling of seed 000) the full term is used.

    With `want_fsi`, an owned MPM point b whose SPH neighbour a is of another material takes
    the reaction of the pair force, fsi_b = -m_a m_b (pair term) (force units): the SPH
    particle pushes the MPM body as much as it is pushed (momentum is exchanged, not made),
    applied by the caller as an external force in the next P2G.

    With a non-empty `clamped` (a mask over the rows: the held particles of mirror clamps,
    physics/sph/mirror_clamp.py) a clamped row takes no force from pairs with another
    material (a fluid, a dummy wall): its clamp holds it against them. Such a row is a
    ghost whose force is handed to its partner as the solid's energy gradient, and the
    water's push on the clamp is no part of that (with it a plate under SPH water sank).

    With a non-empty `fcpl` (the conservative MPM-SPH coupling, `physics.coupling`), a pair
    of one SPH and one MPM point of the same material is one-sided: only the SPH end's
    stress acts through it (t = S_sph - Pi, the MPM point's stress acts through the grid),
    and the owned MPM end takes the reaction fcpl_b = -m_a m_b (pair term), so the pair
    force is the adjoint of the SPH particle's velocity gradient L_a, which sums over the
    MPM neighbours too (see the module docstring of `physics.coupling`).

    With a non-empty `corr_tag` (`[sph] correction = true`) the kernel gradient is corrected
    with the matrices B_a = (M_a^T)^-1 of `kernels.sph.correction` (Bonet & Lok 1999):
    with G_ab = B_a grad_a W_ab and G_ba = B_b grad_b W_ba = -B_b grad_a W_ab,
        L_a = 1/rho_a sum_b m_b (v~_b - v_a) (x) G_ab        (exact for linear v),
        drho_a/dt = sum_b m_b (v_a - v_b) . G_ab             (= -rho_a tr L_a),
        dv_a/dt = sum_b m_b (S_a B_a + S_b B_b) grad_a W_ab  (same-material pairs),
    the force being the adjoint of that L as in the plain form (the stress power
    sum_a m_a/rho_a sigma_a : L_a is the work of these forces, and since B_a M_a^T = 1 and
    S_a is symmetric the pair forces have no net torque: momentum and angular momentum are
    conserved). The artificial viscosity, the artificial stress and the contact pressure
    across a material interface keep the plain gradient (they act along x_ab). This cures
    the truncated-kernel error of the stress and velocity gradient at a free surface
    (seed 004 §2.1; measured on scene 11: the surface row's velocity gradient of the exact
    Kirsch field is 23 % short plain, 5 % corrected).
    With `liu` (the rows' coefficients of kernels/sph/liu.py, `correction = "liu"`) a pair
    of one material takes Liu's corrected gradients instead, G_ab at the a end and -G_ba at
    the b end in place of B_a g and B_b g (a row without coefficients keeps the plain g):
    the same forms, so the force stays the adjoint of L; it reads a bending strain rate
    across a few particle rows, where B's linear fit averages the rows' slopes.

    With `dcoef` (delta h c0 per material, 0 where a material does not diffuse) and the
    renormalised density gradients `gradrho` of `kernels.sph.density.density_gradient`, the
    continuity equation of a pair of SPH rows of one such material gains the delta-SPH
    diffusion of Antuono et al. (2010), eq. (5) (see kernels/sph/density.py):
        drho_a += dcoef V_b psi_ab . grad_a W_ab,   drho_b -= dcoef V_a psi_ab . grad_a W_ab
    (psi_ba = psi_ab and grad_b W_ba = -grad_a W_ab). With `split` instead of `gradrho`,
    psi_ab is that of Fourtakas et al. (2019): 2 (rho_b - rho_a - rho^H_ba) (x_b - x_a) /
    |x_ab|^2, the hydrostatic density difference of the pair taken out (its form here:
    kernels/sph/density.py), so no gradient pass is needed; it reads `cs` and `gravity`.

    With `morris_mu` (the dynamic viscosity per material, 0 where a material's viscosity is
    not pairwise) a pair of a fluid row a and a row b of the same fluid, or a dummy wall b,
    gains the laminar viscous force of Morris, Fox & Zhu (1997), eq. (8):
        dv_a/dt += m_b (mu_a + mu_b) x_ab . grad_a W_ab / (rho_a rho_b (r^2 + 0.01 h^2)) v~_ab
    with v~_ab = v_a - v~_b, v~_b the wall's ghost velocity (Adami et al. 2012, eq. 23:
    2 v_wall - v_fluid extrapolated, so that the no-slip condition holds on the wall
    surface, `kernels.sph.walls`); the reaction on b (fluid rows only) conserves momentum.
    It discretises mu lap(v) with second-order accuracy on regular lattices, and near a wall
    it sees the wall's velocity through the ghost: the stress form's wall pairs carry the
    wall's extrapolated viscous stress instead (`kernels.sph.walls.wall_state`)."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
    x, v, vg, mass, rho, S, cs, method, mat = rows
    (corr_tag, fluid, gravity, damping, av_alpha, av_beta, want_force, want_L, want_fsi,
     split) = options
    R, as_n, w_dp, B, liu, dcoef, gradrho, morris_mu, pw, clamped, pws, contact = terms
    wall_mu, body = contact
    with_contact = wall_mu.shape[0] > 0  # (contact walls: kernels/sph/contact.py)
    acc, drho, L, fsi, fcpl = out
    dim = len(dim_tag)
    kern = len(kern_tag) - 1
    corr = len(corr_tag) > 0
    use_as = R.shape[0] > 0
    use_liu = liu.shape[0] > 0  # (else Bonet-Lok's B, or no correction)
    rv = np.zeros(3)
    gv = np.zeros(3)
    eps2 = 0.01 * h * h
    h4 = 4.0 * h * h
    one_sided = fcpl.shape[0] > 0  # (else not coupled, or the seed's interface)
    diffuse = dcoef.shape[0] > 0  # (delta-SPH; Fourtakas' splitting needs no gradrho)
    # Fourtakas' splitting: drho/dp = 1/c^2 of each row, so rho^H_ba = -(q_a + q_b)/2 g . x_ab
    # with q = rho/c^2 (kernels/sph/density.py), a load per pair instead of a division
    rho_c2 = np.zeros(x.shape[0] if split else 0)
    for a in range(rho_c2.shape[0]):
        rho_c2[a] = rho[a] / (cs[a] * cs[a]) if cs[a] > 0.0 else 0.0
    gx0 = gravity[0]
    gx1 = gravity[1] if dim > 1 else 0.0
    gx2 = gravity[2] if dim > 2 else 0.0
    with_pw = pw.shape[0] > 0  # (else the plain mirror: the fluid's own pressure)
    with_pws = pws.shape[0] > 0  # (dummy walls: their pressure towards solids)
    with_clamped = clamped.shape[0] > 0  # (mirror clamps of an updated solid)
    pairwise = morris_mu.shape[0] > 0  # (Morris' viscosity)
    if want_fsi or one_sided:
        for a in range(n_query):
            if method[a] == MPM:
                for i in range(dim):
                    if want_fsi:
                        fsi[a, i] = 0.0
                    if one_sided:
                        fcpl[a, i] = 0.0
    for a in range(n_query):
        if method[a] == SPH:
            drho[a] = 0.0
            for i in range(3):
                if want_force:
                    if i < dim:
                        acc[a, i] = 0.0
                for j in range(3):
                    L[a, i, j] = 0.0
    for a in range(n_query):
        upd_a = method[a] == SPH
        xa0 = x[a, 0]
        xa1 = x[a, 1] if dim > 1 else 0.0
        xa2 = x[a, 2] if dim > 2 else 0.0
        va0 = v[a, 0]
        va1 = v[a, 1] if dim > 1 else 0.0
        va2 = v[a, 2] if dim > 2 else 0.0
        ma = mass[a]
        mpm_a = want_fsi and method[a] == MPM
        # delta-SPH of row a: its coefficient (0: a takes no part) and, for Fourtakas'
        # splitting, its material's coefficients of rho^H
        mat_a = mat[a]
        rho_a = rho[a]
        ma_rho_a = ma / rho_a
        dif_a = dcoef[mat_a] if diffuse and upd_a else 0.0
        q_a = rho_c2[a] if split else 0.0
        for k in range(start[a], start[a + 1]):
            b = index[k]
            upd_b = b < n_query and method[b] == SPH
            fsi_a = mpm_a and method[b] == SPH and mat[a] != mat[b]
            fsi_b = (want_fsi and upd_a and method[b] == MPM and b < n_query
                     and mat[a] != mat[b])
            # a same-material SPH-MPM pair of the conservative coupling (docstring)
            one = (one_sided and mat[a] == mat[b] and method[a] != WALL
                   and method[b] != WALL and method[a] != method[b])
            cpl_a = one and method[a] == MPM
            cpl_b = one and method[b] == MPM and b < n_query
            if not (upd_a or upd_b or fsi_a or cpl_a):
                continue
            xab0 = xa0 - x[b, 0]
            xab1 = xa1 - x[b, 1] if dim > 1 else 0.0
            xab2 = xa2 - x[b, 2] if dim > 2 else 0.0
            r2 = xab0 * xab0 + xab1 * xab1 + xab2 * xab2
            if r2 >= h4 or r2 == 0.0:
                continue
            r = np.sqrt(r2)
            # a contact wall and an SPH solid: not here (docstring)
            if with_contact and contact_pair(a, b, n_query, method, mat, fluid, wall_mu,
                                             body) >= 0:
                continue
            fr = kernel_dwdr(kern, dim, r, h) / r
            g0 = fr * xab0
            g1 = fr * xab1
            g2 = fr * xab2
            # the gradients used at the a end (ca = B_a g) and at the b end (cb = B_b g)
            ca0, ca1, ca2, cb0, cb1, cb2 = g0, g1, g2, g0, g1, g2
            if use_liu:  # Liu's gradients of a same-material pair: G_ab and -G_ba
                if mat[a] == mat[b]:
                    w = kernel_w(kern, dim, r, h)
                    if liu[a, 0] != 0.0:
                        rv[0], rv[1], rv[2] = xab0, xab1, xab2
                        liu_gradient(dim, liu[a], rv, w, fr, gv)
                        ca0, ca1, ca2 = gv[0], gv[1], gv[2]
                    if liu[b, 0] != 0.0:
                        rv[0], rv[1], rv[2] = -xab0, -xab1, -xab2
                        liu_gradient(dim, liu[b], rv, w, fr, gv)
                        cb0, cb1, cb2 = -gv[0], -gv[1], -gv[2]
            elif corr:
                ca0 = B[a, 0, 0] * g0
                cb0 = B[b, 0, 0] * g0
                if dim > 1:
                    ca0 += B[a, 0, 1] * g1
                    ca1 = B[a, 1, 0] * g0 + B[a, 1, 1] * g1
                    cb0 += B[b, 0, 1] * g1
                    cb1 = B[b, 1, 0] * g0 + B[b, 1, 1] * g1
                if dim > 2:
                    ca0 += B[a, 0, 2] * g2
                    ca1 += B[a, 1, 2] * g2
                    ca2 = B[a, 2, 0] * g0 + B[a, 2, 1] * g1 + B[a, 2, 2] * g2
                    cb0 += B[b, 0, 2] * g2
                    cb1 += B[b, 1, 2] * g2
                    cb2 = B[b, 2, 0] * g0 + B[b, 2, 1] * g1 + B[b, 2, 2] * g2
            vab0 = va0 - v[b, 0]
            vab1 = va1 - v[b, 1] if dim > 1 else 0.0
            vab2 = va2 - v[b, 2] if dim > 2 else 0.0
            mb = mass[b]
            # a fluid-solid pair: the solid point is the fluid's mirror (docstring)
            mirror_a = mat[a] != mat[b] and fluid[mat[a]] and not fluid[mat[b]]
            mirror_b = mat[a] != mat[b] and fluid[mat[b]] and not fluid[mat[a]]
            # a solid's own kinematics (drho, L) ignore a fluid neighbour of another
            # material: that fluid acts on it by pressure only (docstring)
            kin_a = upd_a and not mirror_b
            kin_b = upd_b and not mirror_a
            if kin_a:
                if mirror_a:
                    drho[a] += 2.0 * rho[a] * mb / rho[b] * (vab0 * g0 + vab1 * g1 + vab2 * g2)
                else:
                    drho[a] += mb * (vab0 * ca0 + vab1 * ca1 + vab2 * ca2)
            if kin_b:
                if mirror_b:
                    drho[b] += 2.0 * rho[b] * ma / rho[a] * (vab0 * g0 + vab1 * g1 + vab2 * g2)
                else:
                    drho[b] += ma * (vab0 * cb0 + vab1 * cb1 + vab2 * cb2)
            if dif_a > 0.0 and method[b] == SPH and mat[b] == mat_a:
                if split:  # Fourtakas: -2 (rho_b - rho_a - rho^H_ba) fr
                    rho_h = -0.5 * (q_a + rho_c2[b]) * (gx0 * xab0 + gx1 * xab1 + gx2 * xab2)
                    pg = -2.0 * (rho[b] - rho_a - rho_h) * fr
                else:
                    # psi_ab . grad_a W_ab = -2 (rho_b - rho_a) fr
                    #                        - (<grad rho>_a + <grad rho>_b) . g
                    pg = -2.0 * (rho[b] - rho_a) * fr - (gradrho[a, 0] + gradrho[b, 0]) * g0
                    if dim > 1:
                        pg -= (gradrho[a, 1] + gradrho[b, 1]) * g1
                    if dim > 2:
                        pg -= (gradrho[a, 2] + gradrho[b, 2]) * g2
                pg *= dif_a
                drho[a] += mb / rho[b] * pg  # (a is an SPH row: upd_a)
                if upd_b:
                    drho[b] -= ma_rho_a * pg
            if want_L:
                if kin_a:  # m_b (v~_b - v_a) (x) G_ab
                    u0 = mb * (vg[b, 0] - va0)
                    L[a, 0, 0] += u0 * ca0
                    if dim > 1:
                        u1 = mb * (vg[b, 1] - va1)
                        L[a, 0, 1] += u0 * ca1
                        L[a, 1, 0] += u1 * ca0
                        L[a, 1, 1] += u1 * ca1
                    if dim > 2:
                        u2 = mb * (vg[b, 2] - va2)
                        L[a, 0, 2] += u0 * ca2
                        L[a, 1, 2] += u1 * ca2
                        L[a, 2, 0] += u2 * ca0
                        L[a, 2, 1] += u2 * ca1
                        L[a, 2, 2] += u2 * ca2
                if kin_b:  # m_a (v~_a - v_b) (x) G_ba, G_ba = -B_b g
                    w0 = -ma * (vg[a, 0] - v[b, 0])
                    L[b, 0, 0] += w0 * cb0
                    if dim > 1:
                        w1 = -ma * (vg[a, 1] - v[b, 1])
                        L[b, 0, 1] += w0 * cb1
                        L[b, 1, 0] += w1 * cb0
                        L[b, 1, 1] += w1 * cb1
                    if dim > 2:
                        w2 = -ma * (vg[a, 2] - v[b, 2])
                        L[b, 0, 2] += w0 * cb2
                        L[b, 1, 2] += w1 * cb2
                        L[b, 2, 0] += w2 * cb0
                        L[b, 2, 1] += w2 * cb1
                        L[b, 2, 2] += w2 * cb2
            if not want_force:
                continue
            vx = vab0 * xab0 + vab1 * xab1 + vab2 * xab2
            pi = 0.0
            if vx < 0.0:
                eta = h * vx / (r2 + eps2)
                pi = (-av_alpha * 0.5 * (cs[a] + cs[b]) * eta + av_beta * eta * eta) / (
                    0.5 * (rho[a] + rho[b]))
            if pairwise:  # Morris et al. (1997) eq. 8 (docstring): k v~_ab, k < 0
                same = method[a] == SPH and method[b] == SPH and mat[a] == mat[b]
                to_a = upd_a and morris_mu[mat[a]] > 0.0 and (same or method[b] == WALL)
                to_b = upd_b and morris_mu[mat[b]] > 0.0 and (same or method[a] == WALL)
                if to_a or to_b:
                    # a wall end takes the fluid's viscosity (its own material's is unused)
                    mu_a = morris_mu[mat[a]] if method[a] == SPH else morris_mu[mat[b]]
                    mu_b = morris_mu[mat[b]] if method[b] == SPH else morris_mu[mat[a]]
                    kv = (mu_a + mu_b) * fr * r2 / (rho[a] * rho[b] * (r2 + eps2))
                    # vg is v on fluid rows and the ghost velocity on walls
                    wv0 = kv * (vg[a, 0] - vg[b, 0])
                    wv1 = kv * (vg[a, 1] - vg[b, 1]) if dim > 1 else 0.0
                    wv2 = kv * (vg[a, 2] - vg[b, 2]) if dim > 2 else 0.0
                    if to_a:
                        acc[a, 0] += mb * wv0
                        if dim > 1:
                            acc[a, 1] += mb * wv1
                        if dim > 2:
                            acc[a, 2] += mb * wv2
                    if to_b:
                        acc[b, 0] -= ma * wv0
                        if dim > 1:
                            acc[b, 1] -= ma * wv1
                        if dim > 2:
                            acc[b, 2] -= ma * wv2
            if corr and mat[a] == mat[b]:
                # the stress acts through the corrected gradients (added below)
                t0 = -pi
                t1 = -pi if dim > 1 else 0.0
                t2 = -pi if dim > 2 else 0.0
                t3 = t4 = t5 = 0.0
            elif mat[a] == mat[b]:  # (only the SPH end's stress in a one-sided pair)
                sa = 0.0 if cpl_a else 1.0
                sb = 0.0 if one and not cpl_a else 1.0
                t0 = sa * S[a, 0] + sb * S[b, 0] - pi
                t1 = sa * S[a, 1] + sb * S[b, 1] - pi if dim > 1 else 0.0
                t2 = sa * S[a, 2] + sb * S[b, 2] - pi if dim > 2 else 0.0
                t3 = sa * S[a, 3] + sb * S[b, 3] if dim > 1 else 0.0
                t4 = sa * S[a, 4] + sb * S[b, 4] if dim > 2 else 0.0
                t5 = sa * S[a, 5] + sb * S[b, 5] if dim > 2 else 0.0
            else:  # material interface: compressive pressure only (docstring)
                pa = -(S[a, 0] + S[a, 1] + S[a, 2]) * rho[a] * rho[a] / 3.0
                pb = -(S[b, 0] + S[b, 1] + S[b, 2]) * rho[b] * rho[b] / 3.0
                if mirror_a and with_pws and method[a] == WALL:
                    # a dummy wall on a solid: the wall's solid-side pressure (docstring)
                    q = -(max(pws[a], 0.0) + max(pb, 0.0)) / (rho[a] * rho[b]) - pi
                elif mirror_b and with_pws and method[b] == WALL:
                    q = -(max(pws[b], 0.0) + max(pa, 0.0)) / (rho[a] * rho[b]) - pi
                elif mirror_a:  # m_b q = -V_b (p_a + p_w,b)/rho_a
                    pm = pw[b] if with_pw else pa
                    q = -(max(pa, 0.0) + max(pm, 0.0)) / (rho[a] * rho[b]) - pi
                elif mirror_b:
                    pm = pw[a] if with_pw else pb
                    q = -(max(pb, 0.0) + max(pm, 0.0)) / (rho[a] * rho[b]) - pi
                else:
                    pc = max(pa, pb, 0.0)
                    q = -pc * (1.0 / (rho[a] * rho[a]) + 1.0 / (rho[b] * rho[b])) - pi
                t0 = q
                t1 = q if dim > 1 else 0.0
                t2 = q if dim > 2 else 0.0
                t3 = t4 = t5 = 0.0
            if use_as and mat[a] == mat[b]:
                f = (kernel_w(kern, dim, r, h) / w_dp) ** as_n
                t0 += f * (R[a, 0] + R[b, 0])
                if dim > 1:
                    t1 += f * (R[a, 1] + R[b, 1])
                    t3 += f * (R[a, 3] + R[b, 3])
                if dim > 2:
                    t2 += f * (R[a, 2] + R[b, 2])
                    t4 += f * (R[a, 4] + R[b, 4])
                    t5 += f * (R[a, 5] + R[b, 5])
            f0 = t0 * g0 + t3 * g1 + t5 * g2
            f1 = t3 * g0 + t1 * g1 + t4 * g2 if dim > 1 else 0.0
            f2 = t5 * g0 + t4 * g1 + t2 * g2 if dim > 2 else 0.0
            if corr and mat[a] == mat[b]:  # + S_a B_a g + S_b B_b g
                if one:  # (the SPH end's term alone; ca, cb are not used after this)
                    if cpl_a:
                        ca0 = ca1 = ca2 = 0.0
                    else:
                        cb0 = cb1 = cb2 = 0.0
                f0 += S[a, 0] * ca0 + S[b, 0] * cb0
                if dim > 1:
                    f0 += S[a, 3] * ca1 + S[b, 3] * cb1
                    f1 += S[a, 3] * ca0 + S[a, 1] * ca1 + S[b, 3] * cb0 + S[b, 1] * cb1
                if dim > 2:
                    f0 += S[a, 5] * ca2 + S[b, 5] * cb2
                    f1 += S[a, 4] * ca2 + S[b, 4] * cb2
                    f2 += (S[a, 5] * ca0 + S[a, 4] * ca1 + S[a, 2] * ca2
                           + S[b, 5] * cb0 + S[b, 4] * cb1 + S[b, 2] * cb2)
            # a clamped row's pushes from other materials go to its clamp (docstring)
            force_a = upd_a and not (with_clamped and clamped[a] and mat[a] != mat[b])
            force_b = upd_b and not (with_clamped and clamped[b] and mat[a] != mat[b])
            if force_a:
                acc[a, 0] += mb * f0
                if dim > 1:
                    acc[a, 1] += mb * f1
                if dim > 2:
                    acc[a, 2] += mb * f2
            if force_b:
                acc[b, 0] -= ma * f0
                if dim > 1:
                    acc[b, 1] -= ma * f1
                if dim > 2:
                    acc[b, 2] -= ma * f2
            if fsi_a:  # b (SPH) gets -m_a f per unit mass: a takes +m_a m_b f
                fsi[a, 0] += ma * mb * f0
                if dim > 1:
                    fsi[a, 1] += ma * mb * f1
                if dim > 2:
                    fsi[a, 2] += ma * mb * f2
            if fsi_b:  # a (SPH) gets +m_b f per unit mass: b takes -m_a m_b f
                fsi[b, 0] -= ma * mb * f0
                if dim > 1:
                    fsi[b, 1] -= ma * mb * f1
                if dim > 2:
                    fsi[b, 2] -= ma * mb * f2
            if cpl_a:  # the same reactions, for the conservative coupling's own kick
                fcpl[a, 0] += ma * mb * f0
                if dim > 1:
                    fcpl[a, 1] += ma * mb * f1
                if dim > 2:
                    fcpl[a, 2] += ma * mb * f2
            if cpl_b:
                fcpl[b, 0] -= ma * mb * f0
                if dim > 1:
                    fcpl[b, 1] -= ma * mb * f1
                if dim > 2:
                    fcpl[b, 2] -= ma * mb * f2
    for a in range(n_query):
        if method[a] != SPH:
            continue
        if want_force:
            for i in range(dim):
                acc[a, i] += gravity[i] - damping * v[a, i]
        if want_L:
            ir = 1.0 / rho[a]
            for i in range(3):
                for j in range(3):
                    L[a, i, j] *= ir
