"""SPH smoothing kernels W(r, h) and dW/dr in 1D/2D/3D, support radius 2h.

Codes: ``CUBIC = 0`` the cubic spline of seed 004, section 2 (Monaghan's M4; 2D factor
10/(7 pi h^2), 1D 2/(3h), 3D 1/(pi h^3)); ``WENDLAND_C2 = 1`` Wendland's C2 function
(1 - q/2)^4 (2q + 1) with 7/(4 pi h^2) in 2D and 21/(16 pi h^3) in 3D, and the 1D C2
function (1 - q/2)^3 (3q/2 + 1) with 5/(8h). q = r/h in both, so both reach 2h.

`kernel_w(kind, dim, r, h)` and `kernel_dwdr(kind, dim, r, h)`; the gradient with respect to
x_a of W(|x_a - x_b|) is dW/dr * (x_a - x_b)/r (zero at r = 0).
"""
import numpy as np

from ...jit import njit

CUBIC = 0
WENDLAND_C2 = 1
KERNELS = {"cubic": CUBIC, "wendland": WENDLAND_C2}
#: support radius in units of h (both kernels)
SUPPORT = 2.0


@njit(inline="always")
def _norm(kind, dim, h):
    if kind == CUBIC:
        if dim == 1:
            return 2.0 / (3.0 * h)
        if dim == 2:
            return 10.0 / (7.0 * np.pi * h * h)
        return 1.0 / (np.pi * h * h * h)
    if dim == 1:
        return 5.0 / (8.0 * h)
    if dim == 2:
        return 7.0 / (4.0 * np.pi * h * h)
    return 21.0 / (16.0 * np.pi * h * h * h)


@njit(inline="always")
def kernel_w(kind, dim, r, h):
    """W(r, h) (seed 004, section 2, for the cubic spline)."""
    q = r / h
    if q >= 2.0:
        return 0.0
    s = _norm(kind, dim, h)
    if kind == CUBIC:
        if q < 1.0:
            return s * (1.0 - 1.5 * q * q + 0.75 * q * q * q)
        t = 2.0 - q
        return s * 0.25 * t * t * t
    t = 1.0 - 0.5 * q
    if dim == 1:
        return s * t * t * t * (1.5 * q + 1.0)
    return s * t * t * t * t * (2.0 * q + 1.0)


@njit(inline="always")
def kernel_dwdr(kind, dim, r, h):
    """dW/dr (<= 0) of `kernel_w`."""
    q = r / h
    if q >= 2.0:
        return 0.0
    s = _norm(kind, dim, h) / h
    if kind == CUBIC:
        if q < 1.0:
            return s * (-3.0 * q + 2.25 * q * q)
        t = 2.0 - q
        return -s * 0.75 * t * t
    t = 1.0 - 0.5 * q
    if dim == 1:
        # d/dq [t^3 (1.5 q + 1)] = -1.5 t^2 (1.5q + 1) + 1.5 t^3 = -3 q t^2
        return -s * 3.0 * q * t * t
    # d/dq [t^4 (2q + 1)] = -2 t^3 (2q + 1) + 2 t^4 = -5 q t^3
    return -s * 5.0 * q * t * t * t


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
