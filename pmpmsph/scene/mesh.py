"""Bodies from mesh files read with meshio (DESIGN.md §6): particles seeded per element.

A body with ``shape = "mesh"``, ``file = "part.msh"`` (any format meshio reads; a relative
path is taken from the case file's folder) and ``ppe = 1`` takes the elements of the body's
dimension from the file:

    2D  triangle, quad           (the first two point coordinates are used)
    3D  tetra, hexahedron

Lower-dimensional cells (gmsh's boundary lines, points) are ignored; other cells of the
body's dimension (second-order elements, wedges, polygons) are an error.

``ppe`` (particles per element) is 1 or 2^(k dim): 1, 4, 16, 64 in 2D and 1, 8, 64, 512 in
3D. With ppe = 1 one particle sits at the centroid of each element and carries its whole
area/volume. Otherwise every element is split k times into 2^dim children and one particle
sits at the centroid of each child, carrying the child's area/volume:

- a triangle (tetrahedron) is split by its edge midpoints into 4 (8) children: the corner
  triangles (tetrahedra) plus, in 3D, the inner octahedron cut into 4 along its diagonal
  between the midpoints of edges 0-2 and 1-3; all children have a quarter (an eighth) of the
  parent's measure;
- a quad (hexahedron) is split into n x n (x n) children, n = 2^k, along the lines of
  constant isoparametric coordinates, i.e. the images of a regular split of the reference
  square (cube); children of a distorted element have different measures.

Measures are exact: a triangle's and tetrahedron's from the cross product and determinant,
a bilinear quad's from the shoelace formula, a trilinear hexahedron's and the centroids of
quads and hexahedra from 2 x 2 (x 2) Gauss quadrature of det J, which is exact for them. The
particles' volumes therefore add up to the mesh's area/volume to round-off. Elements of
either orientation are accepted; a degenerate or inverted (self-crossing) element is an error.

For GIMP and traction loads, which want a lattice spacing, a mesh body reports the mean
particle size (mean volume)^(1/dim) along every axis.
"""
import contextlib
import io
import os
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConfigError

#: element types per dimension and their vertex counts (meshio / VTK vertex order)
ELEMENTS = {2: {"triangle": 3, "quad": 4}, 3: {"tetra": 4, "hexahedron": 8}}
#: meshio cell types of each topological dimension (to tell ignored from unsupported cells)
_CELL_DIM = {"vertex": 0, "line": 1, "line3": 1, "triangle": 2, "quad": 2, "triangle6": 2,
             "quad8": 2, "quad9": 2, "polygon": 2, "triangle7": 2, "tetra": 3, "hexahedron": 3,
             "wedge": 3, "pyramid": 3, "tetra10": 3, "hexahedron20": 3, "hexahedron27": 3,
             "wedge15": 3, "pyramid13": 3}

_G = 1.0 / np.sqrt(3.0)  # 2-point Gauss-Legendre abscissa on [-1, 1] (weights 1)
#: reference corners (quad: counter-clockwise; hexahedron: bottom face then top face)
_QUAD_REF = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], float)
_HEX_REF = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                     [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)


def allowed_ppe(dim):
    return tuple(2 ** (k * dim) for k in range(4))


# -- element geometry (vectorised over elements: arrays of shape (m, nv, dim)) ---------------
def _shape_q1(ref, xi):
    """Values (nv,) and reference gradients (nv, d) of the (bi/tri)linear shape functions."""
    n = np.prod(1.0 + ref * xi, axis=1) / len(ref)
    d = ref.shape[1]
    grad = np.empty((len(ref), d))
    for a in range(d):
        others = np.prod(np.delete(1.0 + ref * xi, a, axis=1), axis=1)
        grad[:, a] = ref[:, a] * others / len(ref)
    return n, grad


def _q1_integrals(v, ref):
    """Signed measure (m,) and first moment (m, d) of Q1 elements by 2^d-point Gauss."""
    d = ref.shape[1]
    pts = np.array(np.meshgrid(*[[-_G, _G]] * d, indexing="ij")).reshape(d, -1).T
    meas = np.zeros(len(v))
    moment = np.zeros((len(v), v.shape[2]))
    for xi in pts:
        n, grad = _shape_q1(ref, xi)
        jac = np.einsum("mvi,va->mia", v, grad)  # dx_i / dxi_a
        det = np.linalg.det(jac)
        meas += det
        moment += det[:, None] * np.einsum("v,mvi->mi", n, v)
    return meas, moment


