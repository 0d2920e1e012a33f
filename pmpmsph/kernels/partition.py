"""Which owned particles left this rank's slab (one pass, no temporaries)."""
import math

import numpy as np

from ..jit import njit


@njit
def slab_leavers(x, axis, origin, inv_dx, ncells, lo_cell, hi_cell):
    """Indices of particles whose cell along `axis` lies outside [lo_cell, hi_cell).

    Cells are clipped to the grid like `Decomposition.cell_of`; NaN positions count as
    staying (the NaN check of G2P reports them).
    """
    n = x.shape[0]
    out = np.empty(n, np.int64)
    k = 0
    for p in range(n):
        c = math.floor((x[p, axis] - origin) * inv_dx)
        if c < 0:
            c = 0
        elif c > ncells - 1:
            c = ncells - 1
        if c < lo_cell or c >= hi_cell:
            out[k] = p
            k += 1
    return out[:k]


@njit
def max_abs_column(v, axis, n):
    """max |v[p, axis]| over the rows [0, n) (0 for none; NaN propagates)."""
    m = 0.0
    for p in range(n):
        a = abs(v[p, axis])
        if not a <= m:
            m = a
    return m


@njit
def max_stray(x, axis, lo, hi, n):
    """How far the farthest of the rows [0, n) lies outside [lo, hi] along `axis` (0 when
    all are inside; NaN propagates)."""
    m = 0.0
    for p in range(n):
        a = max(lo - x[p, axis], x[p, axis] - hi)
        if not a <= m:
            m = a
    return m


@njit
def column_extent(x, n):
    """(min, max) of x[p, 0] over the rows [0, n) (n > 0); a NaN gives NaN."""
    lo = x[0, 0]
    hi = x[0, 0]
    nan = 0.0  # a - a is 0, or NaN for NaN and inf: no branch, so the loop vectorises
    for p in range(1, n):
        a = x[p, 0]
        lo = min(lo, a)
        hi = max(hi, a)
        nan += a - a
    return lo + nan, hi + nan


@njit
def cell_keys(x, origin, inv_dx, strides):
    """Linear cell index of each particle (C order over the grid), for sorting by cell."""
    n, dim = x.shape
    keys = np.empty(n, np.int64)
    for p in range(n):
        k = 0
        for a in range(dim):
            k += int(math.floor((x[p, a] - origin[a]) * inv_dx)) * strides[a]
        keys[p] = k
    return keys


@njit
def gather_rows(views, index, out):
    """Pack rows `index` of several fields side by side: `views` are the fields as (rows,
    bytes per row) uint8 arrays (`ParticleSet.byte_views`), `out` is (len(index), their total
    bytes). One compiled pass instead of a fancy-indexed copy per field (the halo refresh
    and migration pack a dozen fields two or three times a step).

    The indices are unsigned: with signed ones Numba adds the wrap-around of negative
    indices to every byte, which keeps LLVM from vectorising the copy (5x slower: 22 us
    against 4 us for a refresh of 132 rows of 216 bytes)."""
    pos = np.uint64(0)
    for view in views:
        width = np.uint64(view.shape[1])
        for r in range(index.shape[0]):
            src = np.uint64(index[r])
            row = np.uint64(r)
            for b in range(width):
                out[row, pos + b] = view[src, b]
        pos += width


@njit
def scatter_rows(views, first, rows):
    """The inverse of `gather_rows` into consecutive rows: packed row r goes to row
    first + r of every field (unsigned indices, as there)."""
    pos = np.uint64(0)
    for view in views:
        width = np.uint64(view.shape[1])
        for r in range(rows.shape[0]):
            dst = np.uint64(first + r)
            row = np.uint64(r)
            for b in range(width):
                view[dst, b] = rows[row, pos + b]
        pos += width
