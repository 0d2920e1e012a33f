"""Wendland's C4 function (Wendland 1995; Dehnen & Aly 2012, table 1, with their support
H = 2h): with q = r/h < 2 and t = 1 - q/2,
    2D  W = 9/(4 pi h^2)      t^6 (1 + 3 q + 35/12 q^2)
    3D  W = 495/(256 pi h^3)  t^6 (1 + 3 q + 35/12 q^2)
    1D  W = 3/(4h)            t^5 (1 + 5/2 q + 2 q^2).
Smoother than C2 and, per Dehnen & Aly, free of the pairing instability at larger
neighbour numbers (h of 1.5-2 spacings). Added as one file through the registry
(`registry.py`) to show that a kernel needs nothing else."""
import numpy as np

from ....jit import njit
from .registry import SmoothingKernel, register_kernel


@njit(inline="always")
def _norm(dim, h):
    if dim == 1:
        return 3.0 / (4.0 * h)
    if dim == 2:
        return 9.0 / (4.0 * np.pi * h * h)
    return 495.0 / (256.0 * np.pi * h * h * h)


@njit(inline="always")
def w_wendland_c4(dim, r, h):
    q = r / h
    if q >= 2.0:
        return 0.0
    s = _norm(dim, h)
    t = 1.0 - 0.5 * q
    t2 = t * t
    if dim == 1:
        return s * t2 * t2 * t * (1.0 + 2.5 * q + 2.0 * q * q)
    return s * t2 * t2 * t2 * (1.0 + 3.0 * q + 35.0 / 12.0 * q * q)


@njit(inline="always")
def dwdr_wendland_c4(dim, r, h):
    q = r / h
    if q >= 2.0:
        return 0.0
    s = _norm(dim, h) / h
    t = 1.0 - 0.5 * q
    t2 = t * t
    if dim == 1:
        # d/dq [t^5 (1 + 5q/2 + 2q^2)] = -7/2 q (1 + 2q) t^4
        return -s * 3.5 * q * (1.0 + 2.0 * q) * t2 * t2
    # d/dq [t^6 (1 + 3q + 35/12 q^2)] = -14/3 q (1 + 5q/2) t^5
    return -s * (14.0 / 3.0) * q * (1.0 + 2.5 * q) * t2 * t2 * t


register_kernel(SmoothingKernel("wendland_c4", 2, w_wendland_c4, dwdr_wendland_c4))
