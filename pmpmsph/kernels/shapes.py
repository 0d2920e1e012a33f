"""MPM shape functions as tensor products of 1-D weights, and the per-particle stencil.

Kinds (integer codes, so one compiled kernel serves all of them):
  LINEAR    linear hat, thesis eqs. 63-67 (2 nodes per axis)
  GIMP      uniform GIMP (Bardenhagen & Kober 2004, used by Raymond seed 000 section 3),
            particle half-width `lp` in cell units (3 nodes per axis for lp <= 1/2)
  QUADRATIC quadratic B-spline (3 nodes per axis)
  CUBIC     cubic B-spline (4 nodes per axis)
All coordinates here are in cell units: X = (x - origin)/dx + pad, so node i sits at X = i.
"""
import math

import numpy as np

from ..jit import njit

LINEAR, GIMP, QUADRATIC, CUBIC = 0, 1, 2, 3
SHAPE_CODES = {"linear": LINEAR, "gimp": GIMP, "quadratic": QUADRATIC, "cubic": CUBIC}
#: nodes per axis touched by one particle, and grid padding (nodes outside the domain) needed
STENCIL_WIDTH = {LINEAR: 2, GIMP: 3, QUADRATIC: 3, CUBIC: 4}
GRID_PAD = 2


@njit(inline="always")
def stencil_width(kind):
    if kind == LINEAR:
        return 2
    if kind == CUBIC:
        return 4
    return 3


@njit(inline="always")
def weights_1d(kind, X, lp, w, dw):
    """Weights w[k] and derivatives dw[k] (per cell unit) of nodes base+k; returns base."""
    if kind == LINEAR:
        base = math.floor(X)
        f = X - base
        w[0] = 1.0 - f
        w[1] = f
        dw[0] = -1.0
        dw[1] = 1.0
    elif kind == QUADRATIC:
        base = math.floor(X - 0.5)
        f = X - base  # in [0.5, 1.5)
        w[0] = 0.5 * (1.5 - f) ** 2
        w[1] = 0.75 - (f - 1.0) ** 2
        w[2] = 0.5 * (f - 0.5) ** 2
        dw[0] = f - 1.5
        dw[1] = -2.0 * (f - 1.0)
        dw[2] = f - 0.5
    elif kind == CUBIC:
        base = math.floor(X) - 1
        f = X - base  # in [1, 2)
        for k in range(4):
            r = f - k
            a = abs(r)
            s = 1.0 if r >= 0.0 else -1.0
            if a < 1.0:
                w[k] = 2.0 / 3.0 - r * r + 0.5 * a * a * a
                dw[k] = s * (-2.0 * a + 1.5 * a * a)
            elif a < 2.0:
                t = 2.0 - a
                w[k] = t * t * t / 6.0
                dw[k] = -s * 0.5 * t * t
            else:
                w[k] = 0.0
                dw[k] = 0.0
    else:  # GIMP, uniform particle half-width lp (cell units, <= 0.5)
        base = math.floor(X - 0.5)
        for k in range(3):
            r = X - (base + k)
            a = abs(r)
            s = 1.0 if r >= 0.0 else -1.0
            if a < lp:
                w[k] = 1.0 - (r * r + lp * lp) / (2.0 * lp)
                dw[k] = -r / lp
            elif a < 1.0 - lp:
                w[k] = 1.0 - a
                dw[k] = -s
            elif a < 1.0 + lp:
                t = 1.0 + lp - a
                w[k] = t * t / (4.0 * lp)
                dw[k] = -s * t / (2.0 * lp)
            else:
                w[k] = 0.0
                dw[k] = 0.0
    return base


@njit(inline="always")
def axis_weights(kind, dim, a, xp, origin, inv_dx, lp, w, dw):
    """Weights along axis `a` of particle position `xp`; axes beyond `dim` get one unit weight.

    Returns (base node index along the axis, number of nodes). Letting the unused axes have a
    single node of weight 1 and derivative 0 lets one triple loop serve 1D, 2D and 3D.
    """
    if a < dim:
        X = (xp[a] - origin[a]) * inv_dx + 2.0  # + GRID_PAD
        return weights_1d(kind, X, lp, w, dw), stencil_width(kind)
    w[0] = 1.0
    dw[0] = 0.0
    return 0, 1


def static_tags(dim, kind):
    """Compile-time constants for the kernels: Numba types a tuple by its length, so
    `len(dim_tag)` and `len(kind_tag) - 1` fold to constants and each (dim, shape function)
    pair gets its own fully specialised machine code (a runtime int costs ~3x here)."""
    return (0,) * dim, (0,) * (kind + 1)
