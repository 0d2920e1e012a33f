"""Grid boundary-condition kernels, generated from the registry of `grid_conditions`.

`apply_grid_bc` imposes each listed node's condition on every velocity field; `mirror_grid_bc`
sets the nodes beyond a grid face to the mirror image of those inside it. The per-node
conditions are the registered ones (fixed, slip, friction: one module each), chosen by code
through generated `if` chains.
"""
from ...jit import code_switch, njit
from .grid_conditions.registry import grid_conditions

_CONDITIONS = grid_conditions()
BC_CODES = {c.name: c.code for c in _CONDITIONS}

_impose = code_switch("_impose", "dim, gvel, gdv, f, i, normal, mu, wall",
                      {c.code: c.impose for c in _CONDITIONS}, "return")
_mirror = code_switch("_mirror", "dim, gvel, gdv, f, o, i, normal, wall",
                      {c.code: c.mirror for c in _CONDITIONS if c.mirror is not None},
                      "return")


@njit
def apply_grid_bc(dim, bc_node, bc_kind, bc_normal, bc_mu, bc_wall, gvel, gdv):
    """Velocity boundary conditions on grid nodes, for every velocity field: node
    `bc_node[j]` takes condition `bc_kind[j]` with outward normal `bc_normal[j]`, friction
    coefficient `bc_mu[j]` and wall velocity `bc_wall[j]`."""
    nf = gvel.shape[0]
    for j in range(bc_node.shape[0]):
        i = bc_node[j]
        for f in range(nf):
            _impose(bc_kind[j], dim, gvel, gdv, f, i, bc_normal[j], bc_mu[j], bc_wall[j])


@njit
def mirror_grid_bc(dim, outside, inside, kind, normal, wall, gvel, gdv):
    """Velocities of the nodes beyond a wall as the mirror image of those inside it.

    Wide stencils (GIMP, B-splines) give a particle near a wall weight on nodes one or two
    cells inside it, so constraining the wall nodes alone does not stop it crossing. With the
    outside nodes set to the reflection of the inside ones (the condition's `mirror`), the
    interpolated normal velocity is odd about the wall and vanishes on it, for any stencil.
    """
    nf = gvel.shape[0]
    for j in range(outside.shape[0]):
        for f in range(nf):
            _mirror(kind, dim, gvel, gdv, f, outside[j], inside[j], normal, wall)
