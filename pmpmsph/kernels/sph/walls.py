"""Dummy-particle walls of SPH fluids (Adami, Hu & Adams 2012, eq. 27): the wall particles'
pressure extrapolated from the fluid with the hydrostatic correction, their density from the
inverse Tait law, their viscous stress extrapolated likewise, and the ghost velocity used in
the viscous terms (eq. 23, no-slip: 2 v_wall - v~, free slip: +v~). Part of the SPH kernels
(`kernels.sph.rates`)."""
import numpy as np

from ...jit import njit
from ...codes import SPH, WALL
from .kernel_functions import kernel_w


@njit
def extrapolated_pressure(dim, kern, h, x, rho, sigma, gravity, w, f):
    """One fluid row f's part of Adami et al.'s (2012) eq. 27 at row w: (W_wf, p_f,
    p_f + rho_f g . (x_w - x_f)), the fluid's pressure carried hydrostatically to w."""
    r2 = 0.0
    gr = 0.0
    for d in range(dim):
        dx = x[w, d] - x[f, d]
        r2 += dx * dx
        gr += gravity[d] * dx
    pf = -(sigma[f, 0, 0] + sigma[f, 1, 1] + sigma[f, 2, 2]) / 3.0
    return kernel_w(kern, dim, np.sqrt(r2), h), pf, pf + rho[f] * gr


