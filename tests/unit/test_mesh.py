"""Bodies seeded from mesh files (meshio): particle volumes add up to the mesh's measure."""

import meshio
import numpy as np
import pytest

from pmpmsph import ConfigError, load_case_file
from pmpmsph.initial_particles import build_particles
from pmpmsph.scene.mesh import MeshGeometry

CASE_2D = """
dimension = 2
[grid]
length = [1.0, 1.0]
cells = [10, 10]
[materials.m]
model = "neo_hookean"
E = 1000.0
nu = 0.3
rho = 1000.0
[[bodies]]
material = "m"
shape = "mesh"
file = "{file}"
ppe = {ppe}
[time]
end = 0.01
dt = 1e-4
"""

CASE_3D = """
dimension = 3
[grid]
length = [1.0, 1.0, 1.0]
cells = [6, 6, 6]
[materials.m]
model = "neo_hookean"
E = 1000.0
nu = 0.3
rho = 1000.0
[[bodies]]
material = "m"
shape = "mesh"
file = "{file}"
ppe = {ppe}
[time]
end = 0.01
dt = 1e-4
"""


def mixed_2d_mesh(lo=(0.2, 0.2), hi=(0.8, 0.6), n=(6, 4), seed=0):
    """Rectangle meshed with quads on the left half and triangles on the right, interior
    nodes jiggled (the boundary stays straight, so the area is exactly the rectangle's)."""
    rng = np.random.default_rng(seed)
    xs = np.linspace(lo[0], hi[0], n[0] + 1)
    ys = np.linspace(lo[1], hi[1], n[1] + 1)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    pts = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    inner = ((X > lo[0]) & (X < hi[0]) & (Y > lo[1]) & (Y < hi[1])).ravel()
    h = min((hi[0] - lo[0]) / n[0], (hi[1] - lo[1]) / n[1])
    pts[inner, :2] += 0.2 * h * (rng.random((inner.sum(), 2)) - 0.5)

    def node(i, j):
        return i * (n[1] + 1) + j

    quads, tris = [], []
    for i in range(n[0]):
        for j in range(n[1]):
            a, b, c, d = node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)
            if i < n[0] // 2:
                quads.append([a, b, c, d])
            else:
                tris += [[a, b, c], [a, c, d]]
    cells = [("quad", np.array(quads)), ("triangle", np.array(tris)),
             ("line", np.array([[node(0, 0), node(1, 0)]]))]  # boundary cells are ignored
    area = (hi[0] - lo[0]) * (hi[1] - lo[1])
    return meshio.Mesh(pts, cells), area, len(quads) + len(tris)


def box_3d_mesh(kind, lo=(0.2, 0.25, 0.3), hi=(0.7, 0.65, 0.6), n=(3, 2, 2), seed=1):
    """Box of tetrahedra (6 per cube, Kuhn) or hexahedra, interior nodes jiggled."""
    rng = np.random.default_rng(seed)
    axes = [np.linspace(lo[a], hi[a], n[a] + 1) for a in range(3)]
    G = np.meshgrid(*axes, indexing="ij")
    pts = np.stack([g.ravel() for g in G], axis=1)
    inner = np.all([(G[a] > lo[a]) & (G[a] < hi[a]) for a in range(3)], axis=0).ravel()
    h = min((hi[a] - lo[a]) / n[a] for a in range(3))
    pts[inner] += 0.2 * h * (rng.random((inner.sum(), 3)) - 0.5)

    def node(i, j, k):
        return (i * (n[1] + 1) + j) * (n[2] + 1) + k

    cells = []
    for i, j, k in np.ndindex(*n):
        c = [node(i + a, j + b, k + d) for a, b, d in
             ((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1),
              (0, 1, 1))]
        if kind == "hexahedron":
            cells.append(c)
        else:  # Kuhn: 6 tetrahedra along the diagonal 0-6
            for path in ((1, 2), (3, 2), (3, 7), (4, 7), (4, 5), (1, 5)):
                cells.append([c[0], c[path[0]], c[path[1]], c[6]])
    vol = float(np.prod(np.subtract(hi, lo)))
    return meshio.Mesh(pts, [(kind, np.array(cells))]), vol, len(cells)


def write_case(tmp_path, template, mesh, ppe, name="part.msh", fmt="gmsh22"):
    folder = tmp_path / "case"
    folder.mkdir(exist_ok=True)
    meshio.write(str(folder / name), mesh, file_format=fmt, binary=False)
    path = folder / "case.toml"
    path.write_text(template.format(file=name, ppe=ppe))
    return str(path)


