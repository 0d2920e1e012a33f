"""The one object that owns MPI (Dedalus style): every other module asks it.

`Distributor(comm)` wraps an mpi4py communicator and offers the few collective operations the
solver needs on plain numbers and numpy arrays. It is the only place outside `parallel/`
that touches mpi4py, and user code never sees a communicator.
"""
import os

import numpy as np

from ..errors import ConfigError

#: the points before step 1 where the ranks agree on bad input (`Distributor.agree`); the
#: fault tests inject an error on one rank at each (PMPMSPH_INJECT_CONFIG_ERROR=rank:place)
AGREEMENT_PLACES = ("case", "output location", "build", "time", "output files", "restart")


def _mpi():
    """mpi4py's MPI module, imported at first use (importing it initialises MPI)."""
    from mpi4py import MPI  # noqa: PLC0415 - see the docstring

    return MPI


def _world():
    return _mpi().COMM_WORLD


def wait_all(requests):
    """Complete non-blocking sends and receives (the halo and migration exchanges)."""
    _mpi().Request.Waitall(requests)


def exchange_rows(comm, sends, width):
    """Swap packed particle rows with neighbours in one round: `sends` lists (neighbour, send
    tag, receive tag, rows) with `rows` a (k, width) uint8 array (k may be 0); returns the
    rows received from each, in the same order. Every message is sent, empty or not, and
    the receiver sizes its buffer from the message itself (MPI_Probe), so no count message
    goes first: one latency per exchange instead of two. Messages between two ranks with one
    tag arrive in the order sent (MPI's non-overtaking rule), so successive exchanges cannot
    mix."""
    MPI = _mpi()
    reqs = [comm.Isend(rows, dest=nb, tag=send_tag) for nb, send_tag, _, rows in sends]
    status = MPI.Status()
    received = []
    for nb, _, recv_tag, _ in sends:
        comm.Probe(source=nb, tag=recv_tag, status=status)
        nbytes = status.Get_count(MPI.BYTE)
        buf = np.empty((nbytes // width if width else 0, width), np.uint8)
        comm.Recv(buf, source=nb, tag=recv_tag)
        received.append(buf)
    MPI.Request.Waitall(reqs)
    return received


class Distributor:
    """MPI context of a run: rank, size, reductions, exscan, broadcast, error agreement."""

    @classmethod
    def serial(cls):
        """A distributor of this process alone (MPI.COMM_SELF): one rank whatever the launch."""
        return cls(_mpi().COMM_SELF)

    def __init__(self, comm=None):
        self.comm = _world() if comm is None else comm
        self.rank = self.comm.Get_rank()
        self.size = self.comm.Get_size()
        self._flag = np.zeros(1, np.int64)      # the buffers of `any`
        self._flag_out = np.zeros(1, np.int64)

    @property
    def is_root(self):
        return self.rank == 0

    # -- reductions on scalars and arrays ---------------------------------------------------
    def sum(self, value):
        """Global sum of a number or numpy array (same shape on every rank)."""
        if self.size == 1:
            return value
        MPI = _mpi()

        if np.isscalar(value):
            return self.comm.allreduce(value, op=MPI.SUM)
        arr = np.ascontiguousarray(value, dtype=np.float64)
        out = np.empty_like(arr)
        self.comm.Allreduce(arr, out, op=MPI.SUM)
        return out

    def min(self, value):
        if self.size == 1:
            return value
        MPI = _mpi()

        return self.comm.allreduce(value, op=MPI.MIN)

    def max(self, value):
        if self.size == 1:
            return value
        MPI = _mpi()

        return self.comm.allreduce(value, op=MPI.MAX)

    def max_array(self, values):
        """Element-wise global maximum of a short float64 vector (one collective for several
        decisions)."""
        arr = np.ascontiguousarray(values, dtype=np.float64)
        if self.size == 1:
            return arr
        MPI = _mpi()

        out = np.empty_like(arr)
        self.comm.Allreduce(arr, out, op=MPI.MAX)
        return out

    def any(self, flag):
        """True on every rank if `flag` is true on any rank (collective decisions, no hangs).
        On a preallocated buffer (Allreduce): the pickling allreduce of a Python int cost
        several times more, and the SPH stage asks once or twice a step."""
        if self.size == 1:
            return bool(flag)
        self._flag[0] = 1 if flag else 0
        self.comm.Allreduce(self._flag, self._flag_out, op=_mpi().MAX)
        return bool(self._flag_out[0])

    def exscan(self, count):
        """Exclusive prefix sum of an integer over ranks (offset of this rank's slice)."""
        if self.size == 1:
            return 0
        MPI = _mpi()

        out = self.comm.exscan(int(count), op=MPI.SUM)
        return 0 if out is None else int(out)

    def allgather_float(self, value):
        """Every rank's float, on every rank (np.float64 array of length size)."""
        if self.size == 1:
            return np.array([value], dtype=np.float64)
        return np.array(self.comm.allgather(float(value)), dtype=np.float64)

    def gather_counts(self, count):
        """Every rank's count, on every rank (np.int64 array of length size)."""
        if self.size == 1:
            return np.array([count], dtype=np.int64)
        return np.array(self.comm.allgather(int(count)), dtype=np.int64)

    def allgather(self, obj):
        """Every rank's (small, picklable) object, on every rank, as a list."""
        if self.size == 1:
            return [obj]
        return self.comm.allgather(obj)

    def gather(self, obj, root=0):
        """Every rank's object as a list on `root` (None elsewhere)."""
        if self.size == 1:
            return [obj]
        return self.comm.gather(obj, root=root)

    def bcast(self, obj, root=0):
        if self.size == 1:
            return obj
        return self.comm.bcast(obj, root=root)

    def barrier(self):
        if self.size > 1:
            self.comm.Barrier()

    def agree(self, place, fn, root_only=False):
        """fn() on every rank (with `root_only`, on rank 0 only and its result broadcast),
        then one collective on the outcome: a ConfigError on any rank is raised on every
        rank (the lowest failing rank's), so no rank goes on into a collective the others
        have left (DESIGN.md §4, "never hang"). fn must make no collective call itself.
        `place` is one of AGREEMENT_PLACES."""
        out, err = None, None
        try:
            _injected_config_error(place, self.rank)
            if self.is_root or not root_only:
                out = fn()
        except ConfigError as exc:
            err = (exc.key, exc.reason)
        if self.size > 1:
            outcomes = self.comm.allgather((err, out if root_only and self.is_root else None))
            err = next((e for e, _ in outcomes if e is not None), None)
            if root_only:
                out = outcomes[0][1]
        if err is not None:
            raise ConfigError(*err)
        return out

    def abort(self, code):
        """End every rank now (used when one rank fails outside a collective decision)."""
        if self.size > 1:
            self.comm.Abort(code)
        raise SystemExit(code)


def _injected_config_error(place, rank):
    """The fault tests' bad input on one rank only: PMPMSPH_INJECT_CONFIG_ERROR=rank:place."""
    spec = os.environ.get("PMPMSPH_INJECT_CONFIG_ERROR")
    if not spec:
        return
    where, _, what = spec.partition(":")
    if what not in AGREEMENT_PLACES:
        raise ValueError(f"PMPMSPH_INJECT_CONFIG_ERROR: unknown place {what!r}")
    if int(where) == rank and what == place:
        raise ConfigError(f"<{place}>", f"fault injected on rank {rank} at {place}")
