"""Load balancing: move slab faces by whole cells towards equal work (DESIGN.md §4).

Work of a cell layer along the slab axis = the sum of its particles' costs + NODE_COST x its
grid nodes, in units of one MPM point's step (P2G + G2P). A particle's cost depends on its
method (PARTICLE_COST): an SPH particle's pair loops cost 2.7 MPM points, a dummy wall
particle's 1.4 (it takes part in the pair loops without rates of its own). Counting every
particle alike put the free surface's SPH water on one rank and the floor's walls and the
MPM obstacle on the other in `coupled_dam_obstacle`: 2.5 ms of the SPH stage's 19 ms per
step apart. NODE_COST is the cost of a grid node, measured with `python -m pmpmsph.bench`
(grid solve + reset + halo per node against P2G + G2P per particle: about 0.05-0.1; 0.1 is
used). Every `every` steps the global layer histogram is reduced; if
the most loaded rank exceeds the mean by more than `threshold`, new faces are placed at the
quantiles of the cumulative work and kept only if they cut the imbalance at least in half
(hysteresis: a balanced partition never flips back and forth). Deterministic: every rank
computes the same faces from the same global histogram.

With `[parallel] balance_by = "time"` the model is calibrated by what each rank measured:
every rank's compute time since the last check (its stages' kernels, not the waiting in
halo exchanges) divided by its modelled work gives its seconds per work unit, each layer's
work is scaled by its owner's, and the faces go to the quantiles of that. Ranks that run
slower per particle (a busier core, worse cache locality) then get fewer particles; the
imbalance tested against the threshold is the measured one. The faces then depend on
timings, so runs are no longer bit-for-bit repeatable (only equal to round-off). A marginal
measured imbalance (below CONFIRM_BELOW x threshold) must be seen at two checks in a row,
with the same rank the most loaded, before faces move: one window's timing noise (a busy
spell of the machine) then does not move them back and forth, and each move costs a grid
rebuild and a migration. A larger one (a core that runs much slower, as the virtual cores
of a shared host do for seconds at a time) moves them at once.
"""
import numpy as np


NODE_COST = 0.1
#: a particle's step cost by method code (codes.METHOD_CODES: mpm, sph, wall) in MPM points,
#: measured on one rank of `bench scaling --scene coupled_dam --spacing 0.0033` (3,630 MPM
#: points 0.26 us each, 45,753 SPH water 0.70 us, walls 0.36 us from 5,912 more of them)
PARTICLE_COST = np.array([1.0, 2.7, 1.4])
#: measured imbalances below this multiple of the threshold wait for a second check
CONFIRM_BELOW = 3.0


def layer_work(dec, x, nodes_per_layer, method=None):
    """Global work of each cell layer along the slab axis (same array on every rank);
    `method`: the particles' method codes (None: all MPM points)."""
    weights = None if method is None else PARTICLE_COST[method]
    counts = np.bincount(dec.cell_of(x), weights=weights,
                         minlength=dec.ncells).astype(np.float64)
    counts = dec.dist.sum(counts)
    return counts + NODE_COST * nodes_per_layer


def rank_work(faces, work):
    return np.array([work[faces[r]:faces[r + 1]].sum() for r in range(len(faces) - 1)])


def imbalance(faces, work):
    w = rank_work(faces, work)
    return w.max() / max(w.mean(), 1e-300) - 1.0


def balanced_faces(work, size, min_width):
    """Faces at the quantiles of cumulative work, each slab at least `min_width` cells."""
    n = len(work)
    cum = np.concatenate([[0.0], np.cumsum(work)])
    faces = [0]
    for r in range(1, size):
        target = cum[-1] * r / size
        f = int(np.argmin(np.abs(cum - target)))
        lo = faces[-1] + min_width
        hi = n - (size - r) * min_width
        faces.append(min(max(f, lo), hi))
    faces.append(n)
    return np.array(faces, dtype=np.int64)


def calibrated_work(faces, work, busy):
    """Layer work scaled by its owner's measured seconds per modelled work unit (ranks
    without work take the mean rate), so that each rank's total equals its busy time."""
    modelled = rank_work(faces, work)
    busy = np.asarray(busy, dtype=np.float64)
    ok = (modelled > 0) & (busy > 0)
    if not np.any(ok):
        return work
    rate = np.full(len(modelled), busy[ok].sum() / modelled[ok].sum())
    rate[ok] = busy[ok] / modelled[ok]
    scaled = work.copy()
    for r in range(len(modelled)):
        scaled[faces[r]:faces[r + 1]] *= rate[r]
    return scaled


class LoadBalancer:
    def __init__(self, every, threshold):
        self.every = every
        self.threshold = threshold
        self.history = []  # (step, imbalance before, imbalance after, faces)
        self._heaviest = None  # most loaded rank at the last measured check over threshold

    def propose(self, dec, x, nodes_per_layer, busy=None, method=None):
        """New faces, or None to keep the present ones; collective (all ranks call it).
        `busy`: every rank's measured compute seconds since the last check (balance_by =
        "time"), the same array on every rank; None balances the modelled work. `method`: the
        particles' method codes (their costs, PARTICLE_COST)."""
        work = layer_work(dec, x, nodes_per_layer, method)
        if busy is not None:
            work = calibrated_work(dec.faces, work, busy)
        before = imbalance(dec.faces, work)
        if before <= self.threshold:
            self._heaviest = None
            return None, before, before
        if busy is not None:  # measured: a marginal imbalance is confirmed first (module doc)
            heaviest = int(np.argmax(rank_work(dec.faces, work)))
            confirmed = (heaviest == self._heaviest
                         or before >= CONFIRM_BELOW * self.threshold)
            self._heaviest = None if confirmed else heaviest
            if not confirmed:
                return None, before, before
        faces = balanced_faces(work, dec.size, dec.min_slab)
        after = imbalance(faces, work)
        if np.array_equal(faces, dec.faces) or after > 0.5 * before:
            return None, before, before
        return faces, before, after
