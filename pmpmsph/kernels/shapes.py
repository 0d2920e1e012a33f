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

from numba.extending import overload

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
def weights_linear(X, lp):
    """Linear hat (thesis eqs. 63-67): (base, w, dw) for nodes base, base + 1."""
    base = math.floor(X)
    f = X - base
    return base, (1.0 - f, f, 0.0, 0.0), (-1.0, 1.0, 0.0, 0.0)


@njit(inline="always")
def weights_quadratic(X, lp):
    """Quadratic B-spline: nodes base .. base + 2."""
    base = math.floor(X - 0.5)
    f = X - base  # in [0.5, 1.5)
    return (base, (0.5 * (1.5 - f) ** 2, 0.75 - (f - 1.0) ** 2, 0.5 * (f - 0.5) ** 2, 0.0),
            (f - 1.5, -2.0 * (f - 1.0), f - 0.5, 0.0))


@njit(inline="always")
def weights_cubic(X, lp):
    """Cubic B-spline: nodes base .. base + 3."""
    base = math.floor(X) - 1
    f = X - base  # in [1, 2)
    w0, d0 = _cubic(f)
    w1, d1 = _cubic(f - 1.0)
    w2, d2 = _cubic(f - 2.0)
    w3, d3 = _cubic(f - 3.0)
    return base, (w0, w1, w2, w3), (d0, d1, d2, d3)


@njit(inline="always")
def weights_gimp(X, lp):
    """Uniform GIMP with particle half-width lp (cell units): nodes base .. base + 2."""
    base = math.floor(X - 0.5)
    f = X - base
    w0, d0 = _gimp(f, lp)
    w1, d1 = _gimp(f - 1.0, lp)
    w2, d2 = _gimp(f - 2.0, lp)
    return base, (w0, w1, w2, 0.0), (d0, d1, d2, 0.0)


_WEIGHTS = {LINEAR: weights_linear, GIMP: weights_gimp, QUADRATIC: weights_quadratic,
            CUBIC: weights_cubic}


@njit
def weights_1d(kind, X, lp):
    """(base, w, dw) for a runtime shape-function code: weights w[k] and derivatives dw[k]
    (per cell unit) of nodes base + k, as 4-tuples (unused entries 0) that live in registers.
    The kernels use `weights_tagged`, which fixes the kind at compile time."""
    if kind == LINEAR:
        return weights_linear(X, lp)
    if kind == QUADRATIC:
        return weights_quadratic(X, lp)
    if kind == CUBIC:
        return weights_cubic(X, lp)
    return weights_gimp(X, lp)


def weights_tagged(kind_tag, X, lp):
    """`weights_1d` with the kind given by `len(kind_tag) - 1`, chosen while Numba types the
    caller so only that shape function is compiled (Python body: NUMBA_DISABLE_JIT=1)."""
    return _WEIGHTS[len(kind_tag) - 1](X, lp)


@overload(weights_tagged, inline="always")
def _weights_tagged_typed(kind_tag, X, lp):
    fn = _WEIGHTS[len(kind_tag.types) - 1]

    def impl(kind_tag, X, lp):
        return fn(X, lp)
    return impl


@njit(inline="always")
def axis_weights(kind_tag, dim, a, xp, origin, inv_dx, lp):
    """(base, count, w, dw) along axis `a`; axes beyond `dim` get one node of weight 1.

    Letting the unused axes have a single node of weight 1 and derivative 0 lets one triple
    loop serve 1D, 2D and 3D.
    """
    if a < dim:
        X = (xp[a] - origin[a]) * inv_dx + 2.0  # + GRID_PAD
        base, w, dw = weights_tagged(kind_tag, X, lp)
        return base, stencil_width(len(kind_tag) - 1), w, dw
    return 0, 1, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0)


@njit(inline="always")
def particle_stencil(kind_tag, dim, x, lp, p, origin, inv_dx, st):
    """Stencil of particle p: (base node, nodes per axis n0-n2, weights w0-w2, derivatives
    d0-d2), the prologue P2G and G2P share. `lp` (GIMP half-widths) may be None."""
    lp0 = lp1 = lp2 = 0.5
    if lp is not None:
        lp0 = lp[p, 0]
        lp1 = lp[p, min(1, dim - 1)]
        lp2 = lp[p, min(2, dim - 1)]
    b0, n0, w0, d0 = axis_weights(kind_tag, dim, 0, x[p], origin, inv_dx, lp0)
    b1, n1, w1, d1 = axis_weights(kind_tag, dim, 1, x[p], origin, inv_dx, lp1)
    b2, n2, w2, d2 = axis_weights(kind_tag, dim, 2, x[p], origin, inv_dx, lp2)
    base = b0 * st[0] + b1 * st[1] + b2 * st[2]
    return base, n0, n1, n2, w0, w1, w2, d0, d1, d2


def static_tags(dim, kind):
    """Compile-time constants for the kernels: Numba types a tuple by its length, so
    `len(dim_tag)` and `len(kind_tag) - 1` fold to constants and each (dim, shape function)
    pair gets its own fully specialised machine code (a runtime int costs ~3x here)."""
    return (0,) * dim, (0,) * (kind + 1)
