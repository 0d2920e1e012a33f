"""Uniform GIMP (Bardenhagen & Kober 2004, used by Raymond, seed 000, section 3): the linear
hat averaged over a particle of half-width lp (cell units, lp <= 1/2): nodes base .. base + 2.
"""
import math

from ....jit import njit
from .registry import ShapeFunction, register_shape


@njit
def _gimp(r, lp):
    """Uniform GIMP weight and derivative at signed distance r for half-width lp <= 1/2."""
    a = abs(r)
    s = 1.0 if r >= 0.0 else -1.0
    if a < lp:
        return 1.0 - (r * r + lp * lp) / (2.0 * lp), -r / lp
    if a < 1.0 - lp:
        return 1.0 - a, -s
    if a < 1.0 + lp:
        t = 1.0 + lp - a
        return t * t / (4.0 * lp), -s * t / (2.0 * lp)
    return 0.0, 0.0


@njit(inline="always")
def weights_gimp(X, lp):
    """(base, w, dw) for nodes base .. base + 2."""
    base = math.floor(X - 0.5)
    f = X - base
    w0, d0 = _gimp(f, lp)
    w1, d1 = _gimp(f - 1.0, lp)
    w2, d2 = _gimp(f - 2.0, lp)
    return base, (w0, w1, w2, 0.0), (d0, d1, d2, 0.0)


register_shape(ShapeFunction("gimp", 1, weights_gimp, width=3, support=1.25, half_width=0.5))
