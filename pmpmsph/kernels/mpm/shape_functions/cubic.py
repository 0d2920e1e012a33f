"""The cubic B-spline (Steffen, Kirby & Berzins 2008): nodes base .. base + 3."""
import math

from ....jit import njit
from .registry import ShapeFunction, register_shape


@njit  # scalar in, scalars out: LLVM inlines it (Numba-IR inlining trips its SSA check)
def _cubic(r):
    """Cubic B-spline and its derivative at signed distance r (cell units)."""
    a = abs(r)
    s = 1.0 if r >= 0.0 else -1.0
    if a < 1.0:
        return 2.0 / 3.0 - r * r + 0.5 * a * a * a, s * (-2.0 * a + 1.5 * a * a)
    if a < 2.0:
        t = 2.0 - a
        return t * t * t / 6.0, -s * 0.5 * t * t
    return 0.0, 0.0


@njit(inline="always")
def weights_cubic(X, lp):
    """(base, w, dw) for nodes base .. base + 3."""
    base = math.floor(X) - 1
    f = X - base  # in [1, 2)
    w0, d0 = _cubic(f)
    w1, d1 = _cubic(f - 1.0)
    w2, d2 = _cubic(f - 2.0)
    w3, d3 = _cubic(f - 3.0)
    return base, (w0, w1, w2, w3), (d0, d1, d2, d3)


register_shape(ShapeFunction("cubic", 3, weights_cubic, width=4, support=2.0,
                             apic_d_inverse=3.0))
