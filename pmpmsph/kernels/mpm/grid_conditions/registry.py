"""The grid boundary-condition registry (`[[boundaries]] type`): a condition's module ends with

    register_condition(GridCondition("slip", 1, impose_slip, mirror=mirror_slip,
                                     normal="required"))

and `kernels.mpm.grid_bc` generates from it the switches the boundary kernels call, as
`[[boundaries]] type`'s choice list (`config.case.BC_KINDS`) and the checks of its keys
(`config.conditions`) are.

  impose    `impose(dim, gvel, gdv, f, i, normal, mu, wall)`: the condition on node i of
            velocity field f (`gvel`, and the FLIP increment `gdv` changed by the same amount
            so a constrained component carries no spurious acceleration); `normal` the
            outward unit normal, `mu` the friction coefficient, `wall` the wall velocity
  mirror    `mirror(dim, gvel, gdv, f, o, i, normal, wall)`: on a grid face, node o beyond
            the wall from node i inside it (`kernels.mpm.grid_bc.mirror_grid_bc`); None:
            the condition does not mirror (a one-sided wall lets material leave)
  normal    "required" off a face (`normal = [...]`), or "none" (the condition needs none)
  friction  the condition takes `friction` (a coefficient >= 0)
  velocity  the condition takes a wall `velocity` (the nodes take it: a lid)

Plain Python: importing it does not import numba.
"""
from dataclasses import dataclass

from ....plugins import Registry


@dataclass(frozen=True)
class GridCondition:
    name: str
    code: int
    impose: object
    mirror: object = None
    normal: str = "required"
    friction: bool = False
    velocity: bool = False


_CONDITIONS = Registry("grid boundary condition", __package__, __file__)


def register_condition(condition):
    """Add `condition`; its code and name must be new."""
    if condition.normal not in ("required", "none"):
        raise ValueError(f"grid condition {condition.name!r}: normal is 'required' or 'none'")
    return _CONDITIONS.register(condition)


#: the registered conditions in code order; the one called `name` (KeyError if none is)
grid_conditions, condition_named = _CONDITIONS.entries, _CONDITIONS.named
