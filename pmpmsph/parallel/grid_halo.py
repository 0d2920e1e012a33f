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

    def _view(self, arr, sl):
        blk = self.grid.block(arr)
        index = [slice(None)] * blk.ndim
        index[1 + self.axis] = sl
        return blk[tuple(index)]

    def _exchange(self, arrays, name, tag, combine):
        """Send each neighbour the node slice `out` of every array and put what it sends into
        the slice `in` (`self.routes[name]`: (neighbour, out, in, side) per face), combined
        with `combine` (a ufunc such as np.add; None: copied). Buffers are made once per
        (`name`, array shapes) and reused."""
        routes = self.routes[name]
        if not routes:
            return
        plan = self._plan(name, arrays)
        reqs = []
        for (nb, _, _, side), (sendbuf, recvbuf, outgoing, _) in zip(routes, plan):
            for view, part in outgoing:
                part[...] = view
            # tagged with the sender's face: what arrives on our low face left the
            # neighbour's high face
            reqs.append(self.comm.Irecv(recvbuf, source=nb, tag=tag + 100 * (1 - side)))
            reqs.append(self.comm.Isend(sendbuf, dest=nb, tag=tag + 100 * side))
            self.bytes_sent += sendbuf.nbytes
        wait_all(reqs)
        for _, _, _, incoming in plan:
            for view, part in incoming:
                if combine is not None:
                    combine(view, part, out=view)
                else:
                    view[...] = part

    def _plan(self, name, arrays):
        """Per route of `name`: (send buffer, receive buffer, [(node slice of an array, its
        part of the send buffer)], the same for the receive buffer), made once per route name
        and set of arrays and reused (the views keep the arrays alive, so their ids are not
        reused while cached; a few sets per name: P2G sums with and without forces)."""
        key = (name, tuple(id(a) for a in arrays))
        plan = self._buffers.get(key)
        if plan is None:
            if len(self._buffers) > 16:  # arrays replaced (a new grid): forget the old ones
                self._buffers.clear()
            plan = []
            for _, out_sl, in_sl, _ in self.routes[name]:
                sides = []
                for sl in (out_sl, in_sl):
                    views = [self._view(a, sl) for a in arrays]
                    buf = np.empty(sum(v.size for v in views))
                    parts, pos = [], 0
                    for v in views:
                        parts.append((v, buf[pos:pos + v.size].reshape(v.shape)))
                        pos += v.size
                    sides.append((buf, parts))
                plan.append((sides[0][0], sides[1][0], sides[0][1], sides[1][1]))
            self._buffers[key] = plan
        return plan

    def sum(self, arrays):
        """Full sums on owned and ghost nodes alike, in one exchange (module doc)."""
        if not self.pairwise:
            self.reduce(arrays)
            self.broadcast(arrays)
            return
        self._exchange(arrays, "sum", TAG_SUM, combine=np.add)

    def reduce(self, arrays):
        """Add every ghost node's values into its owner (arrays: nodal accumulators)."""
        self._exchange(arrays, "reduce", TAG_REDUCE, combine=np.add)

    def broadcast(self, arrays):
        """Copy the owners' values into the ghost nodes."""
        self._exchange(arrays, "broadcast", TAG_BCAST, combine=None)

    def maximum(self, arrays):
        """The largest value over all ranks on owned and ghost nodes alike (as `sum` sums),
        NaN counting as missing (np.fmax)."""
        if not self.pairwise:
            self._exchange(arrays, "reduce", TAG_REDUCE, combine=np.fmax)
            self.broadcast(arrays)
            return
        self._exchange(arrays, "sum", TAG_SUM, combine=np.fmax)
