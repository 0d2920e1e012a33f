"""Collective snapshot output on 2 and 3 ranks equals the concatenation of the ranks' data.

Run as ``mpirun -n 2 python -m pytest tests/parallel/test_io_mpi.py -q`` (and ``-n 3``);
on one rank every test skips. Every rank runs the same collective calls in the same order;
assertions on rank 0 come after the last collective of a test, so a failure cannot leave
the other ranks waiting.
"""
import os

import numpy as np
import pytest

import pmpmsph

from pmpmsph.io import (DiagnosticsCSV, SnapshotWriter, list_snapshots, read_attrs,
                        read_diagnostics, read_snapshot)
from pmpmsph.io.h5files import rank_file
from pmpmsph.parallel.distributor import Distributor

pytestmark = [pytest.mark.mpi, pytest.mark.timeout(120)]


@pytest.fixture(scope="module")
def dist():
    d = Distributor()
    if d.size < 2:
        pytest.skip("needs mpirun with 2 or more ranks")
    return d


@pytest.fixture
def shared_dir(dist, request):
    """Rank 0's tmp_path, the same directory on every rank.

    Only rank 0 asks for tmp_path: several pytest processes creating and cleaning numbered
    temporary directories at once race with each other.
    """
    local = str(request.getfixturevalue("tmp_path")) if dist.is_root else None
    path = dist.bcast(local)
    dist.barrier()
    return path


def local_count(rank, size, snap):
    """Different counts per rank; the last rank owns nothing (and rank 0 owns nothing in
    the second snapshot)."""
    if rank == size - 1 or (snap == 1 and rank == 0):
        return 0
    return 3 + 4 * rank + snap


def local_fields(rank, size, snap):
    """Fields of this rank: gids interleaved over ranks so that sorting by gid is a real test."""
    n = local_count(rank, size, snap)
    rng = np.random.default_rng(1000 * snap + rank)
    gid = (np.arange(n, dtype=np.int64) * size + rank)[::-1].copy()
    return {
        "gid": gid,
        "x": rng.random((n, 3)),
        "v": rng.standard_normal((n, 3)),
        "sigma": rng.standard_normal((n, 3, 3)),
        "F": np.eye(3) + 0.01 * rng.standard_normal((n, 3, 3)),
        "mass": rng.random(n),
        "body": np.full(n, rank, dtype=np.int32),
        "method": (gid % 2).astype(np.int8),
        "flag": gid % 3 == 0,
    }


def expected(size, snap):
    parts = [local_fields(r, size, snap) for r in range(size)]
    out = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
    out["flag"] = out["flag"].astype(np.uint8)
    return out


def write_run(dist, path, mode):
    times = [0.0, 0.25, 0.5]
    with SnapshotWriter(dist, path, case_text="[run]\nname='mpi'\n", attrs={"dim": 3},
                        mode=mode) as w:
        for snap, t in enumerate(times):
            w.write(10 * snap, t, local_fields(dist.rank, dist.size, snap))
        assert w.mode == ("mpio" if mode == "auto" else mode)
    dist.barrier()
    return times


def check_run(dist, path, times, layout):
    """Rank 0 reads the file back and compares with the concatenated expectation."""
    attrs = read_attrs(path)
    assert attrs["layout"] == layout
    assert attrs["n_ranks"] == dist.size
    assert attrs["case"] == "[run]\nname='mpi'\n"
    infos = list_snapshots(path)
    assert [i.time for i in infos] == times
    assert [i.step for i in infos] == [0, 10, 20]
    for snap in range(len(times)):
        t, step, data = read_snapshot(path, snap)
        assert (t, step) == (times[snap], 10 * snap)
        ref = expected(dist.size, snap)
        assert list(data) == list(ref)
        assert infos[snap].n_total == len(ref["gid"])
        # The stored order is rank 0's slice, then rank 1's, ...: equal to the concatenation.
        for k in ref:
            assert data[k].dtype == ref[k].dtype, k
            np.testing.assert_array_equal(data[k], ref[k], err_msg=k)
        # ... and, independent of the rank order, equal after sorting by gid.
        a, b = np.argsort(data["gid"]), np.argsort(ref["gid"])
        for k in ref:
            np.testing.assert_array_equal(data[k][a], ref[k][b], err_msg=k)
    import h5py

    with h5py.File(path, "r") as f:
        counts = [local_count(r, dist.size, 1) for r in range(dist.size)]
        np.testing.assert_array_equal(f["snapshots/000001"].attrs["counts"], counts)
        assert f["snapshots/000001/sigma"].shape == (sum(counts), 3, 3)
        for info in infos:  # the Polyvertex connectivity, written slice by slice
            if info.n_total:
                np.testing.assert_array_equal(f[f"xdmf/polyvertex/{info.n_total}"][()],
                                              np.arange(info.n_total))
    check_xdmf(path, [i for i in infos if i.n_total > 0])
    check_reader(dist, path, times)