@njit
def wall_state(smoothing, pairs, x, v, rho, sigma, method, mat, materials, fluid, gravity,
               no_slip, vg, pws):
    """Dummy wall particles among rows [0, n_query): Adami et al. (2012) eq. 27,
    p_w = (sum_f p_f W_wf + g . sum_f rho_f (x_w - x_f) W_wf) / sum_f W_wf (static wall),
    rho_w from the inverse Tait law of the wall's material, sigma_w = -p_w I + tau~ with
    tau~ = sum_f dev(sigma_f) W_wf / sum_f W_wf the fluid's viscous stress extrapolated
    (no-slip walls; zero for inviscid fluids and for a viscosity that acts pairwise, whose
    stress has no deviator: without it a fluid row next to the wall misses the wall side of
    its kernel sum of the shear stress, and a viscous flow slips along the wall); the ghost
    velocity vg_w = 2 v_w - v~ (no-slip, v_w the wall's own velocity: a lid or a moving wall)
    or +v~ (free slip), v~ = sum_f v_f W_wf / sum_f W_wf.
    The sums run over the fluid rows f alone (`fluid[mat_f]`, a Tait material, SPH or MPM):
    eq. 27 extrapolates the fluid's pressure into the wall, and a solid's mean stress and
    density carried there are no fluid pressure (a dense block standing on the floor beside
    the water made the walls under the water 1.1 times rho g H with rho 1e3, 2.4 times with
    rho 1e6, and the water moved; tests/verification/test_sph_walls_solids.py).
    The pressure the wall puts on an SPH solid is a second state of the same wall, `pws`:
    eq. 27 over the solid SPH rows s instead (non-fluid, not walls),
        pws_w = (sum_s p_s W_ws + g . sum_s rho_s (x_w - x_s) W_ws) / sum_s W_ws,
    p_s = -tr(sigma_s)/3, the solid's own pressure carried hydrostatically into the wall
    (0 where no solid is near), used by the wall-solid pairs of `kernels.sph.rates` as the
    wall end's pressure: the wall holds a solid resting on it as it holds a fluid, and does
    not feel the fluid beside it doing so (docs/sph.md, "walls and solids").
    Over half neighbour lists (each pair once), the sums gathered for the wall end of every
    wall-fluid and wall-solid pair; a halo wall is left to its owner (then refreshed in the
    halo)."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
    mtypes, mparams = materials
    dim = len(dim_tag)
    kern = len(kern_tag) - 1
    sw = np.zeros(n_query)
    ps = np.zeros(n_query)
    ss = np.zeros(n_query)  # the solid sums: Shepard weight and pressure
    qs = np.zeros(n_query)
    vt = np.zeros((n_query, 3))
    tau = np.zeros((n_query, 3, 3))
    for a in range(n_query):
        wa = method[a] == WALL
        for k in range(start[a], start[a + 1]):
            b = index[k]
            wb = method[b] == WALL
            if wa == wb:
                continue
            if wb and b >= n_query:
                continue  # a halo wall: its owner sums it
            w, f = (a, b) if wa else (b, a)
            is_fluid = fluid[mat[f]]
            if not is_fluid and method[f] != SPH:
                continue  # an MPM solid point: the walls do not act on it
            W, pf, pw_f = extrapolated_pressure(dim, kern, h, x, rho, sigma, gravity, w, f)
            if W == 0.0:
                continue
            if not is_fluid:  # an SPH solid: the wall's state towards solids (docstring)
                qs[w] += pw_f * W
                ss[w] += W
                continue
            ps[w] += pw_f * W
            sw[w] += W
            for d in range(dim):
                vt[w, d] += v[f, d] * W
            if no_slip:
                for i in range(3):
                    for j in range(3):
                        tau[w, i, j] += (sigma[f, i, j] + (pf if i == j else 0.0)) * W
    sgn = -1.0 if no_slip else 1.0
    for w in range(n_query):
        if method[w] != WALL:
            continue
        pws[w] = qs[w] / ss[w] if ss[w] > 0.0 else 0.0
        mi = mat[w]
        p = ps[w] / sw[w] if sw[w] > 0.0 else 0.0
        ratio = p / mparams[mi, 0] + 1.0
        if ratio < 1e-3:
            ratio = 1e-3
        rho[w] = mparams[mi, 2] * ratio ** (1.0 / mparams[mi, 1])
        inv = 1.0 / sw[w] if sw[w] > 0.0 else 0.0
        for i in range(3):
            for j in range(3):
                sigma[w, i, j] = tau[w, i, j] * inv - (p if i == j else 0.0)
        for d in range(dim):
            vg[w, d] = sgn * vt[w, d] * inv + (2.0 * v[w, d] if no_slip else 0.0)


@njit
def mirror_pressure(smoothing, pairs, x, rho, sigma, method, mat, fluid, gravity, pw):
    """The fluid pressure at owned solid rows next to a fluid of another material, as at a
    dummy wall (Adami et al. 2012, eq. 27, static body):
        p_w = (sum_f p_f W_wf + g . sum_f rho_f (x_w - x_f) W_wf) / sum_f W_wf
    over the fluid rows f of other materials within the support (0 where there are none),
    dummy walls left out: a wall's pressure is itself extrapolated from the fluid, and a dry
    wall (no fluid near, p = 0) beside the solid would take the pressure down; a wall presses
    on a solid with its solid-side state instead (`wall_state`'s pws).
    The mirror pair of `kernels.sph.rates.sph_rates` then presses on the solid with p_a + p_w, the
    fluid's pressure at both ends, rather than with 2 p_a, the pressure of the fluid particle
    taken for the solid point's too: in a column at rest that counts the water a kernel's
    depth below the face, and a float rides high by a fraction of a spacing (docs/floats.md).
    Over half neighbour lists, as `wall_state`; a halo row is left to its owner (then
    refreshed in the halo). The body's own acceleration (eq. 27's -a_w) is left out."""
    dim_tag, kern_tag, h = smoothing
    n_query, start, index = pairs
    dim = len(dim_tag)
    kern = len(kern_tag) - 1
    sw = np.zeros(n_query)
    for w in range(n_query):
        pw[w] = 0.0
    for a in range(n_query):
        for k in range(start[a], start[a + 1]):
            b = index[k]
            if mat[a] == mat[b] or method[a] == WALL or method[b] == WALL:
                continue
            if fluid[mat[a]] and not fluid[mat[b]]:
                f, w = a, b
            elif fluid[mat[b]] and not fluid[mat[a]]:
                f, w = b, a
            else:
                continue
            if w >= n_query:
                continue  # a halo row: its owner sums it
            W, _, pw_f = extrapolated_pressure(dim, kern, h, x, rho, sigma, gravity, w, f)
            pw[w] += pw_f * W
            sw[w] += W
    for w in range(n_query):
        if sw[w] > 0.0:
            pw[w] /= sw[w]

