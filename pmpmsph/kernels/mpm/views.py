"""The bundles the MPM transfer kernels take instead of long argument lists.

A bundle is a plain tuple that a kernel unpacks on entry (free in the machine code), built by
one of the functions below, which name its members in order (plain tuples, not `NamedTuple`s,
for the dispatch cost: kernels/sph/views.py). Parts a scene may lack (external forces,
GIMP/CPDI half-widths, CPDI's deformation, the field of each particle, pre-stress, the grid's
force or mass gradients, the FLIP increments) stay separate arguments that are `None` when
absent: Numba prunes a branch on `arg is None` at compile time only for a function's own
arguments, not for a tuple's members, and the transfers' inner loops rely on that pruning.
"""
import numpy as np


def grid_layout(origin, offset, inv_dx, strides, lo, hi):
    """Where a rank's nodes are (`Grid.layout`): `origin` the position of global (padded)
    node 0, `offset` the global index of local node 0 per axis, 1/dx, the flat `strides` of
    the local node array, and the box [lo, hi] particles must stay in."""
    return (origin, offset, float(inv_dx), strides, lo, hi)


def scatter_points(x, v, mass, vol, sigma, C=None):
    """What P2G reads of each particle: position, velocity, mass, volume, Cauchy stress and
    (affine transfers only; empty otherwise) the affine velocity matrix C."""
    return (x, v, mass, vol, sigma, NO_AFFINE if C is None else C)


def gather_points(x, v, sigma, vol, vol0, mat, mstate):
    """What G2P updates of each particle (position, velocity, stress, volume) and reads
    (reference volume, material index, material state)."""
    return (x, v, sigma, vol, vol0, mat, mstate)


def material_table(tag, types, params):
    """The materials: `tag` (`material_tag`: the one type code of every particle, fixed at
    compile time, or () for a mixed scene), type code and parameters per material."""
    return (tag, types, params)


def gather_options(dt, flip, pic_tag, max_reach, want_signal):
    """The step of a G2P: dt, the FLIP fraction, `pic_tag` ((0,) for pure PIC, fixed at
    compile time), the largest CPDI domain in cells, and whether to return the CFL
    signal."""
    return (float(dt), float(flip), pic_tag, float(max_reach), bool(want_signal))


#: the `C` of `scatter_points` for a transfer without affine velocities (never read)
NO_AFFINE = np.zeros((0, 3, 3))