def check_reader(dist, path, times):
    """`pmpmsph.read` returns every snapshot sorted by gid, whatever the rows' rank order."""
    run = pmpmsph.read(path)
    assert len(run) == len(times)
    np.testing.assert_array_equal(run.times, times)
    np.testing.assert_array_equal(run.steps, [0, 10, 20])
    for snap, data in enumerate(run):
        ref = expected(dist.size, snap)
        order = np.argsort(ref["gid"])
        assert (data.time, data.step, data.index) == (times[snap], 10 * snap, snap)
        assert np.all(np.diff(data["gid"]) > 0)
        for k in ref:
            np.testing.assert_array_equal(data[k], ref[k][order], err_msg=k)
    # the same particles in the first two snapshots? no: counts differ, so series refuses
    with pytest.raises(ValueError, match="changes shape"):
        run.series("x")


def check_xdmf(path, infos):
    """The sidecar lists the non-empty snapshots; VTK reads the last one (when installed)."""
    import xml.etree.ElementTree as ET

    xdmf = os.path.splitext(path)[0] + ".xdmf"
    grids = ET.parse(xdmf).getroot().findall("Domain/Grid/Grid")
    assert [float(g.find("Time").get("Value")) for g in grids] == [i.time for i in infos]
    assert [int(g.find("Topology").get("NumberOfElements")) for g in grids] == \
        [i.n_total for i in infos]
    try:
        from vtkmodules.util.numpy_support import vtk_to_numpy
        from vtkmodules.vtkIOXdmf2 import vtkXdmfReader
    except ImportError:
        return
    reader = vtkXdmfReader()
    reader.SetFileName(xdmf)
    reader.UpdateInformation()
    reader.UpdateTimeStep(infos[-1].time)
    out = reader.GetOutputDataObject(0)
    _, _, data = read_snapshot(path, infos[-1].index)
    assert out.GetNumberOfPoints() == out.GetNumberOfCells() == infos[-1].n_total
    np.testing.assert_array_equal(vtk_to_numpy(out.GetPoints().GetData()), data["x"])
    # x is an attribute too (meshio's TimeSeriesReader reads the Geometry of one grid only)
    np.testing.assert_array_equal(vtk_to_numpy(out.GetPointData().GetArray("x")), data["x"])
    np.testing.assert_array_equal(vtk_to_numpy(out.GetPointData().GetArray("F")),
                                  data["F"].reshape(-1, 9))


def test_mpio_collective_write(dist, shared_dir):
    path = os.path.join(shared_dir, "run.h5")
    times = write_run(dist, path, "auto")
    if dist.is_root:
        check_run(dist, path, times, "mpio")
        assert os.path.exists(os.path.join(shared_dir, "run.xdmf"))
        assert not os.path.exists(rank_file(path, 0))


def test_per_rank_virtual_datasets(dist, shared_dir):
    path = os.path.join(shared_dir, "run.h5")
    times = write_run(dist, path, "per-rank")
    ok = None
    if dist.is_root:
        for r in range(dist.size):
            assert os.path.exists(rank_file(path, r))
        check_run(dist, path, times, "per-rank")
        import h5py

        with h5py.File(path, "r") as f:
            assert f["snapshots/000000/x"].is_virtual
            assert f["snapshots/000002/sigma"].is_virtual
        # The virtual datasets find the per-rank files next to the main file, from any cwd.
        cwd = os.getcwd()
        try:
            os.chdir("/")
            _, _, data = read_snapshot(path, 0)
            ok = np.array_equal(data["x"], expected(dist.size, 0)["x"])
        finally:
            os.chdir(cwd)
    assert dist.bcast(ok) in (True, np.True_)


def test_existing_file_refused_on_every_rank(dist, shared_dir):
    path = os.path.join(shared_dir, "run.h5")
    if dist.is_root:
        with open(path, "w") as fh:
            fh.write("old")
    dist.barrier()
    with pytest.raises(FileExistsError):
        SnapshotWriter(dist, path)
    # Overwriting replaces it, and all ranks agree.
    w = SnapshotWriter(dist, path, overwrite=True)
    w.write(0, 0.0, local_fields(dist.rank, dist.size, 0))
    w.close()
    dist.barrier()
    if dist.is_root:
        assert list_snapshots(path)[0].n_total == len(expected(dist.size, 0)["gid"])


