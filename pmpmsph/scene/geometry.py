"""Body geometries: what region of space a body fills (points in/out, bounding box, measure).

Coordinates are `dim`-vectors (1, 2 or 3). A disc is a segment in 1D, a circle in 2D and a
sphere in 3D. Polygons are 2D only (meshes come from meshio, see `scene.mesh`).
"""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Box:
    lo: tuple
    hi: tuple

    @property
    def dim(self):
        return len(self.lo)

    def bbox(self):
        return np.array(self.lo, float), np.array(self.hi, float)

    def contains(self, pts):
        lo, hi = self.bbox()
        return np.all((pts >= lo) & (pts <= hi), axis=1)

    def measure(self):
        return float(np.prod(np.subtract(self.hi, self.lo)))


@dataclass(frozen=True)
class Disc:
    centre: tuple
    radius: float

    @property
    def dim(self):
        return len(self.centre)

    def bbox(self):
        c = np.array(self.centre, float)
        return c - self.radius, c + self.radius

    def contains(self, pts):
        d = pts - np.array(self.centre, float)
        return np.einsum("ij,ij->i", d, d) <= self.radius**2

    def measure(self):
        r = self.radius
        return {1: 2 * r, 2: np.pi * r * r, 3: 4.0 / 3.0 * np.pi * r**3}[self.dim]


@dataclass(frozen=True)
class Polygon:
    vertices: tuple  # ((x, y), ...), closed implicitly

    @property
    def dim(self):
        return 2

    def bbox(self):
        v = np.array(self.vertices, float)
        return v.min(axis=0), v.max(axis=0)

    def contains(self, pts):
        """Even-odd ray casting, vectorised over points."""
        v = np.array(self.vertices, float)
        x, y = pts[:, 0], pts[:, 1]
        inside = np.zeros(len(pts), dtype=bool)
        n = len(v)
        for k in range(n):
            (x1, y1), (x2, y2) = v[k], v[(k + 1) % n]
            crosses = (y1 > y) != (y2 > y)
            with np.errstate(divide="ignore", invalid="ignore"):
                xint = x1 + (y - y1) * (x2 - x1) / (y2 - y1)
            inside ^= crosses & (x < xint)
        return inside

    def measure(self):
        v = np.array(self.vertices, float)
        x, y = v[:, 0], v[:, 1]
        return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))

    def signed_area(self):
        v = np.array(self.vertices, float)
        x, y = v[:, 0], v[:, 1]
        return 0.5 * (np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
