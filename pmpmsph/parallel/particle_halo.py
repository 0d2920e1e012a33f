"""Halo particles: copies of the owned particles near a slab face, sent to the neighbour
across it (DESIGN.md §4). They sit after the owned rows and are dropped and rebuilt at every
exchange, never written back. Only fields declared with `halo=True` travel.

`width` is the interaction radius plus one step of motion (2h for the cubic spline): a
particle of the neighbour within `width` of the face can interact with our particles.
"""
import numpy as np

from ..errors import ConfigError
from .distributor import exchange_rows, wait_all
from ..kernels.partition import scatter_rows
from .migration import _pack, _unpack

TAG_HALO_DATA = 32
TAG_HALO_REFRESH = 33
#: halo fields fixed for the particle's life (identity, method, material, mass)
CONSTANT_FIELDS = frozenset(("gid", "method", "body", "mat", "mass"))


class ParticleHalo:
    """`periodic`: (axis, lo, length) of each periodic axis of the domain. Along the slab
    axis of several ranks the first and last slabs are neighbours (`Decomposition.routes`):
    the rows crossing that wrap arrive shifted by the period. Along every other periodic
    axis (and the slab axis of one rank), after the neighbours' rows, the rows (owned and
    halo) within `width` of either end of the axis are copied to the other end as images,
    shifted by the period, axis after axis (so a corner of two periodic axes gets its
    diagonal images too); `refresh` copies them again from the same rows.

    Messages carry the side of the sender's face in their tag, so the two routes between the
    same two ranks (two ranks, periodic) stay apart."""

    def __init__(self, decomposition, particles, width, check=True, periodic=()):
        self.dec = decomposition
        self.particles = particles
        self.width = float(width)
        self.periodic = tuple(periodic)
        for axis, _, length in self.periodic:
            if 2.0 * self.width > length:  # an image would be its own neighbour's image
                raise ConfigError("domain.periodic", f"the period {length:g} along "
                                  f"{'xyz'[axis]} is shorter than twice the halo width "
                                  f"{self.width:g} (2.75 h): lengthen the domain")
        # the axes with images: all periodic ones but a slab axis cut between ranks
        self.imaged = tuple(per for per in self.periodic
                            if not (per[0] == decomposition.axis and decomposition.size > 1))
        self._images = []  # (source rows, first image row, axis, shift) of the last exchange
        thinnest = np.diff(decomposition.faces).min() * decomposition.dx
        if check and decomposition.size > 1 and self.width > thinnest:
            # a halo must come from the two neighbours only
            raise ValueError(f"halo width {self.width:g} exceeds the thinnest slab {thinnest:g}")
        self.names = particles.fields(halo=True)
        # what a particle never changes while it stays in one exchange's plan: a refresh of
        # "everything" (`refresh(halo.mutable)`) leaves these out
        self.mutable = tuple(n for n in self.names if n not in CONSTANT_FIELDS)
        self.bytes_sent = 0
        self._plan = None  # (send lists, [(neighbour, first halo row, count)]) of the last exchange

    def send_lists(self):
        """Owned particles within `width` of the low and high faces of this slab, per route
        (side, neighbour, shift) of `Decomposition.routes`."""
        dec = self.dec
        xa = self.particles["x"][:, dec.axis]
        lo_face = dec.origin + dec.lo_cell * dec.dx
        hi_face = dec.origin + dec.hi_cell * dec.dx
        return {route: np.nonzero(xa < lo_face + self.width if route[0] == 0
                                  else xa >= hi_face - self.width)[0]
                for route in dec.routes()}

    def exchange(self):
        """Rebuild the halo rows (the neighbours', then the periodic images); returns how
        many halo rows there are."""
        p = self.particles
        p.drop_halo()
        if self.dec.size > 1:
            self._exchange_neighbours()
        self._add_images()
        return p.n_total - p.n_owned

    def _add_images(self):
        p = self.particles
        self._images = []
        for axis, lo, length in self.imaged:
            xa = p.arrays["x"][: p.n_total, axis]
            low = np.nonzero(xa < lo + self.width)[0]
            high = np.nonzero(xa >= lo + length - self.width)[0]
            for rows, shift in ((low, length), (high, -length)):
                if not len(rows):
                    continue
                values = {name: p.arrays[name][rows] for name in self.names}
                values["x"] = values["x"].copy()
                values["x"][:, axis] += shift
                self._images.append((rows, p.n_total, axis, shift))
                p.append_halo(values)

    def _refresh_images(self, names):
        p = self.particles
        for rows, first, axis, shift in self._images:
            for name in names:
                arr = p.arrays[name]
                arr[first:first + len(rows)] = arr[rows]
                if name == "x":
                    arr[first:first + len(rows), axis] += shift

    def _exchange_neighbours(self):
        p = self.particles
        lists = self.send_lists()
        width = p.byte_views(self.names)[1]
        # sent from my face `side`, a message reaches the neighbour's opposite face
        sends = [(nb, TAG_HALO_DATA + 100 * side, TAG_HALO_DATA + 100 * (1 - side),
                  _pack(p, self.names, idx)) for (side, nb, _shift), idx in lists.items()]
        bufs = exchange_rows(self.dec.dist.comm, sends, width)
        self.bytes_sent += sum(rows.nbytes for *_, rows in sends)
        received = 0
        recv_rows = []
        for route, buf in zip(lists, bufs):
            recv_rows.append((route, p.n_total, buf.shape[0]))
            if buf.shape[0]:
                values = _unpack(p, self.names, buf)
                if route[2] != 0.0:  # across the periodic wrap
                    values["x"][:, self.dec.axis] += route[2]
                p.append_halo(values)
                received += buf.shape[0]
        self._plan = (lists, recv_rows)
        return received

    def refresh(self, names):
        """Re-send fields `names` of the particles of the last exchange into the same halo
        rows (after the owners updated them, e.g. the wall pressures); same plan, no search.
        The periodic images are copied again after the neighbours' rows (which they may
        copy)."""
        if self.dec.size > 1 and self._plan is not None:
            self._refresh_neighbours(names)
        self._refresh_images(names)

    def _refresh_neighbours(self, names):
        p = self.particles
        comm = self.dec.dist.comm
        lists, recv_rows = self._plan
        reqs, bufs = [], []
        for (side, nb, _), idx in lists.items():
            rows = _pack(p, names, idx)
            if rows.size:
                reqs.append(comm.Isend(rows, dest=nb, tag=TAG_HALO_REFRESH + 100 * side))
                self.bytes_sent += rows.nbytes
        views, width = p.byte_views(names)
        for (side, nb, shift), first, count in recv_rows:
            buf = np.empty((count, width), np.uint8)
            bufs.append((first, shift, buf))
            if count:
                reqs.append(comm.Irecv(buf, source=nb, tag=TAG_HALO_REFRESH + 100 * (1 - side)))
        wait_all(reqs)
        for first, shift, buf in bufs:
            if buf.shape[0]:
                scatter_rows(views, first, buf)
                if shift != 0.0 and "x" in names:  # across the periodic wrap
                    p.arrays["x"][first:first + buf.shape[0], self.dec.axis] += shift