def test_mismatched_fields_raise_on_every_rank(dist, shared_dir):
    path = os.path.join(shared_dir, "bad.h5")
    w = SnapshotWriter(dist, path)
    fields = local_fields(dist.rank, dist.size, 0)
    if dist.rank == 1:
        fields["mass"] = fields["mass"].astype(np.float32)
    with pytest.raises(ValueError, match="differ between ranks"):
        w.write(0, 0.0, fields)
    # The writer is still usable afterwards (no rank is stuck in a collective).
    w.write(0, 0.0, local_fields(dist.rank, dist.size, 0))
    dist.barrier()
    if dist.is_root:
        assert len(list_snapshots(path)) == 1


def test_all_ranks_empty(dist, shared_dir):
    path = os.path.join(shared_dir, "empty.h5")
    with SnapshotWriter(dist, path) as w:
        w.write(0, 0.0, {"gid": np.zeros(0, np.int64), "x": np.zeros((0, 3))})
    dist.barrier()
    if dist.is_root:
        _, _, data = read_snapshot(path)
        assert data["x"].shape == (0, 3) and data["gid"].shape == (0,)


def test_diagnostics_written_once(dist, shared_dir):
    path = os.path.join(shared_dir, "diag.csv")
    with DiagnosticsCSV(dist, path, ["time", "step", "kinetic"]) as d:
        for k in range(4):
            d.append({"time": 0.5 * k, "step": k, "kinetic": dist.sum(1.0) * k})
    dist.barrier()
    if dist.is_root:
        table = read_diagnostics(path)
        np.testing.assert_array_equal(table["step"], np.arange(4))
        np.testing.assert_array_equal(table["kinetic"], dist.size * np.arange(4.0))


def test_fallback_without_parallel_h5py(dist, shared_dir, monkeypatch, caplog):
    """With a serial h5py the writer picks per-rank files and says so once, on rank 0."""
    import types

    import h5py

    real = h5py.get_config()
    monkeypatch.setattr(h5py, "get_config",
                        lambda: types.SimpleNamespace(mpi=False, real=real))
    path = os.path.join(shared_dir, "fallback.h5")
    with caplog.at_level("WARNING", logger="pmpmsph"):
        w = SnapshotWriter(dist, path)
        w.write(3, 1.5, local_fields(dist.rank, dist.size, 2))
        w.close()
    dist.barrier()
    warnings = [r for r in caplog.records if "virtual datasets" in r.getMessage()]
    assert w.mode == "per-rank"
    assert len(warnings) == (1 if dist.is_root else 0)
    if dist.is_root:
        t, step, data = read_snapshot(path)
        assert (t, step) == (1.5, 3)
        np.testing.assert_array_equal(data["F"], expected(dist.size, 2)["F"])


@pytest.mark.parametrize("mode", ["auto", "per-rank"])
def test_single_precision_symmetric_sigma_on_n_ranks(dist, shared_dir, mode):
    """float32 snapshots with sigma as 6 components, written collectively (and per rank),
    with empty ranks: rank 0 reads back the concatenated doubles rounded to float32."""
    def fields(rank, snap):
        f = local_fields(rank, dist.size, snap)
        f["sigma"] = 0.5 * (f["sigma"] + f["sigma"].transpose(0, 2, 1))
        return f

    path = os.path.join(shared_dir, f"single_{mode}.h5")
    with SnapshotWriter(dist, path, mode=mode, precision="single", symmetric=("sigma",)) as w:
        for snap in range(3):
            w.write(snap, 0.5 * snap, fields(dist.rank, snap))
    dist.barrier()
    if dist.is_root:
        import h5py

        for snap in range(3):
            parts = [fields(r, snap) for r in range(dist.size)]
            ref = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
            _, _, data = read_snapshot(path, snap)
            assert list(data) == list(ref)
            for k, want in ref.items():
                if want.dtype.kind == "f":
                    assert data[k].dtype == np.float32, k
                    want = want.astype(np.float32)
                np.testing.assert_array_equal(data[k], want, err_msg=k)
        with h5py.File(path, "r") as f:
            dset = f["snapshots/000002/sigma"]
            assert dset.shape == (len(ref["gid"]), 6) and dset.dtype == np.float32
            assert dset.attrs["symmetric"] == "xx xy xz yy yz zz"
        check_xdmf(path, [i for i in list_snapshots(path) if i.n_total > 0])
