"""The ghost-node exchange's packing (`parallel.grid_halo`): a layer range of the slab axis,
over several grid arrays, into one buffer and back.

A range [lo, hi) of node layers along axis a of a C-ordered local grid is a set of runs of
consecutive flat nodes: `outer` runs (the product of the node counts before a), `stride`
nodes apart (the product of those from a on), each `run` nodes long (hi - lo times the
product of those after a) and starting at node `first` (lo times that product). A grid
array is (fields, nodes[, components]); seen flat as (fields, nodes x components), each run
is one contiguous stretch. The buffer holds, array after array, field after field, the runs
in order: the C order of the numpy view of the same layers, which both ends share.
One compiled call per exchange instead of a numpy copy and a ufunc per array (on strided
views, 2 and 9 us per sum of mass and momentum in `coupled_dam_obstacle`).
"""
import numpy as np

from ..jit import njit

#: what `move_runs` does with a buffer value v and a node's value a: PACK copies a into the
#: buffer; ADD, MAXIMUM (the larger, a NaN counting as missing like np.fmax) and COPY
#: combine v into a
PACK, ADD, MAXIMUM, COPY = 0, 1, 2, 3


@njit
def move_runs(arrays, comps, outer, stride, first, run, buf, mode):
    """Between the runs of every array (flat (fields, nodes x comps[i])) and `buf`, in the
    buffer order of the module docstring: packed into it (PACK) or combined from it."""
    pos = np.uint64(0)
    for i in range(len(arrays)):
        a = arrays[i]
        k = np.uint64(comps[i])
        length = np.uint64(run) * k
        for f in range(a.shape[0]):
            for o in range(outer):
                start = (np.uint64(o) * np.uint64(stride) + np.uint64(first)) * k
                if mode == PACK:
                    for j in range(length):
                        buf[pos + j] = a[f, start + j]
                elif mode == ADD:
                    for j in range(length):
                        a[f, start + j] += buf[pos + j]
                elif mode == MAXIMUM:
                    for j in range(length):
                        v = buf[pos + j]
                        if v > a[f, start + j] or a[f, start + j] != a[f, start + j]:
                            a[f, start + j] = v
                else:
                    for j in range(length):
                        a[f, start + j] = buf[pos + j]
                pos += length
