"""HDF5 snapshots, XDMF sidecar and diagnostics CSV on one rank."""
import os
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest

from pmpmsph import ConfigError, load_case_text
from pmpmsph.io import (DiagnosticsCSV, SnapshotWriter, list_snapshots, read_attrs,
                        read_diagnostics, read_snapshot, rebuild_xdmf_main, write_xdmf)
from pmpmsph.io.h5files import GROUP, rank_file, snapshot_name
from pmpmsph.parallel.distributor import Distributor

TIMES = [0.0, 0.125, 1.0 / 3.0]
STEPS = [0, 7, 300]
COUNTS = [5, 11, 8]


@pytest.fixture(scope="module")
def dist():
    d = Distributor()
    if d.size != 1:  # the unit suite launched under mpirun: stay on one rank per process
        from mpi4py import MPI

        d = Distributor(MPI.COMM_SELF)
    return d


def make_fields(snap):
    n = COUNTS[snap]
    rng = np.random.default_rng(snap)
    return {
        "gid": rng.permutation(100)[:n].astype(np.int64),
        "x": rng.random((n, 3)),
        "v": rng.standard_normal((n, 3)).astype(np.float32),
        "sigma": rng.standard_normal((n, 3, 3)),
        "F": np.eye(3) + 0.1 * rng.standard_normal((n, 3, 3)),
        "mass": rng.random(n),
        "body": rng.integers(0, 4, n).astype(np.int32),
        "method": rng.integers(0, 2, n).astype(np.int8),
        "active": rng.random(n) > 0.5,
        "stress6": rng.standard_normal((n, 6)),
    }


def write_run(dist, path, **kw):
    kw.setdefault("case_text", "[time]\nend = 1.0\n")
    with SnapshotWriter(dist, path, attrs={"dim": 2, "title": "unit"}, **kw) as w:
        for snap in range(3):
            assert w.write(STEPS[snap], TIMES[snap], make_fields(snap)) == snap
    return path


def test_roundtrip_fields_and_attrs(dist, tmp_path):
    path = write_run(dist, str(tmp_path / "run.h5"))
    infos = list_snapshots(path)
    assert [i.name for i in infos] == ["000000", "000001", "000002"]
    assert [i.time for i in infos] == TIMES
    assert [i.step for i in infos] == STEPS
    assert [i.n_total for i in infos] == COUNTS
    for snap in range(3):
        t, step, data = read_snapshot(path, snap)
        assert (t, step) == (TIMES[snap], STEPS[snap])
        ref = make_fields(snap)
        assert list(data) == list(ref)  # written order is kept
        for k, a in ref.items():
            want = a.astype(np.uint8) if a.dtype == bool else a
            assert data[k].dtype == want.dtype, k
            assert data[k].shape == want.shape, k
            np.testing.assert_array_equal(data[k], want, err_msg=k)
    # index counts like a list; a subset of fields can be read
    t, step, data = read_snapshot(path, -1, fields=["mass", "gid"])
    assert t == TIMES[-1] and list(data) == ["mass", "gid"]
    with pytest.raises(KeyError):
        read_snapshot(path, 0, fields=["nope"])

    attrs = read_attrs(path)
    assert attrs["case"] == "[time]\nend = 1.0\n"
    assert attrs["n_ranks"] == 1 and attrs["layout"] == "serial"
    assert attrs["dim"] == 2 and attrs["title"] == "unit"
    assert attrs["code_version"] not in ("", None)
    with h5py.File(path, "r") as f:
        g = f["snapshots/000001"]
        assert g.attrs["time"] == TIMES[1] and g.attrs["step"] == STEPS[1]
        np.testing.assert_array_equal(g.attrs["counts"], [COUNTS[1]])
        assert g["sigma"].shape == (COUNTS[1], 3, 3)


