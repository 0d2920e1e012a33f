"""Cell-list neighbour search (DESIGN.md §3, step 3).

`neighbour_lists(x, n_query, radius)` bins all rows of `x` (owned then halo) into cells of
side `radius`, then lists for each of the first `n_query` rows every row within `radius`
(itself included: corrected kernels and summation densities need the self term) as CSR
arrays `start[n_query + 1]`, `index[start[-1]]`. Within a row the neighbours come in cell
order and, within a cell, in row order, so a list depends only on positions and row order.
"""
import numpy as np

from ..jit import njit


@njit
def _bin(x, n, dim, lo, inv, ncell):
    """Counting sort of rows into cells: (cell start offsets, rows ordered by cell)."""
    cell = np.empty(n, np.int64)
    for i in range(n):
        c = 0
        for a in range(dim - 1, -1, -1):
            k = int((x[i, a] - lo[a]) * inv)
            if k < 0:
                k = 0
            elif k >= ncell[a]:
                k = ncell[a] - 1
            c = c * ncell[a] + k
        cell[i] = c
    total = 1
    for a in range(dim):
        total *= ncell[a]
    head = np.zeros(total + 1, np.int64)
    for i in range(n):
        head[cell[i] + 1] += 1
    for c in range(total):
        head[c + 1] += head[c]
    fill = head[:-1].copy()
    order = np.empty(n, np.int64)
    for i in range(n):
        order[fill[cell[i]]] = i
        fill[cell[i]] += 1
    return head, order


@njit
def _scan(x, xs, n_query, dim, lo, inv, ncell, head, order, r2, start, index, count_only,
          half):
    """Count (count_only) or write the neighbours of the first n_query rows."""
    total = 0
    for i in range(n_query):
        k0 = min(max(int((x[i, 0] - lo[0]) * inv), 0), ncell[0] - 1)
        k1 = min(max(int((x[i, 1] - lo[1]) * inv), 0), ncell[1] - 1) if dim > 1 else 0
        k2 = min(max(int((x[i, 2] - lo[2]) * inv), 0), ncell[2] - 1) if dim > 2 else 0
        if not count_only:
            total = start[i]
        found = 0
        lo2 = max(k2 - 1, 0)
        hi2 = min(k2 + 1, ncell[2] - 1)
        lo1 = max(k1 - 1, 0)
        hi1 = min(k1 + 1, ncell[1] - 1)
        lo0 = max(k0 - 1, 0)
        hi0 = min(k0 + 1, ncell[0] - 1)
        for c2 in range(lo2, hi2 + 1):
            for c1 in range(lo1, hi1 + 1):
                # the cells c0 = lo0..hi0 of one row are contiguous in the sorted order
                c_lo = lo0 + ncell[0] * (c1 + ncell[1] * c2)
                c_hi = hi0 + ncell[0] * (c1 + ncell[1] * c2)
                for s in range(head[c_lo], head[c_hi + 1]):
                    if half and order[s] <= i:
                        continue
                    d2 = 0.0
                    for a in range(dim):
                        d = x[i, a] - xs[s, a]
                        d2 += d * d
                    if d2 < r2:
                        if not count_only:
                            index[total + found] = order[s]
                        found += 1
        if count_only:
            start[i + 1] = start[i] + found
    return start[n_query] if count_only else 0


def neighbour_lists(x, n_query, radius, half=False):
    """CSR neighbour lists (start, index) of rows [0, n_query) among all rows of x. With
    `half`, row i lists only rows j > i (each pair among the query rows once; every pair
    with a later row, e.g. a halo row, in the query row's list), for pair-symmetric loops."""
    x = np.ascontiguousarray(x)
    n, dim = x.shape
    start = np.zeros(n_query + 1, np.int64)
    if n == 0:
        return start, np.zeros(0, np.int64)
    lo = x.min(axis=0) - 1e-12 * radius
    span = x.max(axis=0) - lo
    cell = radius
    while True:  # cells of side >= radius; coarser if the box is mostly empty
        ncell = np.maximum(np.floor(span / cell).astype(np.int64) + 1, 1)
        if np.prod(ncell.astype(float)) <= max(8.0 * n, 4096.0):
            break
        cell *= 2.0
    ncell = np.concatenate([ncell, np.ones(3 - dim, np.int64)])
    inv = 1.0 / cell
    head, order = _bin(x, n, dim, lo, inv, ncell)
    xs = x[order]  # positions in cell order: the candidate scans read memory contiguously
    npairs = _scan(x, xs, n_query, dim, lo, inv, ncell, head, order, radius * radius, start,
                   np.zeros(0, np.int64), True, half)
    index = np.empty(npairs, np.int64)
    _scan(x, xs, n_query, dim, lo, inv, ncell, head, order, radius * radius, start, index,
          False, half)
    return start, index


@njit
def moved_beyond(x, x_ref, distance):
    """True if any row of x lies farther than `distance` from the same row of x_ref."""
    d2 = distance * distance
    for i in range(x.shape[0]):
        s = 0.0
        for a in range(x.shape[1]):
            d = x[i, a] - x_ref[i, a]
            s += d * d
        if s > d2:
            return True
    return False
