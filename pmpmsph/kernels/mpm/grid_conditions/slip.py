"""Free-slip wall: no flow through it, v.n = 0 (Muthukumar thesis, seed 003, eq. 90)."""
from ....jit import njit
from .registry import GridCondition, register_condition


@njit(inline="always")
def impose_slip(dim, gvel, gdv, f, i, normal, mu, wall):
    """The normal component removed: v -> v - (v.n) n."""
    vn = 0.0
    for a in range(dim):
        vn += gvel[f, i, a] * normal[a]
    for a in range(dim):
        d = vn * normal[a]
        gvel[f, i, a] -= d
        gdv[f, i, a] -= d


@njit(inline="always")
def mirror_slip(dim, gvel, gdv, f, o, i, normal, wall):
    """The normal component reflected, v_o = v_i - 2 (v_i.n) n, and the same for dv."""
    vn = 0.0
    dn = 0.0
    for a in range(dim):
        vn += gvel[f, i, a] * normal[a]
        dn += gdv[f, i, a] * normal[a]
    for a in range(dim):
        gvel[f, o, a] = gvel[f, i, a] - 2.0 * vn * normal[a]
        gdv[f, o, a] = gdv[f, i, a] - 2.0 * dn * normal[a]


register_condition(GridCondition("slip", 1, impose_slip, mirror=mirror_slip))
