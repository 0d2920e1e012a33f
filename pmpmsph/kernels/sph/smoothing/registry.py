"""The SPH smoothing-kernel registry: a kernel's module ends with

    register_kernel(SmoothingKernel("wendland", 1, w_wendland, dwdr_wendland))

(name in the case file's `[sph] kernel`, a stable code, W(dim, r, h) and dW/dr(dim, r, h)),
and `kernels.sph.kernel_functions` generates the switch the SPH kernels call from it,
as `[sph] kernel`'s choice list is (`config.case.SPH_KERNELS`). Every kernel reaches 2h
(`SUPPORT`): the neighbour search and the halo widths are built on it.

`smoothing_kernels()` imports every module of this package that is not this one, so a new
kernel is one new file (and its test). Plain Python: importing it does not import numba.
"""
from dataclasses import dataclass

from ....plugins import Registry

#: support radius in units of h (every registered kernel)
SUPPORT = 2.0


@dataclass(frozen=True)
class SmoothingKernel:
    """name: `[sph] kernel` value; code: the integer the compiled kernels switch on;
    w(dim, r, h): W, zero from r = 2h; dwdr(dim, r, h): dW/dr (<= 0)."""

    name: str
    code: int
    w: object
    dwdr: object


_KERNELS = Registry("SPH kernel", __package__, __file__)
#: add a kernel (its code and name must be new); the registered kernels in code order
register_kernel, smoothing_kernels = _KERNELS.register, _KERNELS.entries


def kernel_code(name):
    """The code of the kernel called `name` (KeyError if none is)."""
    return _KERNELS.named(name).code
