"""The quadratic B-spline (Steffen, Kirby & Berzins 2008): nodes base .. base + 2."""
import math

from ....jit import njit
from .registry import ShapeFunction, register_shape


@njit(inline="always")
def weights_quadratic(X, lp):
    """(base, w, dw) for nodes base .. base + 2."""
    base = math.floor(X - 0.5)
    f = X - base  # in [0.5, 1.5)
    return (base, (0.5 * (1.5 - f) ** 2, 0.75 - (f - 1.0) ** 2, 0.5 * (f - 0.5) ** 2, 0.0),
            (f - 1.5, -2.0 * (f - 1.0), f - 0.5, 0.0))


register_shape(ShapeFunction("quadratic", 2, weights_quadratic, width=3, support=1.5,
                             apic_d_inverse=4.0))
