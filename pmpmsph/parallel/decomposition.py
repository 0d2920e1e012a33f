"""Slab decomposition of the global grid along one axis (DESIGN.md §4).

Rank r owns the cells [faces[r], faces[r+1]) along `axis` (domain cell indices), the grid
nodes with those indices (the last rank also the closing node, rank 0 and the last rank the
padding outside the domain) and the particles whose cell lies there. Each rank keeps a local
grid of its owned nodes plus `ghost` node layers on each side, which the neighbours own.
With one rank the same code runs with no neighbours.
"""
import numpy as np

from ..errors import ConfigError

# Ghost node layers on each side of a slab (`GridSpec.ghost`, 3 unless CPDI needs more): a
# particle in an owned cell touches at most one node below its cell and two above (cubic
# B-spline), plus one layer for particles that have moved up to a cell since the last
# migration (MUSL's second P2G comes before migration). The thinnest slab (`min_slab`, in
# cells) equals it: ghost layers must lie in the two neighbouring slabs only.


def wrap_axis(x, axis, lo, length):
    """Positions x (n, dim) back into [lo, lo + length) along `axis`, in place (a periodic
    axis: the particles that crossed one end re-enter at the other)."""
    xa = x[:, axis]
    xa[:] = lo + np.mod(xa - lo, length)


def default_axis(cells):
    """The longest axis (the first of equals), so slabs are as thick as possible."""
    return int(np.argmax(cells))