def test_a_half_written_last_snapshot_is_left_out_and_dropped_on_append(dist, tmp_path):
    """A run killed while it wrote a snapshot can leave its group without attributes (or with
    an object header cut short): the complete snapshots stay readable, and a restart
    appending to the file removes the leftover (by rewriting the file: unlinking it in
    place once crashed HDF5)."""
    path = write_run(dist, str(tmp_path / "run.h5"))
    with h5py.File(path, "r+") as f:
        f[GROUP].create_group(snapshot_name(3))  # created, nothing written yet
    assert [i.step for i in list_snapshots(path)] == STEPS
    assert read_snapshot(path, -1)[1] == STEPS[-1]
    with SnapshotWriter(dist, path, append=True, after_step=7) as w:
        assert w.write(8, 0.5, make_fields(2)) == 2
    assert [i.step for i in list_snapshots(path)] == [0, 7, 8]
    with h5py.File(path, "r") as f:
        assert sorted(f[GROUP].keys()) == [snapshot_name(i) for i in range(3)]
    # dropped by copying the kept snapshots into a fresh file (no unlink in the old one)
    assert read_attrs(path)["case"] == "[time]\nend = 1.0\n"
    assert not os.path.exists(path + ".tmp") and not os.path.exists(path + ".damaged")


def test_a_file_hdf5_cannot_read_leaves_a_new_file_of_the_complete_snapshots(
        dist, tmp_path, monkeypatch):
    """A kill while HDF5 flushed the file's metadata once left a link that the restart could
    not delete ("Couldn't delete link (memory allocation failed for on disk image buffer)";
    tests/parallel/test_faults.py, 2026-11-27), and once one whose unlinking crashed HDF5;
    the restart no longer unlinks (test above). Should the file fail to be read, the
    restart copies the complete snapshots up to its step into a new particles file, keeps
    the damaged one beside it, and goes on appending."""
    path = write_run(dist, str(tmp_path / "run.h5"))
    with h5py.File(path, "r+") as f:
        f[GROUP].create_group(snapshot_name(3))  # a half-written group of the kill

    def fails(self, after_step):
        raise KeyError("Couldn't delete link (memory allocation failed for on disk image "
                       "buffer)")

    monkeypatch.setattr(SnapshotWriter, "_has_snapshots_to_drop", fails)
    with SnapshotWriter(dist, path, append=True, after_step=7) as w:
        assert w.write(8, 0.5, make_fields(2)) == 2
    assert [i.step for i in list_snapshots(path)] == [0, 7, 8]
    t, step, data = read_snapshot(path, 1)
    assert step == 7 and data["x"].shape == (COUNTS[1], 3)
    assert [i.step for i in list_snapshots(path + ".damaged")] == STEPS  # nothing lost
    assert read_attrs(path)["case"] == read_attrs(path + ".damaged")["case"]


def test_large_case_text_and_readable_between_writes(dist, tmp_path):
    case = "# long case\n" + "key = 1.0\n" * 20000  # 200 kB: beyond the compact attribute limit
    path = str(tmp_path / "big.h5")
    w = SnapshotWriter(dist, path, case_text=case)
    w.write(0, 0.0, make_fields(0))
    # The writer is still open: a reader sees a complete file (as after a crash).
    t, _, data = read_snapshot(path)
    assert t == 0.0 and data["x"].shape == (COUNTS[0], 3)
    w.write(1, 0.5, make_fields(1))
    assert len(list_snapshots(path)) == 2
    w.close()
    assert read_attrs(path)["case"] == case


def test_overwrite_refused_then_allowed(dist, tmp_path):
    path = write_run(dist, str(tmp_path / "run.h5"))
    with pytest.raises(FileExistsError):
        SnapshotWriter(dist, path)
    assert len(list_snapshots(path)) == 3  # untouched
    with SnapshotWriter(dist, path, overwrite=True) as w:
        w.write(1, 0.5, make_fields(2))
    infos = list_snapshots(path)
    assert len(infos) == 1 and infos[0].step == 1


