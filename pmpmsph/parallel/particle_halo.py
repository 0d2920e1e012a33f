"""Halo particles: copies of the owned particles near a slab face, sent to the neighbour
across it (DESIGN.md §4). They sit after the owned rows and are dropped and rebuilt at every
exchange, never written back. Only fields declared with `halo=True` travel.

`width` is the interaction radius plus one step of motion (2h for the cubic spline): a
particle of the neighbour within `width` of the face can interact with our particles.
"""
import numpy as np

from .migration import _pack, _unpack

TAG_HALO_COUNT = 31
TAG_HALO_DATA = 32


class ParticleHalo:
    def __init__(self, decomposition, particles, width):
        self.dec = decomposition
        self.particles = particles
        self.width = float(width)
        thinnest = np.diff(decomposition.faces).min() * decomposition.dx
        if decomposition.size > 1 and self.width > thinnest:
            # a halo must come from the two neighbours only
            raise ValueError(f"halo width {self.width:g} exceeds the thinnest slab {thinnest:g}")
        self.names = particles.fields(halo=True)
        self.bytes_sent = 0

    def send_lists(self):
        """Owned particles within `width` of the low and high faces of this slab."""
        dec = self.dec
        xa = self.particles["x"][:, dec.axis]
        lo_face = dec.origin + dec.lo_cell * dec.dx
        hi_face = dec.origin + dec.hi_cell * dec.dx
        out = {}
        if dec.left is not None:
            out[dec.left] = np.nonzero(xa < lo_face + self.width)[0]
        if dec.right is not None:
            out[dec.right] = np.nonzero(xa >= hi_face - self.width)[0]
        return out

    def exchange(self):
        """Rebuild the halo rows; returns the number of halo particles received."""
        p = self.particles
        p.drop_halo()
        if self.dec.size == 1:
            return 0
        from mpi4py import MPI

        comm = self.dec.dist.comm
        sends = {nb: _pack(p, self.names, idx) for nb, idx in self.send_lists().items()}
        counts, reqs = {}, []
        for nb, rows in sends.items():
            counts[nb] = np.zeros(2, np.int64)
            reqs.append(comm.Isend(np.array(rows.shape, np.int64), dest=nb, tag=TAG_HALO_COUNT))
            reqs.append(comm.Irecv(counts[nb], source=nb, tag=TAG_HALO_COUNT))
        MPI.Request.Waitall(reqs)
        reqs, bufs = [], []
        for nb, rows in sends.items():
            buf = np.empty(tuple(int(c) for c in counts[nb]), np.uint8)
            bufs.append(buf)
            if rows.size:
                reqs.append(comm.Isend(rows, dest=nb, tag=TAG_HALO_DATA))
                self.bytes_sent += rows.nbytes
            if buf.size:
                reqs.append(comm.Irecv(buf, source=nb, tag=TAG_HALO_DATA))
        MPI.Request.Waitall(reqs)
        received = 0
        for buf in bufs:
            if buf.shape[0]:
                p.append_halo(_unpack(p, self.names, buf))
                received += buf.shape[0]
        return received
