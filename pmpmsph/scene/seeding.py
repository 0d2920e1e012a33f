"""Seed particles of a body on a regular lattice (DESIGN.md §1, `scene/`).

Three ways, as a CB-Geo/Uintah user expects:
  ppc      n particles per cell per axis, at the centres of the n^dim sub-cells of every grid
           cell (aligned with the grid) whose centre lies in the body;
  spacing  a lattice of the given spacing starting half a spacing inside the bounding box;
  count    exactly count[a] particles per axis over the bounding box (thesis "20x20 points").
Each particle carries the volume of its lattice cell, so the body's volume is the lattice's.
Mesh bodies (`scene.mesh`) are seeded per element instead, with the elements' volumes.
"""
import numpy as np


def _lattice(lo, hi, spacing):
    axes = []
    for a in range(len(lo)):
        n = max(int(np.floor((hi[a] - lo[a]) / spacing[a] + 1e-9)), 1)
        # centre the points in the box
        start = lo[a] + 0.5 * ((hi[a] - lo[a]) - (n - 1) * spacing[a])
        axes.append(start + spacing[a] * np.arange(n))
    mesh = np.meshgrid(*axes, indexing="ij")
    return np.stack([m.ravel() for m in mesh], axis=1)


def seed_body(body, grid):
    """Return (x, vol, spacing) for one body: positions (n, dim), volumes (n,), spacing (dim,)."""
    geom = body.geometry
    if hasattr(geom, "seed"):  # a mesh: particles per element (scene/mesh.py)
        return geom.seed()
    lo, hi = geom.bbox()
    dim = len(lo)
    if body.count is not None:
        count = np.array(body.count, float)
        spacing = (hi - lo) / count
        axes = [lo[a] + spacing[a] * (np.arange(int(count[a])) + 0.5) for a in range(dim)]
        mesh = np.meshgrid(*axes, indexing="ij")
        x = np.stack([m.ravel() for m in mesh], axis=1)
    elif body.spacing is not None:
        spacing = np.array(body.spacing, float)
        x = _lattice(lo, hi, spacing)
    else:
        h = np.array(grid.cell_size, float)
        org = np.array(grid.origin, float)
        spacing = h / body.ppc
        c_lo = np.floor((lo - org) / h).astype(int)
        c_hi = np.ceil((hi - org) / h).astype(int)
        axes = [org[a] + spacing[a] * (np.arange(c_lo[a] * body.ppc, c_hi[a] * body.ppc) + 0.5)
                for a in range(dim)]
        mesh = np.meshgrid(*axes, indexing="ij")
        x = np.stack([m.ravel() for m in mesh], axis=1)
    x = x[geom.contains(x)]
    vol = np.full(len(x), float(np.prod(spacing)))
    return x, vol, spacing