def test_bad_fields_rejected(dist, tmp_path):
    w = SnapshotWriter(dist, str(tmp_path / "bad.h5"))
    f = make_fields(0)
    f["mass"] = f["mass"][:-1]
    with pytest.raises(ValueError, match="rows"):
        w.write(0, 0.0, f)
    f = make_fields(0)
    del f["x"]
    with pytest.raises(ValueError, match="'x'"):
        w.write(0, 0.0, f)
    f = make_fields(0)
    f["x"] = f["x"][:, :2]
    with pytest.raises(ValueError, match="'x'"):
        w.write(0, 0.0, f)
    with pytest.raises(ValueError):
        SnapshotWriter(dist, str(tmp_path / "m.h5"), mode="gather")
    # without the sidecar, positions are not required
    w2 = SnapshotWriter(dist, str(tmp_path / "nox.h5"), xdmf=False)
    w2.write(0, 0.0, {"mass": np.ones(3)})
    assert not os.path.exists(tmp_path / "nox.xdmf")


def check_xdmf_file(xdmf_path, h5_rel):
    """Parse the sidecar and check every DataItem against the HDF5 file it names."""
    tree = ET.parse(xdmf_path)
    root = tree.getroot()
    assert root.tag == "Xdmf" and root.get("Version") == "3.0"
    series = root.find("Domain/Grid")
    assert series.get("GridType") == "Collection"
    assert series.get("CollectionType") == "Temporal"
    grids = series.findall("Grid")
    assert len(grids) == 3
    folder = os.path.dirname(xdmf_path)
    types = {"Scalar": (), "Vector": (3,), "Tensor": (3, 3), "Tensor6": (6,)}
    for snap, grid in enumerate(grids):
        assert float(grid.find("Time").get("Value")) == TIMES[snap]
        topo = grid.find("Topology")
        assert topo.get("TopologyType") == "Polyvertex"
        assert int(topo.get("NumberOfElements")) == COUNTS[snap]
        # explicit connectivity 0..N-1 (the XDMF3 reader makes no cells without it)
        conn = topo.find("DataItem")
        fname, dpath = conn.text.strip().split(":")
        assert fname == h5_rel and dpath == f"/xdmf/polyvertex/{COUNTS[snap]}"
        assert conn.get("Dimensions") == str(COUNTS[snap])
        assert (conn.get("NumberType"), conn.get("Precision")) == ("Int", "4")
        with h5py.File(os.path.join(folder, fname), "r") as f:
            np.testing.assert_array_equal(f[dpath][()], np.arange(COUNTS[snap]))
        geom = grid.find("Geometry")
        assert geom.get("GeometryType") == "XYZ"
        items = [("x", "Vector", geom.find("DataItem"))]
        items += [(a.get("Name"), a.get("AttributeType"), a.find("DataItem"))
                  for a in grid.findall("Attribute")]
        ref = make_fields(snap)
        # geometry first, then every field as an attribute in the written order, x too (the
        # per-step positions for meshio's TimeSeriesReader, which reads one Geometry only)
        assert [name for name, _, _ in items] == ["x"] + list(ref)
        for name, atype, item in items:
            assert item.get("Format") == "HDF"
            fname, dpath = item.text.strip().split(":")
            assert fname == h5_rel  # relative to the sidecar
            assert dpath == f"/snapshots/{snap:06d}/{name}"
            dims = tuple(int(d) for d in item.get("Dimensions").split())
            with h5py.File(os.path.join(folder, fname), "r") as f:
                dset = f[dpath]
                assert dims == dset.shape
                kind = {"f": "Float", "i": "Int", "u": "UInt"}[dset.dtype.kind]
                if dset.dtype.itemsize == 1:
                    kind = {"Int": "Char", "UInt": "UChar"}[kind]
                assert item.get("NumberType") == kind
                assert int(item.get("Precision")) == dset.dtype.itemsize
            assert dims[0] == COUNTS[snap]
            assert dims[1:] == types[atype], (name, atype, dims)