class Decomposition:
    def __init__(self, dist, grid_spec, axis=None, faces=None, key="grid.cells", period=None):
        self.dist = dist
        #: the length of the domain along the slab axis when that axis is periodic: the
        #: first and last slabs are then neighbours (`routes`; particles shifted by it)
        self.period = period
        self.spec = grid_spec
        self.axis = default_axis(grid_spec.cells) if axis is None else axis
        self.ncells = int(grid_spec.cells[self.axis])
        self.dx = float(grid_spec.cell_size[self.axis])
        self.origin = float(grid_spec.origin[self.axis])
        self.pad = int(grid_spec.pad)
        self.ghost = int(grid_spec.ghost)
        size = dist.size
        #: the grid is periodic along the slab axis across ranks: node k and node k + ncells
        #: are one node, owned once, and the first and last slabs share ghosts across the
        #: wrap (`grid_neighbours`). Its slabs are two ghost widths thick at least, so that
        #: every shared node is shared by two ranks only, and no slab's ghosts meet
        #: themselves across the wrap.
        self.wraps = size > 1 and self.axis in grid_spec.periodic and period is not None
        self.min_slab = 2 * self.ghost if self.wraps else self.ghost
        m = self.min_slab
        if self.ncells < m:
            raise ConfigError(key, f"{self.ncells} cells along axis {'xyz'[self.axis]}: the "
                              f"grid needs at least {m} there")
        if self.ncells < m * size:
            raise ConfigError(key, f"{self.ncells} cells along axis {'xyz'[self.axis]} "
                              f"cannot make {size} slabs of at least {m} cells"
                              + (" (two ghost widths: the grid is periodic along it)"
                                 if self.wraps else "")
                              + f": use at most {self.ncells // m} ranks")
        if faces is None:
            faces = np.round(np.linspace(0, self.ncells, size + 1)).astype(np.int64)
        self.faces = np.asarray(faces, dtype=np.int64)
        self.rank = dist.rank
        self.size = size
        self.key = key

    # -- ownership ----------------------------------------------------------------------------
    @property
    def lo_cell(self):
        return int(self.faces[self.rank])

    @property
    def hi_cell(self):
        return int(self.faces[self.rank + 1])

    @property
    def left(self):
        return self.rank - 1 if self.rank > 0 else None

    @property
    def right(self):
        return self.rank + 1 if self.rank < self.size - 1 else None

    def routes(self):
        """The particle neighbours of this slab: (side, rank, shift) per face that has one,
        side 0 the low face and 1 the high face; `shift` is what a position received across
        that face gains (the period, when the face is the periodic wrap; else 0). On two
        ranks with a periodic axis both faces lead to the other rank. One rank has none (its
        periodic images stay inside it, `ParticleHalo`)."""
        out = []
        if self.left is not None:
            out.append((0, self.left, 0.0))
        elif self.period is not None and self.size > 1:
            out.append((0, self.size - 1, -self.period))
        if self.right is not None:
            out.append((1, self.right, 0.0))
        elif self.period is not None and self.size > 1:
            out.append((1, 0, self.period))
        return out

    def wrap(self, x):
        """Positions x (n, dim) back into the period along the slab axis, in place."""
        wrap_axis(x, self.axis, self.origin, self.period)

    def slab_distance(self, owner):
        """How many slabs away the ranks `owner` are (around the period when periodic)."""
        d = np.abs(np.asarray(owner) - self.rank)
        if self.period is not None:
            d = np.minimum(d, self.size - d)
        return d

    def cell_of(self, x):
        """Domain cell index along the slab axis of positions x (n, dim), clipped to the grid."""
        c = np.floor((x[:, self.axis] - self.origin) / self.dx).astype(np.int64)
        return np.clip(c, 0, self.ncells - 1)

    def owner(self, x):
        """Owning rank of each position."""
        return np.searchsorted(self.faces, self.cell_of(x), side="right") - 1

    def keep(self, x):
        """Mask of positions this rank owns (used while seeding)."""
        return self.owner(x) == self.rank

    # -- nodes ---------------------------------------------------------------------------------
    def owned_nodes(self, rank=None):
        """[lo, hi) of owned nodes along the axis, in padded global node indices."""
        r = self.rank if rank is None else rank
        lo = int(self.faces[r]) + self.pad
        hi = int(self.faces[r + 1]) + self.pad
        if self.wraps:  # every node once: the padding and the closing node are images
            return lo, hi
        if r == 0:
            lo = 0
        if r == self.size - 1:
            hi = self.ncells + 1 + 2 * self.pad
        return lo, hi

    def local_nodes(self, rank=None):
        """[lo, hi) of the nodes a rank stores: owned plus ghost layers inside the grid
        (across the wrap of a periodic grid they run past its padding: the images)."""
        lo, hi = self.owned_nodes(rank)
        if self.wraps:
            return lo - self.ghost, hi + self.ghost
        total = self.ncells + 1 + 2 * self.pad
        return max(lo - self.ghost, 0), min(hi + self.ghost, total)

    def grid_neighbours(self):
        """(side, rank, node shift) per slab face with a neighbour on the grid: the shift
        takes the neighbour's node indices into ours (-ncells across the low wrap, +ncells
        across the high one)."""
        out = []
        if self.left is not None:
            out.append((0, self.left, 0))
        elif self.wraps:
            out.append((0, self.size - 1, -self.ncells))
        if self.right is not None:
            out.append((1, self.right, 0))
        elif self.wraps:
            out.append((1, 0, self.ncells))
        return out

    def overlap(self, nb, shift=0):
        """Node ranges shared with neighbour `nb` (padded global indices, in ours: its
        indices plus `shift`, `grid_neighbours`): (my ghosts that nb owns, my owned nodes
        that are nb's ghosts)."""
        my_lo, my_hi = self.local_nodes()
        own_lo, own_hi = self.owned_nodes()
        nb_lo, nb_hi = (i + shift for i in self.local_nodes(nb))
        nb_own_lo, nb_own_hi = (i + shift for i in self.owned_nodes(nb))
        ghosts = (max(my_lo, nb_own_lo), min(my_hi, nb_own_hi))
        shared = (max(own_lo, nb_lo), min(own_hi, nb_hi))
        return ghosts, shared

    def with_faces(self, faces):
        return Decomposition(self.dist, self.spec, self.axis, faces, self.key, self.period)
