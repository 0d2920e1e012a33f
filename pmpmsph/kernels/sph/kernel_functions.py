"""SPH smoothing kernels W(r, h) and dW/dr in 1D/2D/3D, support radius 2h: the switch over
the registered kernels (`kernels.sph.smoothing`, one module each: `cubic` the cubic spline
of seed 004 section 2, `wendland` Wendland's C2, `wendland_c4` Wendland's C4).

`kernel_w(kind, dim, r, h)` and `kernel_dwdr(kind, dim, r, h)` (kind: the kernel's code;
the callers pass it as a compile-time constant, `len(kern_tag) - 1`, so the chain folds
to one kernel); the gradient with respect to x_a of W(|x_a - x_b|) is
dW/dr * (x_a - x_b)/r (zero at r = 0). An unknown code gives NaN.
"""
import numpy as np

from ...jit import code_switch, njit
from .smoothing.registry import SUPPORT, smoothing_kernels

__all__ = ["SUPPORT", "kernel_w", "kernel_dwdr", "pair_gradient"]

kernel_w = code_switch("kernel_w", "dim, r, h", {k.code: k.w for k in smoothing_kernels()},
                       "return np.nan", np=np)
kernel_dwdr = code_switch("kernel_dwdr", "dim, r, h",
                          {k.code: k.dwdr for k in smoothing_kernels()}, "return np.nan",
                          np=np)


@njit(inline="always")
def pair_gradient(kind, dim, x, a, b, h):
    """(x_ab components, fr) of rows a and b: x_ab = x_a - x_b and fr = W'(r) / r, so that
    grad_a W_ab = fr x_ab; fr = 0 when the pair is outside the support 2h or coincident (the
    neighbour loops skip it)."""
    xab0 = x[a, 0] - x[b, 0]
    xab1 = x[a, 1] - x[b, 1] if dim > 1 else 0.0
    xab2 = x[a, 2] - x[b, 2] if dim > 2 else 0.0
    r2 = xab0 * xab0 + xab1 * xab1 + xab2 * xab2
    if r2 >= 4.0 * h * h or r2 == 0.0:
        return xab0, xab1, xab2, 0.0
    r = np.sqrt(r2)
    return xab0, xab1, xab2, kernel_dwdr(kind, dim, r, h) / r
