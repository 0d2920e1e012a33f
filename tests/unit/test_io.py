"""HDF5 snapshots, XDMF sidecar and diagnostics CSV on one rank."""
import os
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest

from pmpmsph.io import (DiagnosticsCSV, SnapshotWriter, list_snapshots, read_attrs,
                        read_diagnostics, read_snapshot, rebuild_xdmf_main, write_xdmf)
from pmpmsph.io.snapshots import rank_file
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
        # geometry first, then every other field as an attribute, in the written order
        assert [name for name, _, _ in items] == ["x"] + [k for k in ref if k != "x"]
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
    ncomp = {"gid": 1, "v": 3, "sigma": 9, "F": 9, "mass": 1, "body": 1, "method": 1,
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