@pytest.mark.parametrize("ppe", [1, 4, 16])
def test_2d_gmsh_tri_quad_area(tmp_path, ppe):
    mesh, area, n_el = mixed_2d_mesh()
    case = load_case_file(write_case(tmp_path, CASE_2D, mesh, ppe))
    geom = case.bodies[0].geometry
    assert isinstance(geom, MeshGeometry)
    assert geom.measure() == pytest.approx(area, rel=1e-12, abs=0)
    p = build_particles(case)
    assert p.n_owned == n_el * ppe
    assert abs(p["vol0"].sum() - area) <= 1e-12 * area
    np.testing.assert_allclose(p["mass"], 1000.0 * p["vol0"])
    lo, hi = np.array([0.2, 0.2]), np.array([0.8, 0.6])
    assert np.all(p["x"] > lo) and np.all(p["x"] < hi)


@pytest.mark.parametrize("kind,ppe", [("tetra", 1), ("tetra", 8), ("hexahedron", 1),
                                      ("hexahedron", 8)])
def test_3d_gmsh_volume(tmp_path, kind, ppe):
    mesh, vol, n_el = box_3d_mesh(kind)
    case = load_case_file(write_case(tmp_path, CASE_3D, mesh, ppe))
    p = build_particles(case)
    assert p.n_owned == n_el * ppe
    assert abs(p["vol0"].sum() - vol) <= 1e-12 * vol


def test_centroid_and_split_of_single_elements(tmp_path):
    """ppe = 1: the centroid; a split tetrahedron's 8 children have equal volumes."""
    tri = np.array([[[0.0, 0.0], [3.0, 0.0], [0.0, 3.0]]])
    from pmpmsph.scene.mesh import element_particles

    x, v = element_particles("triangle", tri, 1)
    np.testing.assert_allclose(x, [[1.0, 1.0]])
    assert v[0] == pytest.approx(4.5)
    tet = np.array([[[0, 0, 0], [1, 0, 0], [0, 2, 0], [0, 0, 3]]], float)
    _, v8 = element_particles("tetra", tet, 8)
    np.testing.assert_allclose(np.abs(v8), 1.0 / 8.0, rtol=1e-13)
    # a trapezoid quad: centroid of area, not the vertex average
    quad = np.array([[[0.0, 0.0], [4.0, 0.0], [3.0, 1.0], [1.0, 1.0]]])
    xq, vq = element_particles("quad", quad, 1)
    assert vq[0] == pytest.approx(3.0)
    np.testing.assert_allclose(xq, [[2.0, 4.0 / 9.0]], rtol=1e-12)


def test_bad_mesh_files_name_the_key(tmp_path):
    folder = tmp_path / "case"
    folder.mkdir()
    path = folder / "case.toml"
    path.write_text(CASE_2D.format(file="missing.msh", ppe=1))
    with pytest.raises(ConfigError) as err:
        load_case_file(str(path))
    assert err.value.key == "bodies[0].file" and "does not exist" in err.value.reason
    (folder / "junk.msh").write_text("this is not a mesh\n")
    path.write_text(CASE_2D.format(file="junk.msh", ppe=1))
    with pytest.raises(ConfigError) as err:
        load_case_file(str(path))
    assert err.value.key == "bodies[0].file" and "cannot read" in err.value.reason
    mesh, _, _ = mixed_2d_mesh()
    with pytest.raises(ConfigError) as err:
        load_case_file(write_case(tmp_path, CASE_2D, mesh, 3))
    assert err.value.key == "bodies[0].ppe"
    tets, _, _ = box_3d_mesh("tetra")
    with pytest.raises(ConfigError) as err:  # a 2D body from a volume mesh
        load_case_file(write_case(tmp_path, CASE_2D, tets, 1, name="tets.msh"))
    assert err.value.key == "bodies[0].file" and "tetra" in err.value.reason


def test_cli_reports_bad_mesh_with_exit_2(tmp_path, capsys):
    from pmpmsph.cli import main

    folder = tmp_path / "case"
    folder.mkdir()
    path = folder / "case.toml"
    path.write_text(CASE_2D.format(file="nowhere/part.msh", ppe=1))
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "bodies[0].file" in err and "Traceback" not in err
