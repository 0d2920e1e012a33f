"""The background grid of MPM (DESIGN.md §2): nodal arrays over this rank's nodes.

Nodes are numbered by a flat index with C-order strides over (cells + 1 + 2 pad) nodes per
axis; `pad` layers of nodes lie outside the domain so that wide stencils of particles at a
wall stay inside the arrays (boundary conditions act on them too). A scene without MPM
builds no Grid.

Only the node layers along axis 0 that particles can reach are reset and solved each step
(`work_range`): a dam break in a wide tank, or a slab whose particles fill a part of it,
does not pay for its empty nodes. Invariant: every node outside the range holds zeros, since
the range is hulled with the previous one, so nodes the particles left are zeroed once.
"""
import math

import numpy as np

from ...kernels.partition import column_extent
from ...kernels.mpm.views import grid_layout


class Grid:
    """Nodal arrays of the nodes this rank stores.

    `node_range = (axis, lo, hi)` restricts the grid along one axis to the padded global node
    indices [lo, hi) (a slab with its ghost layers, see `parallel.decomposition`); the local
    origin is shifted so the kernels index local nodes directly.
    """

    def __init__(self, spec, nfields=1, with_normals=False, node_range=None, folded=None):
        self.spec = spec
        #: the periodic axes folded inside this grid (`fold_periodic`): all of
        #: `spec.periodic` but a slab axis whose wrap runs between ranks (`GridHalo`)
        self.folded = tuple(spec.periodic if folded is None else folded)
        self.dim = spec.dim
        self.pad = spec.pad
        self.dx = float(spec.cell_size[0])
        if any(abs(h - self.dx) > 1e-12 * self.dx for h in spec.cell_size):
            # one cell size for all axes keeps stencils isotropic (thesis uses dx = dy)
            raise ValueError("non-square cells")
        self.inv_dx = 1.0 / self.dx
        self.global_origin = np.array(spec.origin, dtype=np.float64)
        shape = [int(n) + 1 + 2 * self.pad for n in spec.cells]
        self.offset = np.zeros(self.dim, dtype=np.int64)  # global padded index of local node 0
        if node_range is not None:
            axis, lo, hi = node_range
            self.offset[axis] = lo
            shape[axis] = hi - lo
        self.shape = tuple(shape)
        self.origin = self.global_origin + self.offset * self.dx
        #: position of global (padded) node 0, the kernels' coordinate origin (global node i
        #: sits i cells from it; local node index = global - offset)
        self.node0 = self.global_origin - self.pad * self.dx
        strides = np.ones(self.dim, dtype=np.int64)
        for a in range(self.dim - 2, -1, -1):
            strides[a] = strides[a + 1] * self.shape[a + 1]
        self.strides = strides
        self.n_nodes = int(np.prod(self.shape))
        self.nfields = nfields
        nf, nn, d = nfields, self.n_nodes, self.dim
        self.mass = np.zeros((nf, nn))
        self.mom = np.zeros((nf, nn, d))
        self.force = np.zeros((nf, nn, d))
        self.vel = np.zeros((nf, nn, d))
        self.dv = np.zeros((nf, nn, d))
        # multi-field contact: mass gradients, the normals made of them and each field's
        # reach along its normal (kernels/mpm/contact.py)
        self.mgrad = np.zeros((nf, nn if with_normals else 0, d))
        self.normals = np.zeros((nf, nn if with_normals else 0, d))
        self.reach = np.zeros((nf, nn if with_normals else 0))
        self._reached = (0, 0)  # the layers the last `work_range` call's rows reach
        #: the domain and the band around it in which particles may be (one cell outside)
        self.lo = self.global_origin - self.dx
        self.hi = np.array(spec.upper) + self.dx
        #: all of the above the transfer kernels read, as one bundle
        self.layout = grid_layout(self.node0, self.offset, self.inv_dx, self.strides, self.lo,
                                 self.hi)

    def fold_periodic(self, arrays, combine=np.add):
        """Make the grid periodic along `folded` (axes whose wrap is inside the rank): padded
        node g and g + cells are one node, so the nodal sums of the padded layers beyond each
        end are added into the nodes they stand for and the full sums copied back. After
        P2G; the solve is node-local, so the copies then hold the same velocities."""
        for a in self.folded:
            n = int(self.spec.cells[a])
            total = n + 1 + 2 * self.pad
            pairs = ((slice(0, self.pad), slice(n, n + self.pad)),         # below the start
                     (slice(self.pad + n, total), slice(self.pad, total - n)))  # past the end
            for arr in arrays:
                blk = self.block(arr)
                for image, node in pairs:
                    index_i = [slice(None)] * blk.ndim
                    index_n = [slice(None)] * blk.ndim
                    index_i[1 + a] = image
                    index_n[1 + a] = node
                    combine(blk[tuple(index_n)], blk[tuple(index_i)],
                            out=blk[tuple(index_n)])
                for image, node in pairs:
                    index_i = [slice(None)] * blk.ndim
                    index_n = [slice(None)] * blk.ndim
                    index_i[1 + a] = image
                    index_n[1 + a] = node
                    blk[tuple(index_i)] = blk[tuple(index_n)]

    def block(self, arr):
        """`arr` (nfields, n_nodes[, dim]) viewed as (nfields, *shape[, dim])."""
        return arr.reshape((arr.shape[0],) + self.shape + arr.shape[2:])

    def reset(self, lo=0, hi=None):
        """Zero the accumulators of the flat node range [lo, hi) (all nodes by default)."""
        sl = slice(lo, hi)
        self.mass[:, sl] = 0.0
        self.mom[:, sl] = 0.0
        self.force[:, sl] = 0.0
        if self.mgrad.shape[1]:
            self.mgrad[:, sl] = 0.0

    def work_range(self, x, n, margin, keep_lo=0, keep_hi=0):
        """Flat node range [a, b) to reset and solve before a P2G of the rows x[:n]: the node
        layers along axis 0 within `margin` layers of the rows' cells, and the first
        `keep_lo` and last `keep_hi` layers (those shared with a neighbour rank, which
        `GridHalo` exchanges), hulled with the previous range (module doc). A non-finite
        position (a failing step) takes every node."""
        layers = self.shape[0]
        lo, hi = layers, 0
        if n:
            xmin, xmax = column_extent(x, n)
            if not (math.isfinite(xmin) and math.isfinite(xmax)):
                lo, hi = 0, layers
            else:
                o = self.node0[0]
                lo = int(math.floor((xmin - o) * self.inv_dx)) - int(self.offset[0]) - margin
                hi = int(math.floor((xmax - o) * self.inv_dx)) - int(self.offset[0]) + margin + 1
        if keep_lo:
            lo, hi = 0, max(hi, keep_lo)
        if keep_hi:
            lo, hi = min(lo, layers - keep_hi), layers
        lo, hi = max(lo, 0), min(hi, layers)
        stride = int(self.strides[0])
        new = (lo * stride, hi * stride) if lo < hi else (0, 0)
        old, self._reached = self._reached, new
        if old[0] == old[1]:
            return new
        if new[0] == new[1]:
            return old
        return min(old[0], new[0]), max(old[1], new[1])

    def global_index(self):
        """Padded global node index of every local node, (dim, n_nodes)."""
        return np.indices(self.shape).reshape(self.dim, -1) + self.offset[:, None]

    def node_coords(self):
        """Physical coordinates of all local nodes, (n_nodes, dim)."""
        return self.global_origin + (self.global_index().T - self.pad) * self.dx

    def nodes_on_face(self, face):
        """Flat indices of nodes on a domain face and outside it (the padding)."""
        axis = "xyz".index(face[0])
        idx = self.global_index()[axis]
        if face[1] == "-":
            sel = idx <= self.pad
        else:
            sel = idx >= self.pad + self.spec.cells[axis]
        return np.nonzero(sel)[0].astype(np.int64)

    def mirror_pairs(self, face):
        """(outside, inside): flat indices of the local nodes beyond a domain face and of
        their mirror images across it, for the pairs whose image is also local."""
        axis = "xyz".index(face[0])
        gidx = self.global_index()
        wall = self.pad if face[1] == "-" else self.pad + self.spec.cells[axis]
        i = gidx[axis]
        outside = (i < wall) if face[1] == "-" else (i > wall)
        mirror = gidx.copy()
        mirror[axis] = 2 * wall - i
        local = mirror - self.offset[:, None]
        shape = np.array(self.shape)[:, None]
        ok = outside & np.all((local >= 0) & (local < shape), axis=0)
        inside = np.ravel_multi_index(tuple(local[:, ok]), self.shape)
        return np.nonzero(ok)[0].astype(np.int64), inside.astype(np.int64)

    def nodes_in_box(self, lo, hi):
        xs = self.node_coords()
        tol = 1e-9 * self.dx
        sel = np.all((xs >= np.array(lo) - tol) & (xs <= np.array(hi) + tol), axis=1)
        return np.nonzero(sel)[0].astype(np.int64)
