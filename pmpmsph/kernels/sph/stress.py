"""Per-row inputs of the updated-Lagrangian SPH pair loop (`kernels.sph.rates.sph_rates`):

* `sph_stress` / `sph_stress_all`: stress of owned SPH particles from their F (solids) or
  density (fluids);
* `sound_speeds`: each row's signal speed (the artificial viscosity's c and the time step);
* `pair_stress`: S = sigma / rho^2, the symmetric 6-vector the pair terms use;
* `sync_ghost_velocity`: the velocity the viscous terms see on fluid rows.
"""
import numpy as np

from ...jit import njit
from ...codes import SPH, WALL
from ...materials.dispatch import compute_stress_tagged, wave_speed_tagged
from ...materials.fluid import TAIT_FLUID, stress_tait_of_jm1
from ...materials.tensor import det3


@njit
def sound_speeds(dim, n, method, mat, rho, F, materials, cs):
    """Current wave speed of rows [0, n) (for the artificial viscosity); `materials` =
    (types, parameters, `material_tag` of the types present)."""
    mtypes, mparams, mtag = materials
    for a in range(n):
        mi = mat[a]
        if mtypes[mi] == TAIT_FLUID:
            if mparams[mi, 1] == 7.0:  # c^2 = kappa gamma/rho0 (rho/rho0)^6, no log/exp
                r = rho[a] / mparams[mi, 2]
                r2 = r * r
                cs[a] = np.sqrt(7.0 * mparams[mi, 0] / mparams[mi, 2] * r2 * r2 * r2)
                continue
            J = mparams[mi, 2] / rho[a]
        else:
            J = det3(F[a])
        cs[a] = wave_speed_tagged(mtag, mtypes[mi], mparams[mi], J) if J > 0 else 0.0


@njit
def sync_ghost_velocity(n, method, v, vg):
    """vg = v on the rows [0, n) that are not walls (walls keep their ghost velocity)."""
    for a in range(n):
        if method[a] != WALL:
            for d in range(v.shape[1]):
                vg[a, d] = v[a, d]


@njit
def pair_stress(dim_tag, n, sigma, rho, S):
    """S_a = sigma_a / rho_a^2 as (xx, yy, zz, xy, yz, xz), for rows [0, n)."""
    for a in range(n):
        r2 = 1.0 / (rho[a] * rho[a])
        S[a, 0] = sigma[a, 0, 0] * r2
        S[a, 1] = sigma[a, 1, 1] * r2
        S[a, 2] = sigma[a, 2, 2] * r2
        S[a, 3] = sigma[a, 0, 1] * r2
        S[a, 4] = sigma[a, 1, 2] * r2
        S[a, 5] = sigma[a, 0, 2] * r2


@njit
def sph_stress(n, method, mat, rho, F, L, dt, states, materials, sigma, vol, mass, p_min,
               morris_mu):
    """Stress and volume (m/rho) of owned SPH rows. A fluid's state is its continuity
    density: its F is set to diag(J, 1, 1) with J = rho0/rho (the Tait stress and energy
    depend on det F only; its pressure is floored at `p_min`), a solid's stress comes from
    its integrated F. A fluid whose viscosity acts pairwise (morris_mu[mat] > 0, see
    `sph_rates`; `morris_mu` may be empty) keeps the pressure alone. The material state
    restarts from `mstate_in` (the state at the step start) so that multi-stage integrators
    commit it once: `states` = (mstate_in, mstate), `materials` = (types, parameters,
    `material_tag` of the types present: the stress switch covers those only).
    Returns the first row with a NaN or non-positive J, or -1."""
    mstate_in, mstate = states
    mtypes, mparams, mtag = materials
    bad = -1
    La = np.zeros((3, 3))
    for a in range(n):
        if method[a] != SPH:
            continue
        mi = mat[a]
        for s in range(mstate.shape[1]):
            mstate[a, s] = mstate_in[a, s]
        Fa = F[a]
        if mtypes[mi] == TAIT_FLUID:
            J = mparams[mi, 2] / rho[a]
            Fa[0, 0] = J
            Fa[1, 1] = 1.0
            Fa[2, 2] = 1.0
            Fa[0, 1] = Fa[1, 0] = Fa[0, 2] = Fa[2, 0] = Fa[1, 2] = Fa[2, 1] = 0.0
        else:
            J = det3(Fa)
        if not J > 0.0:
            bad = a if bad < 0 else bad
            continue
        pairwise = morris_mu.shape[0] > 0 and morris_mu[mi] > 0.0
        if mtypes[mi] == TAIT_FLUID:  # from J - 1 directly (no determinant of diag(J, 1, 1))
            # the velocity gradient only for a viscous stress (not read otherwise)
            viscous = not pairwise and mparams[mi, 3] != 0.0
            for i in range(3):
                for j in range(3):
                    La[i, j] = L[a, i, j] if viscous else 0.0
            stress_tait_of_jm1(J - 1.0, La, mparams[mi], sigma[a])
        else:
            for i in range(3):
                for j in range(3):
                    La[i, j] = 0.0 if pairwise else L[a, i, j]
            compute_stress_tagged(mtag, mtypes[mi], Fa, La, dt, mstate[a], mparams[mi],
                                  sigma[a])
        if mtypes[mi] == TAIT_FLUID:
            # a fluid under tension (a splash, the wake of a body) clumps: its pair forces
            # attract (the tensile instability of SPH); `p_min` (e.g. 0) floors the pressure
            p = -(sigma[a, 0, 0] + sigma[a, 1, 1] + sigma[a, 2, 2]) / 3.0
            if p < p_min:
                for i in range(3):
                    sigma[a, i, i] += p - p_min
        if not np.isfinite(sigma[a, 0, 0]) and bad < 0:
            bad = a
        vol[a] = mass[a] / rho[a]
    return bad


@njit
def sph_stress_all(rows, mat, F, L, dt, mstate, materials, sigma):
    """Stress of the `rows` from their F (total-Lagrangian SPH: owned and halo rows alike,
    each with its material state restarted by the caller; the rows of other materials are
    not written); `materials` as in `sph_stress`."""
    mtypes, mparams, mtag = materials
    La = np.zeros((3, 3))
    for a in rows:
        mi = mat[a]
        for i in range(3):
            for j in range(3):
                La[i, j] = L[a, i, j]
        compute_stress_tagged(mtag, mtypes[mi], F[a], La, dt, mstate[a], mparams[mi],
                              sigma[a])
