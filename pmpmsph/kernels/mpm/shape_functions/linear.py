"""The linear hat (Muthukumar thesis, seed 003, eqs. 63-67): nodes base, base + 1."""
import math

from ....jit import njit
from .registry import ShapeFunction, register_shape


@njit(inline="always")
def weights_linear(X, lp):
    """(base, w, dw) for nodes base, base + 1."""
    base = math.floor(X)
    f = X - base
    return base, (1.0 - f, f, 0.0, 0.0), (-1.0, 1.0, 0.0, 0.0)


register_shape(ShapeFunction("linear", 0, weights_linear, width=2, support=1.0))
