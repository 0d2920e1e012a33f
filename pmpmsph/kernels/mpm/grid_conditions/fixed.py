"""No-slip wall: the nodes take the wall's velocity (0 at rest; a lid slides along itself)."""
from ....jit import njit
from .registry import GridCondition, register_condition


@njit(inline="always")
def impose_fixed(dim, gvel, gdv, f, i, normal, mu, wall):
    """v = v_wall on the node."""
    for a in range(dim):
        gdv[f, i, a] += wall[a] - gvel[f, i, a]
        gvel[f, i, a] = wall[a]


@njit(inline="always")
def mirror_fixed(dim, gvel, gdv, f, o, i, normal, wall):
    """The whole velocity reversed relative to the wall's, v_o = 2 v_wall - v_i, so a lid's
    velocity is what the stencils see on the wall; dv_o = -dv_i (the wall's is constant)."""
    for a in range(dim):
        gvel[f, o, a] = 2.0 * wall[a] - gvel[f, i, a]
        gdv[f, o, a] = -gdv[f, i, a]


register_condition(GridCondition("fixed", 0, impose_fixed, mirror=mirror_fixed, normal="none",
                                 velocity=True))