def _measure_and_centroid(kind, v):
    """Signed measure (m,) and centroid (m, dim) of elements with vertices v (m, nv, dim)."""
    if kind == "triangle":
        e1, e2 = v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]
        return 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]), v.mean(axis=1)
    if kind == "tetra":
        e = v[:, 1:] - v[:, :1]
        return np.linalg.det(e) / 6.0, v.mean(axis=1)
    ref = _QUAD_REF if kind == "quad" else _HEX_REF
    meas, moment = _q1_integrals(v, ref)
    with np.errstate(divide="ignore", invalid="ignore"):
        return meas, moment / meas[:, None]


def _split_simplex(kind, v):
    """Midpoint refinement: (m, nv, d) -> (m * 2^d, nv, d)."""
    if kind == "triangle":
        a, b, c = v[:, 0], v[:, 1], v[:, 2]
        ab, bc, ca = 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)
        kids = [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    else:
        p = [v[:, i] for i in range(4)]
        m = {(i, j): 0.5 * (p[i] + p[j]) for i in range(4) for j in range(i + 1, 4)}
        kids = [(p[0], m[0, 1], m[0, 2], m[0, 3]), (m[0, 1], p[1], m[1, 2], m[1, 3]),
                (m[0, 2], m[1, 2], p[2], m[2, 3]), (m[0, 3], m[1, 3], m[2, 3], p[3])]
        ring = [m[0, 1], m[1, 2], m[2, 3], m[0, 3]]  # around the diagonal m02 - m13
        kids += [(m[0, 2], m[1, 3], ring[i], ring[(i + 1) % 4]) for i in range(4)]
    return np.stack([np.stack(k, axis=1) for k in kids], axis=1).reshape(
        -1, v.shape[1], v.shape[2])


def _split_q1(kind, v, n):
    """Children of Q1 elements on an n^d split of the reference element: (m n^d, nv, d)."""
    ref = _QUAD_REF if kind == "quad" else _HEX_REF
    d = ref.shape[1]
    edges = np.linspace(-1.0, 1.0, n + 1)
    kids = []
    for idx in np.ndindex(*(n,) * d):
        lo = np.array([edges[i] for i in idx])
        hi = np.array([edges[i + 1] for i in idx])
        corners = np.where(ref > 0, hi, lo)  # the child's reference corners, same order
        shape = np.array([_shape_q1(ref, c)[0] for c in corners])  # (nv_child, nv)
        kids.append(np.einsum("cv,mvi->mci", shape, v))
    return np.stack(kids, axis=1).reshape(-1, v.shape[1], v.shape[2])


def element_particles(kind, v, ppe):
    """Particle positions (m ppe, d) and signed volumes (m ppe,) of elements v (m, nv, d),
    grouped element by element."""
    d = v.shape[2]
    k = int(round(np.log2(ppe) / d)) if ppe > 1 else 0
    if kind in ("triangle", "tetra"):
        for _ in range(k):
            v = _split_simplex(kind, v)
    elif k:
        v = _split_q1(kind, v, 2 ** k)
    vol, x = _measure_and_centroid(kind, v)
    return x, vol


def _read(path, key):
    """meshio.read, quietly; any failure (meshio may even call sys.exit) is a ConfigError."""
    import meshio  # noqa: PLC0415 - optional: only mesh bodies need it

    chatter = io.StringIO()
    try:
        with contextlib.redirect_stdout(chatter), contextlib.redirect_stderr(chatter):
            return meshio.read(path)
    except (Exception, SystemExit) as exc:  # noqa: BLE001 - any reader failure is bad input
        text = " ".join(str(exc).split()) if str(exc).strip() not in ("", "1") else ""
        text = text or " ".join(chatter.getvalue().split()) or type(exc).__name__
        raise ConfigError(key, f"cannot read mesh file {path}: {text}") from None


@dataclass(frozen=True, eq=False)
class MeshGeometry:
    """The elements of a mesh file and the particles seeded in them."""
    file: str
    dim: int
    ppe: int
    points: np.ndarray = field(repr=False)
    cells: tuple = field(repr=False)   # ((kind, connectivity (m, nv)), ...)
    x: np.ndarray = field(repr=False)   # seeded particle positions (n, dim)
    vol: np.ndarray = field(repr=False)  # and their volumes (n,)

    @classmethod
    def from_file(cls, path, dim, ppe=1, key="file"):
        """Read `path` with meshio; ConfigError(key, reason) if it cannot be used."""
        if dim not in ELEMENTS:
            raise ConfigError(key, "mesh bodies need dimension 2 or 3")
        if ppe not in allowed_ppe(dim):
            raise ConfigError(key.rsplit(".", 1)[0] + ".ppe", f"must be one of "
                              f"{', '.join(map(str, allowed_ppe(dim)))} in {dim}D (1: the "
                              "centroid; 2^(k dim): k midpoint splits), got {ppe}")
        if not os.path.isfile(path):
            raise ConfigError(key, f"mesh file {path} does not exist")
        mesh = _read(path, key)
        points = np.asarray(mesh.points, dtype=np.float64)
        if points.ndim != 2 or points.shape[1] < dim:
            raise ConfigError(key, f"mesh file {path} has {points.shape[-1]}-D points, the case "
                              f"is {dim}D")
        points = points[:, :dim]
        cells, bad = [], set()
        for block in mesh.cells:
            kind, conn = block.type, np.asarray(block.data, dtype=np.int64)
            if kind in ELEMENTS[dim]:
                if len(conn):
                    cells.append((kind, conn))
            elif _CELL_DIM.get(kind, dim) >= dim:
                bad.add(kind)
        if bad:
            raise ConfigError(key, f"mesh file {path} has {', '.join(sorted(bad))} cells; "
                              f"{dim}D bodies take {' and '.join(ELEMENTS[dim])} cells only")
        if not cells:
            raise ConfigError(key, f"mesh file {path} has no {' or '.join(ELEMENTS[dim])} cells")
        xs, vols = [], []
        scale = float(np.max(np.ptp(points, axis=0))) or 1.0
        for kind, conn in cells:
            if conn.min() < 0 or conn.max() >= len(points):
                raise ConfigError(key, f"mesh file {path}: {kind} connectivity refers to "
                                  "points that do not exist")
            x, vol = element_particles(kind, points[conn], ppe)
            vol = vol.reshape(len(conn), ppe)
            sign = np.sign(vol.sum(axis=1, keepdims=True))
            vol = vol * sign
            small = ~(vol > 1e-12 * scale**dim)
            if small.any():
                e = int(np.nonzero(small.any(axis=1))[0][0])
                raise ConfigError(key, f"mesh file {path}: {kind} {e} is degenerate or "
                                  "inverted (zero or negative measure)")
            xs.append(x)
            vols.append(vol.ravel())
        return cls(os.path.abspath(path), dim, int(ppe), points, tuple(cells),
                   np.concatenate(xs), np.concatenate(vols))

    def bbox(self):
        return self.x.min(axis=0), self.x.max(axis=0)

    def measure(self):
        """The mesh's area (2D) or volume (3D): the sum over its elements."""
        return float(self.vol.sum())

    def seed(self):
        """(x, vol, spacing) as `seeding.seed_body` returns them; spacing is the mean
        particle size (mean volume)^(1/dim) along every axis."""
        h = float(np.mean(self.vol)) ** (1.0 / self.dim)
        return self.x.copy(), self.vol.copy(), np.full(self.dim, h)

    @staticmethod
    def check_body(t, method, given):
        """The [[bodies]] keys a mesh body may not have; returns the seeding kind."""
        if given:
            raise ConfigError(t.key(given[0]), "a mesh body is seeded per element (ppe), "
                              "not by ppc, spacing or count")
        if method != "mpm":
            raise ConfigError(t.key("method"), "mesh bodies are MPM bodies in this version")
        return ["mesh"]


def mesh_geometry(t, dim, base_dir=None):
    """The geometry of a [[bodies]] table with shape = "mesh" (keys file, ppe)."""
    name = t.string("file")
    ppe = t.number("ppe", 1, integer=True, min=1)
    path = name if os.path.isabs(name) else os.path.join(base_dir or os.getcwd(), name)
    return MeshGeometry.from_file(os.path.normpath(path), dim, ppe, key=t.key("file"))
