"""The cubic spline of seed 004, section 2 (Monaghan's M4): with q = r/h < 2,
W = s (1 - 3/2 q^2 + 3/4 q^3) for q < 1, s/4 (2 - q)^3 beyond, s = 2/(3h) in 1D,
10/(7 pi h^2) in 2D, 1/(pi h^3) in 3D."""
import numpy as np

from ....jit import njit
from .registry import SmoothingKernel, register_kernel


@njit(inline="always")
def _norm(dim, h):
    if dim == 1:
        return 2.0 / (3.0 * h)
    if dim == 2:
        return 10.0 / (7.0 * np.pi * h * h)
    return 1.0 / (np.pi * h * h * h)


@njit(inline="always")
def w_cubic(dim, r, h):
    q = r / h
    if q >= 2.0:
        return 0.0
    s = _norm(dim, h)
    if q < 1.0:
        return s * (1.0 - 1.5 * q * q + 0.75 * q * q * q)
    t = 2.0 - q
    return s * 0.25 * t * t * t


@njit(inline="always")
def dwdr_cubic(dim, r, h):
    q = r / h
    if q >= 2.0:
        return 0.0
    s = _norm(dim, h) / h
    if q < 1.0:
        return s * (-3.0 * q + 2.25 * q * q)
    t = 2.0 - q
    return -s * 0.75 * t * t


register_kernel(SmoothingKernel("cubic", 0, w_cubic, dwdr_cubic))
