"""MPM shape functions as tensor products of 1-D weights, and the per-particle stencil.

The shape functions are registered one module each in `kernels.mpm.shape_functions`
(linear hat, uniform GIMP, quadratic and cubic B-splines, CPDI1); this module generates
from that registry the switches the transfers call and builds the stencils:
  `weights_1d(kind, X, lp)`          (base, w, dw) of the 1-D weights at X, runtime kind
  `weights_tagged(kind_tag, X, lp)`  the same with the kind fixed at compile time
  `stencil_width(kind)`              nodes per axis of one stencil
  `apic_d_inverse(kind)`             APIC's constant D^-1 dx^2 (0: summed per particle)
CPDI (convected particle domain interpolation, CPDI1, Sadeghirad, Brannon & Burghardt
2011) averages linear hats over the particle's domain, the parallelogram (parallelepiped)
of half-edges r_a = F lp_a e_a, from its 2^dim corners (`corner_stencil`).
All coordinates here are in cell units: X = (x - origin)/dx with `origin` the position of
global (padded) node 0 (`Grid.node0`), so global node i sits at X = i; a rank's local node
index is the global one minus its grid's `offset`. Weights come from the global X, so they
are the same bits on every rank whatever the slab.
"""
import math

import numpy as np
from numba.extending import overload

from ...jit import code_switch, njit
from ...materials.tensor import cofactor3
from .shape_functions.cpdi import CPDI
from .shape_functions.registry import shape_functions, shape_named

_SHAPES = shape_functions()
LINEAR, GIMP, QUADRATIC, CUBIC = (shape_named(n).code
                                  for n in ("linear", "gimp", "quadratic", "cubic"))
SHAPE_CODES = {s.name: s.code for s in _SHAPES}
#: nodes per axis touched by one stencil (for CPDI: by each of the 2^dim corners)
STENCIL_WIDTH = {s.code: s.width for s in _SHAPES}
_WEIGHTS = {s.code: s.weights for s in _SHAPES}


@njit(inline="always")
def _unknown_shape():
    raise ValueError("unknown shape function code")


stencil_width = code_switch("stencil_width", "", STENCIL_WIDTH, "return 0")
apic_d_inverse = code_switch("apic_d_inverse", "", {s.code: float(s.apic_d_inverse)
                                                     for s in _SHAPES}, "return 0.0")
#: (base, w, dw) for a runtime shape-function code: weights w[k] and derivatives dw[k] (per
#: cell unit) of nodes base + k, as 4-tuples (unused entries 0) that live in registers. The
#: kernels use `weights_tagged`, which fixes the kind at compile time.
weights_1d = code_switch("weights_1d", "X, lp", _WEIGHTS, "_unknown_shape()",
                         _unknown_shape=_unknown_shape)


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
        X = (xp[a] - origin[a]) * inv_dx
        base, w, dw = weights_tagged(kind_tag, X, lp)
        return base, stencil_width(len(kind_tag) - 1), w, dw
    return 0, 1, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0)


@njit(inline="always")
def particle_stencil(kind_tag, dim, x, lp, p, origin, inv_dx, st, off):
    """Stencil of particle p: (local base node, nodes per axis n0-n2, weights w0-w2,
    derivatives d0-d2), the prologue P2G and G2P share. `lp` (GIMP half-widths) may be None;
    `off` is the global index of local node 0 per axis."""
    lp0 = lp1 = lp2 = 0.5
    if lp is not None:
        lp0 = lp[p, 0]
        lp1 = lp[p, min(1, dim - 1)]
        lp2 = lp[p, min(2, dim - 1)]
    b0, n0, w0, d0 = axis_weights(kind_tag, dim, 0, x[p], origin, inv_dx, lp0)
    b1, n1, w1, d1 = axis_weights(kind_tag, dim, 1, x[p], origin, inv_dx, lp1)
    b2, n2, w2, d2 = axis_weights(kind_tag, dim, 2, x[p], origin, inv_dx, lp2)
    base = (b0 - off[0]) * st[0] + (b1 - off[1]) * st[1] + (b2 - off[2]) * st[2]
    return base, n0, n1, n2, w0, w1, w2, d0, d1, d2


