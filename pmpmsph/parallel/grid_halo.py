"""Ghost nodes of the slab grid: `GridHalo.reduce` and `GridHalo.broadcast` (DESIGN.md §4).

P2G writes into ghost nodes; `reduce` sends every ghost layer's values to the neighbour that
owns those nodes, which adds them in; after the grid update `broadcast` copies the owners'
values back into the ghosts. Afterwards every node a particle touches holds the serial value.
The node ranges (the communication plan) are built once per decomposition, and the send and
receive buffers once per set of arrays exchanged, then reused every step.

`sum` does both in one exchange, and is what the MPM stage uses: each rank sends its partial
sums on every node it shares with a neighbour (its ghosts and the neighbour's ghosts) and adds
what it receives, so owners and ghost holders both end with the full sum (a + b on one side,
b + a on the other: the same double, addition being commutative). The grid update is local to
each node (masses, momenta, forces, boundary conditions, contact), so solving the ghosts too
gives them the owners' values bit for bit, and the broadcast after the update, with its
synchronisation, is not needed. That matters on a shared machine: every synchronisation makes
the rank that got there first wait for the other, and the grid update differs in length
between ranks (their slabs hold different numbers of nodes), so the broadcast's wait was paid
every step even when the balancer had equalised the ranks' total work. DESIGN.md §4 has
reduce-then-broadcast; `sum` gives the same numbers with one synchronisation fewer per pass.
It needs every shared node to be shared by exactly two ranks, which holds when every interior
slab is at least two ghost widths thick; otherwise (`pairwise` False, the same on every rank)
`sum` falls back to `reduce` then `broadcast` of the sums.
"""
import numpy as np

from ..kernels.node_runs import ADD, COPY, MAXIMUM, PACK, move_runs
from .distributor import wait_all

TAG_REDUCE = 11
TAG_BCAST = 12
TAG_SUM = 13


class GridHalo:
    def __init__(self, decomposition, grid):
        self.dec = decomposition
        self.grid = grid
        self.comm = decomposition.dist.comm
        self.axis = decomposition.axis
        off = int(grid.offset[self.axis])
        self.bytes_sent = 0
        self._buffers = {}  # (route name, array ids) -> buffers and views (`_plan`)
        # (neighbour, slice sent, slice received, side of our face) of each exchange, in
        # local node indices, made once: reduce sends the ghosts to their owner, broadcast
        # the owned shared nodes back, sum sends and receives every node shared with the
        # neighbour; on two ranks with a periodic slab axis both faces lead to the other
        # rank, told apart by the side
        self.routes = {"reduce": [], "broadcast": [], "sum": []}
        for side, nb, shift in decomposition.grid_neighbours():
            (g_lo, g_hi), (s_lo, s_hi) = decomposition.overlap(nb, shift)
            ghost = slice(g_lo - off, g_hi - off)
            shared = slice(s_lo - off, s_hi - off)
            both = slice(min(g_lo, s_lo) - off, max(g_hi, s_hi) - off)
            self.routes["reduce"].append((nb, ghost, shared, side))
            self.routes["broadcast"].append((nb, shared, ghost, side))
            self.routes["sum"].append((nb, both, both, side))
        faces, ghost = decomposition.faces, decomposition.ghost
        # no node is local to three ranks: the two ghost layers of an interior slab's
        # neighbours stay apart (decided from the faces, so every rank decides alike); with
        # the wrap every slab is interior
        inner = (range(decomposition.size) if decomposition.wraps
                 else range(1, decomposition.size - 1))
        self.pairwise = all(faces[r + 1] - faces[r] >= 2 * ghost for r in inner)

    def _runs(self, sl):
        """The node layers `sl` (local, along the slab axis) as runs of flat nodes: (outer,
        stride, first, run) of `kernels.node_runs`."""
        shape, a = self.grid.shape, self.axis
        inner = int(np.prod(shape[a + 1:], dtype=np.int64))
        return (int(np.prod(shape[:a], dtype=np.int64)), int(shape[a]) * inner,
                sl.start * inner, (sl.stop - sl.start) * inner)

    def _exchange(self, arrays, name, tag, mode):
        """Send each neighbour the node layers `out` of every array and combine what it sends
        into the layers `in` (`self.routes[name]`: (neighbour, out, in, side) per face) by
        `mode` (`kernels.node_runs`: ADD, MAXIMUM or COPY). Buffers are made once per
        (`name`, arrays) and reused."""
        routes = self.routes[name]
        if not routes:
            return
        flat, comps, plan = self._plan(name, arrays)
        reqs = []
        for (nb, _, _, side), (sendbuf, recvbuf, out_runs, _) in zip(routes, plan):
            move_runs(flat, comps, *out_runs, sendbuf, PACK)
            # tagged with the sender's face: what arrives on our low face left the
            # neighbour's high face
            reqs.append(self.comm.Irecv(recvbuf, source=nb, tag=tag + 100 * (1 - side)))
            reqs.append(self.comm.Isend(sendbuf, dest=nb, tag=tag + 100 * side))
            self.bytes_sent += sendbuf.nbytes
        wait_all(reqs)
        for _, recvbuf, _, in_runs in plan:
            move_runs(flat, comps, *in_runs, recvbuf, mode)

    def _plan(self, name, arrays):
        """(the arrays flat as (fields, nodes x components), their components, and per route
        of `name`: (send buffer, receive buffer, runs sent, runs received)), made once per
        route name and set of arrays and reused (the flat views keep the arrays alive, so
        their ids are not reused while cached; a few sets per name: P2G sums with and
        without forces)."""
        key = (name, tuple(id(a) for a in arrays))
        plan = self._buffers.get(key)
        if plan is None:
            if len(self._buffers) > 16:  # arrays replaced (a new grid): forget the old ones
                self._buffers.clear()
            if not all(a.flags.c_contiguous for a in arrays):  # (the flat views must alias)
                raise ValueError("ghost-node exchange of a non-contiguous array")
            flat = tuple(a.reshape(a.shape[0], -1) for a in arrays)
            comps = np.array([1 if a.ndim == 2 else a.shape[2] for a in arrays], np.int64)
            per_route = []
            for _, out_sl, in_sl, _ in self.routes[name]:
                out_runs, in_runs = self._runs(out_sl), self._runs(in_sl)
                size = sum(a.shape[0] * int(k) for a, k in zip(arrays, comps))
                per_route.append((np.empty(size * out_runs[0] * out_runs[3]),
                                  np.empty(size * in_runs[0] * in_runs[3]), out_runs, in_runs))
            plan = self._buffers[key] = (flat, comps, per_route)
        return plan

    def sum(self, arrays):
        """Full sums on owned and ghost nodes alike, in one exchange (module doc)."""
        if not self.pairwise:
            self.reduce(arrays)
            self.broadcast(arrays)
            return
        self._exchange(arrays, "sum", TAG_SUM, ADD)

    def reduce(self, arrays):
        """Add every ghost node's values into its owner (arrays: nodal accumulators)."""
        self._exchange(arrays, "reduce", TAG_REDUCE, ADD)

    def broadcast(self, arrays):
        """Copy the owners' values into the ghost nodes."""
        self._exchange(arrays, "broadcast", TAG_BCAST, COPY)

    def maximum(self, arrays):
        """The largest value over all ranks on owned and ghost nodes alike (as `sum` sums),
        NaN counting as missing (np.fmax)."""
        if not self.pairwise:
            self._exchange(arrays, "reduce", TAG_REDUCE, MAXIMUM)
            self.broadcast(arrays)
            return
        self._exchange(arrays, "sum", TAG_SUM, MAXIMUM)
