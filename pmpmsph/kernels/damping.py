"""The velocity damping of a wave absorber (physics/damping.py)."""
from ..jit import njit


@njit
def damp_in_zone(dim, n, x, v, affine, damped_body, body, lo, hi, axis, toward_hi, rate_dt):
    """v_p <- v_p max(0, 1 - dt beta s^2) for the particles of the damped bodies inside the
    box [lo, hi], s in [0, 1] their distance from the box's face opposite the damping
    direction over the box's depth along it (Altomare et al. 2017, Coastal Eng. 127, eq. 12;
    `rate_dt` = dt beta). `affine` (APIC's C, or None) is scaled alike, so the particle's
    whole velocity field is damped and not its centre value alone."""
    depth = hi[axis] - lo[axis]
    for p in range(n):
        if not damped_body[body[p]]:
            continue
        inside = True
        for a in range(dim):
            if x[p, a] < lo[a] or x[p, a] > hi[a]:
                inside = False
        if not inside:
            continue
        s = (x[p, axis] - lo[axis]) / depth if toward_hi else (hi[axis] - x[p, axis]) / depth
        f = max(0.0, 1.0 - rate_dt * s * s)
        for a in range(dim):
            v[p, a] *= f
        if affine is not None:
            for a in range(dim):
                for b in range(dim):
                    affine[p, a, b] *= f