def n_corners(kind_tag, dim):
    """Stencils per particle: 2^dim domain corners for CPDI, else one (compile-time)."""
    return 2 ** dim if len(kind_tag) - 1 == CPDI else 1


@overload(n_corners, inline="always")
def _n_corners_typed(kind_tag, dim):
    if len(kind_tag.types) - 1 == CPDI:
        return lambda kind_tag, dim: 1 << dim
    return lambda kind_tag, dim: 1


@njit(inline="always")
def cpdi_domain(dim, F, lp, p, dom):
    """The CPDI1 domain of particle p in cell units: dom[0] = R = F diag(lp), whose columns
    are the half-edges r_a, and dom[1] = G = F^-T diag(1/lp) (in-plane block of F).

    With x = x_p + sum_a xi_a r_a, xi in [-1, 1]^dim, the domain average of the gradient of
    the multilinear interpolant of a nodal shape function S_I through the corner values is
    2^-dim G sum_c s_c S_I(x_c) (s_c the corner's signs), because the integral of the
    gradient of the corner's multilinear function over the reference cube is s_c and the
    map has the constant Jacobian R; its domain average is 2^-dim sum_c S_I(x_c). Both
    sum to a partition of unity (the gradients to zero). Sadeghirad et al. 2011, eqs. 29-30.
    """
    if dim == 1:
        dom[0, 0, 0] = F[p, 0, 0] * lp[p, 0]
        dom[1, 0, 0] = 1.0 / (F[p, 0, 0] * lp[p, 0])
        return
    if dim == 2:
        a, b, c, d = F[p, 0, 0], F[p, 0, 1], F[p, 1, 0], F[p, 1, 1]
        inv_det = 1.0 / (a * d - b * c)
        # F^-T = [[d, -c], [-b, a]] / det
        dom[1, 0, 0] = d * inv_det / lp[p, 0]
        dom[1, 0, 1] = -c * inv_det / lp[p, 1]
        dom[1, 1, 0] = -b * inv_det / lp[p, 0]
        dom[1, 1, 1] = a * inv_det / lp[p, 1]
    else:
        f = F[p]
        # F^-T = cof(F) / det F
        c00, c01, c02, c10, c11, c12, c20, c21, c22 = cofactor3(f)
        inv_det = 1.0 / (f[0, 0] * c00 + f[0, 1] * c01 + f[0, 2] * c02)
        dom[1, 0, 0] = c00 * inv_det / lp[p, 0]
        dom[1, 0, 1] = c01 * inv_det / lp[p, 1]
        dom[1, 0, 2] = c02 * inv_det / lp[p, 2]
        dom[1, 1, 0] = c10 * inv_det / lp[p, 0]
        dom[1, 1, 1] = c11 * inv_det / lp[p, 1]
        dom[1, 1, 2] = c12 * inv_det / lp[p, 2]
        dom[1, 2, 0] = c20 * inv_det / lp[p, 0]
        dom[1, 2, 1] = c21 * inv_det / lp[p, 1]
        dom[1, 2, 2] = c22 * inv_det / lp[p, 2]
    for a in range(dim):
        for b in range(dim):
            dom[0, a, b] = F[p, a, b] * lp[p, b]


@njit(inline="always")
def cpdi_reach(dim, F, lp, p):
    """Largest half-extent (cells) along an axis of the CPDI domain F diag(lp) of particle p:
    max_a sum_b |F_ab| lp_b (F a 3x3 array)."""
    reach = 0.0
    for a in range(dim):
        r = 0.0
        for b in range(dim):
            r += abs(F[a, b]) * lp[p, b]
        reach = max(reach, r)
    return reach


