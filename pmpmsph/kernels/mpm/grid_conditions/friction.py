"""Coulomb friction wall, one-sided: only an approaching normal velocity (v.n > 0, n outward)
is removed, and the tangential velocity is reduced by mu times it (the Coulomb contact of
Bardenhagen, Brackbill & Sulsky 2000, with the wall as the rigid body). Material may leave
it, so a face with it does not mirror the nodes beyond."""
import numpy as np

from ....jit import njit
from .registry import GridCondition, register_condition


@njit(inline="always")
def impose_friction(dim, gvel, gdv, f, i, normal, mu, wall):
    """v -> max(0, 1 - mu (v.n) / |v_t|) v_t when v.n > 0; unchanged otherwise."""
    vn = 0.0
    for a in range(dim):
        vn += gvel[f, i, a] * normal[a]
    if vn > 0.0:
        vt2 = 0.0
        for a in range(dim):
            t = gvel[f, i, a] - vn * normal[a]
            vt2 += t * t
        vt = np.sqrt(vt2)
        scale = 0.0
        if vt > 0.0:
            scale = max(0.0, 1.0 - mu * vn / vt)
        for a in range(dim):
            t = gvel[f, i, a] - vn * normal[a]
            new = scale * t
            gdv[f, i, a] += new - gvel[f, i, a]
            gvel[f, i, a] = new


register_condition(GridCondition("friction", 2, impose_friction, friction=True))
