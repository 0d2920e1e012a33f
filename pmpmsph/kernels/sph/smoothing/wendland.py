"""Wendland's C2 function (Wendland 1995; the "quintic Wendland" of DualSPHysics): with
q = r/h < 2 and t = 1 - q/2, W = 7/(4 pi h^2) t^4 (2q + 1) in 2D, 21/(16 pi h^3) t^4 (2q + 1)
in 3D, and the 1D C2 function 5/(8h) t^3 (3q/2 + 1)."""
import numpy as np

from ....jit import njit
from .registry import SmoothingKernel, register_kernel


@njit(inline="always")
def _norm(dim, h):
    if dim == 1:
        return 5.0 / (8.0 * h)
    if dim == 2:
        return 7.0 / (4.0 * np.pi * h * h)
    return 21.0 / (16.0 * np.pi * h * h * h)


@njit(inline="always")
def w_wendland(dim, r, h):
    q = r / h
    if q >= 2.0:
        return 0.0
    s = _norm(dim, h)
    t = 1.0 - 0.5 * q
    if dim == 1:
        return s * t * t * t * (1.5 * q + 1.0)
    return s * t * t * t * t * (2.0 * q + 1.0)


@njit(inline="always")
def dwdr_wendland(dim, r, h):
    q = r / h
    if q >= 2.0:
        return 0.0
    s = _norm(dim, h) / h
    t = 1.0 - 0.5 * q
    if dim == 1:
        # d/dq [t^3 (1.5 q + 1)] = -1.5 t^2 (1.5q + 1) + 1.5 t^3 = -3 q t^2
        return -s * 3.0 * q * t * t
    # d/dq [t^4 (2q + 1)] = -2 t^3 (2q + 1) + 2 t^4 = -5 q t^3
    return -s * 5.0 * q * t * t * t


register_kernel(SmoothingKernel("wendland", 1, w_wendland, dwdr_wendland))