@njit(inline="always")
def _corner_axis(dim, a, c, xp, origin, inv_dx, dom, off, nax):
    """(base, count, w, dw) along axis `a` for corner c of a CPDI domain: linear hats at the
    corner, dw = w times the corner's gradient factor (G s_c)_a. The corner is clamped into
    the stored nodes so a domain grown past the grid's reach (`mpm.cpdi_reach`) in one step
    cannot write outside the arrays (G2P reports such a particle)."""
    if a >= dim:
        return 0, 1, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0)
    X = (xp[a] - origin[a]) * inv_dx
    gc = 0.0
    for b in range(dim):
        s = 1.0 if (c >> b) & 1 else -1.0
        X += s * dom[0, a, b]
        gc += s * dom[1, a, b]
    X = min(max(X, float(off[a])), off[a] + nax[a] - 1.000001)
    base = math.floor(X)
    f = X - base
    scale = 1.0 / (1 << dim) if a == 0 else 1.0  # the corner average's 2^-dim, on one axis
    w0 = (1.0 - f) * scale
    w1 = f * scale
    return base, 2, (w0, w1, 0.0, 0.0), (w0 * gc, w1 * gc, 0.0, 0.0)


@njit(inline="always")
def corner_stencil(dim, x, dom, p, c, origin, inv_dx, st, off, nax):
    """Stencil of corner c of particle p's CPDI domain, in the form of `particle_stencil`:
    the products of w give 2^-dim S_I(x_c) and those with one dw the matching term of the
    gradient, so P2G and G2P sum corner stencils exactly as they sum one particle stencil."""
    b0, n0, w0, d0 = _corner_axis(dim, 0, c, x[p], origin, inv_dx, dom, off, nax)
    b1, n1, w1, d1 = _corner_axis(dim, 1, c, x[p], origin, inv_dx, dom, off, nax)
    b2, n2, w2, d2 = _corner_axis(dim, 2, c, x[p], origin, inv_dx, dom, off, nax)
    base = (b0 - off[0]) * st[0] + (b1 - off[1]) * st[1] + (b2 - off[2]) * st[2]
    return base, n0, n1, n2, w0, w1, w2, d0, d1, d2


@njit(inline="always")
def stencil(kind_tag, dim, x, lp, F, dom, p, c, origin, inv_dx, st, off, nax):
    """Stencil c of particle p: a CPDI corner (`dom` filled by `cpdi_domain` from F) or,
    for the other shape functions, the particle's own stencil (c = 0)."""
    if F is not None and len(kind_tag) - 1 == CPDI:
        return corner_stencil(dim, x, dom, p, c, origin, inv_dx, st, off, nax)
    return particle_stencil(kind_tag, dim, x, lp, p, origin, inv_dx, st, off)


@njit
def local_layout(dim, strides, offset, n_nodes):
    """(strides, offset, nodes per axis) of a local grid padded to 3 axes (unused axes: 0, 0,
    1), the form the stencils take (`particle_stencil`)."""
    st = np.zeros(3, np.int64)
    st[:dim] = strides
    off = np.zeros(3, np.int64)
    off[:dim] = offset
    return st, off, node_counts(dim, strides, n_nodes)


@njit(inline="always")
def node_counts(dim, strides, n_nodes):
    """Nodes per axis of the local grid (3 entries, 1 beyond dim) from its C-order strides."""
    nax = np.ones(3, np.int64)
    nax[0] = n_nodes // strides[0]
    for a in range(1, dim):
        nax[a] = strides[a - 1] // strides[a]
    return nax


def static_tags(dim, kind):
    """Compile-time constants for the kernels: Numba types a tuple by its length, so
    `len(dim_tag)` and `len(kind_tag) - 1` fold to constants and each (dim, shape function)
    pair gets its own fully specialised machine code (a runtime int costs ~3x here)."""
    return (0,) * dim, (0,) * (kind + 1)
