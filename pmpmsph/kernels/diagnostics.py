"""Per-rank sums for the diagnostics table and the CFL signal speed.

Kinetic energy K = sum 1/2 m v.v and strain energy U = sum psi(F) vol0 (thesis eq. 88 in its
hyperelastic form), gravitational potential P = -sum m g.x, momentum and mass.

The strain energy is the dear part of a diagnostics row (a log and an exp per particle for a
Tait fluid). When every particle shares one material type, `particle_sums` takes that type as
a compile-time tag (`material_tag`, as the MPM stress update does) and calls the model's
energy directly: the runtime switch over all six models, inlined in the particle loop, cost
more than the energy itself. The sums are the same, in the same order, bit for bit.
"""
import numpy as np

from ..jit import njit
from .deformation import deformation_matrix, jacobian
from ..materials.dispatch import strain_energy_tagged, wave_speed_tagged


@njit
def particle_sums(dim, x, v, mass, vol0, F, mat, mtypes, mparams, mstate, gravity, out,
                  mtag=()):
    """out[:] = (K, U, P, px, py, pz, mass): this rank's owned-particle sums.

    `F`: the stored motion, F (n, 3, 3) or J (n,) (`ParticleSet.deformation`).
    `mtag`: `material_tag` of the materials present (() for a mix: runtime switch)."""
    for k in range(out.shape[0]):
        out[k] = 0.0
    scratch = np.eye(3)
    for p in range(x.shape[0]):
        m = mass[p]
        v2 = 0.0
        gx = 0.0
        for a in range(dim):
            v2 += v[p, a] * v[p, a]
            gx += gravity[a] * x[p, a]
            out[3 + a] += m * v[p, a]
        out[0] += 0.5 * m * v2
        mi = mat[p]
        Fp = deformation_matrix(F, p, scratch)
        out[1] += (strain_energy_tagged(mtag, mtypes[mi], Fp, mstate[p], mparams[mi])
                   * vol0[p])
        out[2] -= m * gx
        out[6] += m


@njit
def max_signal_speed(dim, v, F, mat, mtypes, mparams, mtag):
    """max_p (c_p + |v_p|), the speed in the CFL condition dt = CFL h / max(c + |v|).
    `F`: F (n, 3, 3) or J (n,) (`ParticleSet.deformation`); `mtag` as in `particle_sums`."""
    best = 0.0
    for p in range(v.shape[0]):
        J = jacobian(F, p)
        speed = 0.0
        for a in range(dim):
            speed += v[p, a] * v[p, a]
        mi = mat[p]
        c = wave_speed_tagged(mtag, mtypes[mi], mparams[mi], J) + np.sqrt(speed)
        if not (c <= best):  # NaN propagates so a broken state is never given a finite dt
            best = c
    return best
