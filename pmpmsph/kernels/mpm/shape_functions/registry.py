"""The MPM shape-function registry: a shape's module ends with

    register_shape(ShapeFunction("quadratic", 2, weights_quadratic, width=3, support=1.5,
                                 apic_d_inverse=4.0))

and `kernels.mpm.shapes` generates from it the switches the transfers call (`weights_1d`,
`weights_tagged`, `stencil_width`, the APIC D^-1), as `[mpm] shape`'s choice list
(`config.case.SHAPES`) and the particle fields a shape needs (`physics.mpm.stage`) are.

A shape function here is a tensor product of 1-D weights: `weights(X, lp)` gives
(base, w, dw) at X (cell units) for the nodes base .. base + width - 1, as 4-tuples.
Traits:
  width           nodes per axis of one stencil (at most 4)
  support         half-width of the 1-D weight's support, cells
  apic_d_inverse  D_p^-1 dx^2 of APIC's inertia-like tensor when it is a constant multiple
                  of I (Jiang et al. 2015, section 5.1: 4 quadratic, 3 cubic B-spline); 0
                  when D_p is summed per particle (the linear hat takes C_p = grad v)
  half_width      the largest particle half-width lp (cells) a shape that carries one per
                  particle (field `lp`) can take; 0: it carries none
  corners         the stencil is averaged over the 2^dim corners of a convected particle
                  domain (CPDI: `kernels.mpm.shapes.corner_stencil`)

`shape_functions()` imports every module of this package that is not this one, so a new shape
is one new file (and its test). Plain Python: importing it does not import numba.
"""
from dataclasses import dataclass

from ....plugins import Registry


@dataclass(frozen=True)
class ShapeFunction:
    name: str
    code: int
    weights: object
    width: int
    support: float
    apic_d_inverse: float = 0.0
    half_width: float = 0.0
    corners: bool = False


_SHAPES = Registry("shape function", __package__, __file__)


def register_shape(shape):
    """Add `shape`; its code and name must be new, its stencil at most 4 nodes wide."""
    if not 1 <= shape.width <= 4:
        raise ValueError(f"shape function {shape.name!r}: width {shape.width} not in 1..4")
    return _SHAPES.register(shape)


#: the registered shape functions in code order; the one called `name` (KeyError if none is)
shape_functions, shape_named = _SHAPES.entries, _SHAPES.named