def test_xdmf_sidecar_structure(dist, tmp_path):
    path = write_run(dist, str(tmp_path / "run.h5"))
    xdmf = str(tmp_path / "run.xdmf")
    assert os.path.exists(xdmf)  # written by the writer after every snapshot
    check_xdmf_file(xdmf, "run.h5")
    # a sidecar elsewhere refers to the file by a relative path
    other = tmp_path / "post" / "view.xdmf"
    other.parent.mkdir()
    assert write_xdmf(path, str(other)) == str(other)
    check_xdmf_file(str(other), "../run.h5")


def test_rebuild_xdmf_cli(dist, tmp_path, capsys):
    path = write_run(dist, str(tmp_path / "run.h5"))
    xdmf = tmp_path / "run.xdmf"
    before = xdmf.read_text()
    xdmf.unlink()
    assert rebuild_xdmf_main([path]) == 0
    assert xdmf.read_text() == before
    assert capsys.readouterr().out.strip() == str(xdmf)
    assert rebuild_xdmf_main([str(tmp_path / "missing.h5")]) == 2


def vtk_read_last(xdmf_path):
    """Read the sidecar with VTK's XDMF reader at the last time; returns (reader name,
    time steps, dataset)."""
    pytest.importorskip("vtkmodules", reason="vtk (a test dependency) is not installed")
    from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline

    try:  # the XDMF3 reader, when this VTK build has it (ParaView does; the pip wheel not)
        from vtkmodules.vtkIOXdmf3 import vtkXdmf3Reader as Reader
    except ImportError:
        from vtkmodules.vtkIOXdmf2 import vtkXdmfReader as Reader
    reader = Reader()
    reader.SetFileName(xdmf_path)
    reader.UpdateInformation()
    info = reader.GetOutputInformation(0)
    steps = list(info.Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS()))
    reader.UpdateTimeStep(steps[-1])
    out = reader.GetOutputDataObject(0)
    if out.IsA("vtkMultiBlockDataSet"):
        out = out.GetBlock(0)
    return Reader.__name__, steps, out


