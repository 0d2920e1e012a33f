"""Per-rank sums for the diagnostics table and the CFL signal speed.

Kinetic energy K = sum 1/2 m v.v and strain energy U = sum psi(F) vol0 (thesis eq. 88 in its
hyperelastic form), gravitational potential P = -sum m g.x, momentum and mass.
"""
import numpy as np

from ..jit import njit
from ..materials.dispatch import strain_energy, wave_speed


@njit
def particle_sums(dim, x, v, mass, vol0, F, mat, mtypes, mparams, mstate, gravity, out):
    """out[:] = (K, U, P, px, py, pz, mass): this rank's owned-particle sums."""
    for k in range(out.shape[0]):
        out[k] = 0.0
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
        out[1] += strain_energy(mtypes[mi], F[p], mstate[p], mparams[mi]) * vol0[p]
        out[2] -= m * gx
        out[6] += m


@njit
def max_signal_speed(dim, v, F, mat, mtypes, mparams):
    """max_p (c_p + |v_p|), the speed in the CFL condition dt = CFL h / max(c + |v|)."""
    best = 0.0
    for p in range(v.shape[0]):
        Fp = F[p]
        J = (Fp[0, 0] * (Fp[1, 1] * Fp[2, 2] - Fp[1, 2] * Fp[2, 1])
             - Fp[0, 1] * (Fp[1, 0] * Fp[2, 2] - Fp[1, 2] * Fp[2, 0])
             + Fp[0, 2] * (Fp[1, 0] * Fp[2, 1] - Fp[1, 1] * Fp[2, 0]))
        speed = 0.0
        for a in range(dim):
            speed += v[p, a] * v[p, a]
        mi = mat[p]
        c = wave_speed(mtypes[mi], mparams[mi], J) + np.sqrt(speed)
        if not (c <= best):  # NaN propagates so a broken state is never given a finite dt
            best = c
    return best
