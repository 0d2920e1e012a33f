"""The XDMF sidecar of a 2-rank run read back by meshio's TimeSeriesReader and by VTK's XDMF
reader (what ParaView uses) gives each snapshot's own positions and fields (issue 17).

meshio's TimeSeriesReader reads the Geometry of the first grid only, so the sidecar declares
``x`` as an attribute of every grid too; rows are matched between snapshots by ``gid`` (each
rank writes its own particles, so the row order is not fixed). Runs from the serial session
and starts its own `scripts/mpirun -n 2` (a test under mpirun cannot start another mpirun).
"""
import os
import subprocess
import sys

import numpy as np
import pytest

from pmpmsph.io import list_snapshots, read_snapshot

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = os.path.join(ROOT, "cases", "two_disks_contact.toml")
# 3000 steps of 632 particles, 4 snapshots: a few seconds once Numba's cache is warm
SETS = ["time.end=0.3", "output.every=0.1"]

pytestmark = pytest.mark.timeout(300)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """The README case on 2 ranks; returns its output folder."""
    if int(os.environ.get("OMPI_COMM_WORLD_SIZE", "1")) > 1:
        pytest.skip("starts its own mpirun: run it from the serial session")
    out = tmp_path_factory.mktemp("xdmf_meshio") / "run"
    sets = [a for s in SETS for a in ("--set", s)]
    cmd = [os.path.join(ROOT, "scripts", "mpirun"), "-n", "2", sys.executable, "-m", "pmpmsph",
           CASE, "--out", str(out), "--overwrite", "--progress", "1000000", *sets]
    # the timeout (below the test's) turns a hung run into a failure with its output
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, timeout=240,
                       env=dict(os.environ, PYTHONPATH=ROOT))
    assert r.returncode == 0, r.stdout + r.stderr
    return out


def by_gid(gid, *arrays):
    """The arrays with their rows in increasing gid (gid checked to be unique)."""
    gid = np.asarray(gid).reshape(-1)
    order = np.argsort(gid, kind="stable")
    assert np.all(np.diff(gid[order]) > 0), "gid repeats"
    return [gid[order]] + [np.asarray(a)[order] for a in arrays]


def test_meshio_time_series_gives_each_steps_positions(run):
    import meshio

    h5 = run / "particles.h5"
    infos = list_snapshots(h5)
    assert [i.step for i in infos] == [0, 1000, 2000, 3000]
    with meshio.xdmf.TimeSeriesReader(str(run / "particles.xdmf")) as reader:
        points0, cells = reader.read_points_cells()
        assert reader.num_steps == len(infos)
        assert cells[0].type == "vertex" and len(cells[0].data) == infos[0].n_total
        steps = [reader.read_data(k) for k in range(reader.num_steps)]
    first = None
    for info, (t, pd, _) in zip(infos, steps):
        assert t == info.time
        time, step, data = read_snapshot(h5, info.index, fields=["gid", "x", "v"])
        # matched by gid: the row order of a snapshot is the ranks' order, not the gids'
        gid, x, v = by_gid(pd["gid"], pd["x"], pd["v"])
        gid_h5, x_h5, v_h5 = by_gid(data["gid"], data["x"], data["v"])
        np.testing.assert_array_equal(gid, gid_h5)
        # the same float32 values: both read the dataset the run wrote (single precision)
        assert x.dtype == x_h5.dtype == np.float32
        np.testing.assert_array_equal(x, x_h5, err_msg=f"x of step {step}")
        np.testing.assert_array_equal(v, v_h5, err_msg=f"v of step {step}")
        if first is None:
            first = (gid, x)
            # read_points_cells() holds the first snapshot's positions, row for row
            np.testing.assert_array_equal(points0, pd["x"])
    # the disks move 0.03 along each axis by t = 0.3: step 3000's positions are its own (the
    # sidecar before issue 17 gave every step those of step 0)
    np.testing.assert_array_equal(gid, first[0])
    moved = np.linalg.norm(x - first[1], axis=1)
    assert moved.min() > 0.02, moved.min()
    assert not np.array_equal(pd["x"], points0)


def vtk_readers():
    """VTK's XDMF readers in this build: the XDMF2 reader of the pip wheel, and the XDMF3
    reader (ParaView's default) when the build has it."""
    pytest.importorskip("vtkmodules", reason="vtk (a test dependency) is not installed")
    readers = []
    try:
        from vtkmodules.vtkIOXdmf2 import vtkXdmfReader

        readers.append(vtkXdmfReader)
    except ImportError:
        pass
    try:
        from vtkmodules.vtkIOXdmf3 import vtkXdmf3Reader

        readers.append(vtkXdmf3Reader)
    except ImportError:
        pass
    if not readers:
        pytest.skip("this VTK build has no XDMF reader")
    return readers


def test_vtk_reads_the_last_step(run):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline

    h5 = run / "particles.h5"
    infos = list_snapshots(h5)
    _, _, data = read_snapshot(h5, -1, fields=["gid", "x"])
    _, _, data0 = read_snapshot(h5, 0, fields=["gid", "x"])
    gid_h5, x_h5 = by_gid(data["gid"], data["x"])
    for Reader in vtk_readers():
        reader = Reader()
        reader.SetFileName(str(run / "particles.xdmf"))
        reader.UpdateInformation()
        times = list(reader.GetOutputInformation(0).Get(
            vtkStreamingDemandDrivenPipeline.TIME_STEPS()))
        assert times == [i.time for i in infos], Reader.__name__
        reader.UpdateTimeStep(times[-1])
        out = reader.GetOutputDataObject(0)
        if out.IsA("vtkMultiBlockDataSet"):
            out = out.GetBlock(0)
        assert out.GetNumberOfPoints() == out.GetNumberOfCells() == infos[-1].n_total
        pd = out.GetPointData()
        points = vtk_to_numpy(out.GetPoints().GetData())
        gid, x, x_attr = by_gid(vtk_to_numpy(pd.GetArray("gid")), points,
                                vtk_to_numpy(pd.GetArray("x")))
        np.testing.assert_array_equal(gid, gid_h5, err_msg=Reader.__name__)
        np.testing.assert_array_equal(x, x_h5, err_msg=Reader.__name__)
        np.testing.assert_array_equal(x_attr, x_h5, err_msg=Reader.__name__)
        assert not np.array_equal(points, data0["x"]), Reader.__name__


def test_sidecar_without_gid_warns_once(tmp_path, caplog):
    """Rows of snapshots without gid cannot be matched between steps: the sidecar says so."""
    from mpi4py import MPI

    from pmpmsph.io import SnapshotWriter
    from pmpmsph.parallel.distributor import Distributor

    fields = {"x": np.zeros((4, 3)), "v": np.ones((4, 3))}
    with caplog.at_level("WARNING", logger="pmpmsph"):
        with SnapshotWriter(Distributor(MPI.COMM_SELF), str(tmp_path / "run.h5")) as w:
            for step in range(3):
                w.write(step, 0.1 * step, fields)
    warnings = [r for r in caplog.records if "no 'gid'" in r.getMessage()]
    assert len(warnings) == 1, [r.getMessage() for r in caplog.records]