@pytest.mark.parametrize("mode", ["serial", "per-rank"])
def test_vtk_reads_xdmf(dist, tmp_path, mode):
    path = write_run(dist, str(tmp_path / "run.h5"), mode=mode)
    if mode == "per-rank":  # virtual datasets over run.r0.h5, resolved by VTK's HDF5
        assert os.path.exists(rank_file(path, 0))
        with h5py.File(path, "r") as f:
            assert f["snapshots/000002/x"].is_virtual
    name, steps, grid = vtk_read_last(str(tmp_path / "run.xdmf"))
    from vtkmodules.util.numpy_support import vtk_to_numpy

    np.testing.assert_allclose(steps, TIMES, rtol=0, atol=0)
    ref = make_fields(2)
    n = COUNTS[2]
    assert grid.GetNumberOfPoints() == n, name
    assert grid.GetNumberOfCells() == n, name
    for i in (0, n // 2, n - 1):  # one vertex cell per particle, cell i -> point i
        cell = grid.GetCell(i)
        assert cell.GetNumberOfPoints() == 1 and cell.GetPointId(0) == i
    np.testing.assert_array_equal(vtk_to_numpy(grid.GetPoints().GetData()), ref["x"])
    pd = grid.GetPointData()
    # VTK expands a symmetric Tensor6 (xx, xy, xz, yy, yz, zz) to a full 9-component tensor
    s6 = ref["stress6"]
    ref["stress6"] = s6[:, [0, 1, 2, 1, 3, 4, 2, 4, 5]]
    ncomp = {"gid": 1, "x": 3, "v": 3, "sigma": 9, "F": 9, "mass": 1, "body": 1, "method": 1,
             "active": 1, "stress6": 9}
    for key, nc in ncomp.items():
        arr = pd.GetArray(key)
        assert arr is not None, f"{name}: no point array {key}"
        assert arr.GetNumberOfComponents() == nc, (key, name)
        assert arr.GetNumberOfTuples() == n, (key, name)
        got = vtk_to_numpy(arr).reshape(n, -1)
        want = np.asarray(ref[key]).reshape(n, -1)
        np.testing.assert_array_equal(got, want.astype(got.dtype), err_msg=key)
    assert pd.GetArray("gid").GetDataTypeSize() == 8


def test_diagnostics_roundtrip(dist, tmp_path):
    path = str(tmp_path / "diag.csv")
    cols = ["time", "step", "dt", "kinetic", "strain", "total", "px", "py", "pz", "mass"]
    rng = np.random.default_rng(3)
    rows = []
    with DiagnosticsCSV(dist, path, cols) as d:
        for k in range(5):
            row = {c: float(v) for c, v in zip(cols, rng.standard_normal(len(cols)))}
            row["step"] = np.int64(10 * k)
            row["time"] = np.float64(k / 3.0)
            if k == 2:
                del row["pz"]  # a missing value reads back as nan
            d.append(row)
            rows.append(row)
            assert len(open(path).read().splitlines()) == k + 2  # flushed line by line
        with pytest.raises(KeyError):
            d.append({"energy": 1.0})
    table = read_diagnostics(path)
    assert list(table) == cols
    assert table["step"].dtype == np.int64
    np.testing.assert_array_equal(table["step"], [0, 10, 20, 30, 40])
    for c in cols:
        want = [r.get(c, np.nan) for r in rows]
        np.testing.assert_array_equal(table[c], np.array(want, dtype=table[c].dtype), err_msg=c)
    assert np.isnan(table["pz"][2])

    with pytest.raises(FileExistsError):
        DiagnosticsCSV(dist, path, cols)
    with DiagnosticsCSV(dist, path, cols, append=True) as d:  # a restarted run continues
        d.append({"time": 2.0, "step": 50})
    assert len(read_diagnostics(path)["step"]) == 6
    with pytest.raises(ValueError):
        DiagnosticsCSV(dist, path, ["time"], append=True)
    with DiagnosticsCSV(dist, path, ["time"], overwrite=True) as d:
        d.append({"time": 1.5})
    assert list(read_diagnostics(path)) == ["time"]
    assert read_diagnostics(path)["time"].tolist() == [1.5]
    # a line cut short by a crash is ignored
    with open(path, "a") as fh:
        fh.write("2.5\n3.0,")
    assert read_diagnostics(path)["time"].tolist() == [1.5, 2.5]


# -- single precision and packed symmetric tensors ---------------------------------------------
def symmetric_fields(snap):
    """make_fields with a symmetric sigma (a stress is; the writer keeps its upper triangle)."""
    f = make_fields(snap)
    f["sigma"] = 0.5 * (f["sigma"] + f["sigma"].transpose(0, 2, 1))
    return f


@pytest.mark.parametrize("mode", ["serial", "per-rank"])
def test_single_precision_and_symmetric_sigma(dist, tmp_path, mode):
    path = str(tmp_path / "run.h5")
    with SnapshotWriter(dist, path, mode=mode, precision="single", symmetric=("sigma",)) as w:
        for snap in range(3):
            w.write(STEPS[snap], TIMES[snap], symmetric_fields(snap))
    ref = symmetric_fields(2)
    n = COUNTS[2]
    _, _, data = read_snapshot(path, 2)
    for k, want in ref.items():
        if want.dtype.kind == "f":  # every float field: float32, the double rounded once
            assert data[k].dtype == np.float32, k
            np.testing.assert_array_equal(data[k], want.astype(np.float32), err_msg=k)
        else:  # ids and flags keep their type, exactly
            np.testing.assert_array_equal(data[k], want.astype(data[k].dtype), err_msg=k)
            assert data[k].dtype == (np.uint8 if want.dtype == np.bool_ else want.dtype), k
    assert data["sigma"].shape == (n, 3, 3)
    # float32 is within half an ulp of the double: relative 2**-24
    assert np.max(np.abs(data["x"] - ref["x"]) / np.abs(ref["x"])) <= 2.0**-24
    # stored: 6 components xx, xy, xz, yy, yz, zz with the order as an attribute
    _, _, packed = read_snapshot(path, 2, fields=["sigma"], packed=True)
    s = ref["sigma"].astype(np.float32)
    np.testing.assert_array_equal(
        packed["sigma"], np.stack([s[:, 0, 0], s[:, 0, 1], s[:, 0, 2], s[:, 1, 1], s[:, 1, 2],
                                   s[:, 2, 2]], axis=1))
    with h5py.File(path, "r") as f:
        dset = f["snapshots/000002/sigma"]
        assert dset.shape == (n, 6) and dset.dtype == np.float32
        assert dset.attrs["symmetric"] == "xx xy xz yy yz zz"
        assert "symmetric" not in f["snapshots/000002/F"].attrs
        assert f["snapshots/000002/F"].shape == (n, 3, 3)
    # the sidecar declares it as a Tensor6 of 4-byte floats
    attrs = {a.get("Name"): a for a in ET.parse(str(tmp_path / "run.xdmf")).getroot()
             .findall("Domain/Grid/Grid")[2].findall("Attribute")}
    item = attrs["sigma"].find("DataItem")
    assert attrs["sigma"].get("AttributeType") == "Tensor6"
    assert (item.get("Dimensions"), item.get("NumberType"), item.get("Precision")) == \
        (f"{n} 6", "Float", "4")
    # ... which VTK expands to the full symmetric tensor
    name, _, grid = vtk_read_last(str(tmp_path / "run.xdmf"))
    from vtkmodules.util.numpy_support import vtk_to_numpy

    got = vtk_to_numpy(grid.GetPointData().GetArray("sigma"))
    assert got.shape == (n, 9) and got.dtype == np.float32, name
    np.testing.assert_array_equal(got, s.reshape(n, 9))
    np.testing.assert_array_equal(vtk_to_numpy(grid.GetPoints().GetData()),
                                  ref["x"].astype(np.float32))


def test_precision_and_symmetric_are_checked(dist, tmp_path):
    with pytest.raises(ValueError, match="precision"):
        SnapshotWriter(dist, str(tmp_path / "a.h5"), precision="half")
    w = SnapshotWriter(dist, str(tmp_path / "b.h5"), symmetric=("sigma",), xdmf=False)
    with pytest.raises(ValueError, match="shape"):
        w.write(0, 0.0, {"sigma": np.zeros((4, 6))})
    w.write(0, 0.0, {"sigma": np.zeros((4, 3, 3))})
    with pytest.raises(ConfigError) as err:
        load_case_text(SCENE_CASE + 'precision = "float"\n')
    assert err.value.key == "output.precision"


SCENE_CASE = """
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
name = "block"
material = "m"
shape = "box"
min = [0.3, 0.3]
max = [0.6, 0.6]
ppc = 2
velocity = [0.05, 0.02]
[time]
end = 0.02
dt = 1e-3
[output]
every_steps = 10
"""


def test_run_snapshot_is_float32_of_the_state_and_checkpoint_is_exact(dist, tmp_path):
    """A run's default snapshot holds the double state rounded to float32 (sigma as its full
    3x3 tensor); the checkpoint of the same step is the float64 state bit for bit."""
    from pmpmsph.io.checkpoint import read_checkpoint
    from pmpmsph.simulation import Simulation

    case = load_case_text(SCENE_CASE)
    assert case.output.precision == "single"
    assert case.output.fields == ("gid", "method", "body", "x", "v", "mass", "rho", "sigma")
    sim = Simulation(case, dist=dist, out_dir=str(tmp_path / "run"))
    sim.run()
    ck = sim.write_checkpoint()
    sim.close()
    p, n = sim.particles, sim.particles.n_owned
    _, step, snap = read_snapshot(str(tmp_path / "run" / "particles.h5"), -1)
    assert step == sim.step_count == 20 and list(snap) == list(case.output.fields)
    assert np.abs(p["sigma"][:n]).max() > 0  # a deformed body: a real comparison
    state = {"gid": p["gid"][:n], "method": p["method"][:n], "body": p["body"][:n],
             "x": np.pad(p["x"][:n], ((0, 0), (0, 1))), "v": np.pad(p["v"][:n], ((0, 0), (0, 1))),
             "mass": p["mass"][:n], "rho": p["mass"][:n] / p["vol"][:n],
             "sigma": p["sigma"][:n]}
    for k, want in state.items():
        if want.dtype.kind == "f":
            assert snap[k].dtype == np.float32, k
            np.testing.assert_array_equal(snap[k], want.astype(np.float32), err_msg=k)
        else:
            assert snap[k].dtype == want.dtype, k
            np.testing.assert_array_equal(snap[k], want, err_msg=k)
    with h5py.File(str(tmp_path / "run" / "particles.h5"), "r") as f:
        dset = f["snapshots/000002/sigma"]  # full 9 components: every XDMF reader agrees
        assert dset.shape == (n, 3, 3) and "symmetric" not in dset.attrs
    _, rows = read_checkpoint(ck)
    for k in ("x", "v", "F", "sigma", "mass", "vol"):
        assert rows[k].dtype == np.float64, k
        np.testing.assert_array_equal(rows[k], p[k][:n], err_msg=k)
    # precision = "double" and extra fields by name
    case = load_case_text(SCENE_CASE + 'precision = "double"\nfields = ["gid", "x", "F"]\n')
    sim = Simulation(case, dist=dist, out_dir=str(tmp_path / "double"))
    sim.run(max_steps=3)
    sim.close()
    _, _, snap = read_snapshot(str(tmp_path / "double" / "particles.h5"), -1)
    assert list(snap) == ["gid", "x", "F"] and snap["F"].dtype == np.float64
    np.testing.assert_array_equal(snap["F"], sim.particles["F"][: sim.particles.n_owned])


def test_default_diagnostics_interval():
    """Every step up to 100,000 particles, every 100 steps above; a given value wins."""
    from pmpmsph.config.case import OutputSpec

    o = load_case_text(SCENE_CASE).output
    assert o.diagnostics_every is None
    assert [o.diagnostics_interval(n) for n in (1, 100_000, 100_001, 10**7)] == [1, 1, 100, 100]
    o = load_case_text(SCENE_CASE + "diagnostics_every = 7\n").output
    assert o.diagnostics_interval(10**7) == o.diagnostics_interval(1) == 7
    assert OutputSpec().diagnostics_interval(2_000_000) == 100


def test_particle_sums_tagged_equals_the_switch():
    """The one-material (tagged) strain energy gives the runtime switch's sums bit for bit."""
    from pmpmsph.initial_particles import material_arrays
    from pmpmsph.kernels.diagnostics import particle_sums
    from pmpmsph.materials.dispatch import material_tag

    rng = np.random.default_rng(5)
    n = 200
    x, v = rng.random((n, 2)), rng.standard_normal((n, 2))
    mass, vol0 = rng.random(n) + 0.5, rng.random(n) + 0.5
    F = np.eye(3) + 0.05 * rng.standard_normal((n, 3, 3))
    F[:, 2, :2] = F[:, :2, 2] = 0.0
    g = np.array([0.0, -9.81, 0.0])
    for model in ("neo_hookean", "tait", "linear_elastic"):
        extra = 'gamma = 7.0\nkappa = 1e5\n' if model == "tait" else "E = 1e4\nnu = 0.3\n"
        case = load_case_text(SCENE_CASE.replace(
            'model = "neo_hookean"\nE = 1000.0\nnu = 0.3\n', f'model = "{model}"\n{extra}'))
        mtypes, mparams = material_arrays(case)
        mat = np.zeros(n, dtype=np.int32)
        a, b = np.zeros(7), np.zeros(7)
        particle_sums(2, x, v, mass, vol0, F, mat, mtypes, mparams, np.zeros((n, 0)), g, a)
        tag = material_tag(mtypes)
        assert tag == ((0,) * (int(mtypes[0]) + 1),)  # the set of one model
        particle_sums(2, x, v, mass, vol0, F, mat, mtypes, mparams, np.zeros((n, 0)), g, b,
                      tag)
        assert a[1] != 0.0 and a.tolist() == b.tolist(), model
