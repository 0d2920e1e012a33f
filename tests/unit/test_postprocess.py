"""`python -m pmpmsph plot RUN` and `vtu RUN`: a PNG of the diagnostics, VTU per snapshot."""
import os
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest

from pmpmsph import Scene
from pmpmsph.cli import main
from pmpmsph.io import list_snapshots, read_snapshot


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    out = str(tmp_path_factory.mktemp("post") / "run")
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[10, 10]),
               time=dict(end=0.02, dt=1e-3), gravity=[0, -9.81],
               output=dict(every_steps=10))
    sc.material("m", model="neo_hookean", E=1e4, nu=0.3, rho=1000.0)
    sc.body(name="b", material="m", shape="box", min=[0.3, 0.3], max=[0.7, 0.6], ppc=2)
    sim = sc.simulation(out_dir=out)
    sim.run()
    sim.close()
    return out


def test_plot_writes_png(run_dir):
    assert main(["plot", run_dir]) == 0
    png = os.path.join(run_dir, "diagnostics.png")
    with open(png, "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n"
    assert os.path.getsize(png) > 10_000
    other = os.path.join(run_dir, "other.png")
    assert main(["plot", run_dir, "-o", other]) == 0 and os.path.exists(other)
    assert main(["plot", os.path.join(run_dir, "missing")]) == 2


def test_vtu_export_reads_back(run_dir):
    assert main(["vtu", run_dir]) == 0
    infos = list_snapshots(os.path.join(run_dir, "particles.h5"))
    assert [i.step for i in infos] == [0, 10, 20]
    folder = os.path.join(run_dir, "vtu")
    for info in infos:
        mesh = meshio.read(os.path.join(folder, f"particles_{info.step:08d}.vtu"))
        _, _, data = read_snapshot(os.path.join(run_dir, "particles.h5"), info.index)
        assert len(mesh.points) == info.n_total == 48
        np.testing.assert_array_equal(mesh.points, data["x"])
        assert mesh.cells[0].type == "vertex" and len(mesh.cells[0].data) == 48
        # sigma is stored as 6 float32 components; the VTU has the full row-major tensor
        sigma = mesh.point_data["sigma"]
        assert sigma.shape == (48, 9) and sigma.dtype == np.float32
        np.testing.assert_array_equal(sigma, data["sigma"].reshape(-1, 9))
        np.testing.assert_array_equal(sigma[:, [1, 2, 5]], sigma[:, [3, 6, 7]])
        np.testing.assert_array_equal(mesh.point_data["gid"], data["gid"])
    pvd = ET.parse(os.path.join(folder, "particles.pvd")).getroot()
    assert [float(d.get("timestep")) for d in pvd.iter("DataSet")] == [i.time for i in infos]
    # one step only, to another folder
    other = os.path.join(run_dir, "one")
    assert main(["vtu", run_dir, "--step", "10", "--out", other]) == 0
    assert os.listdir(other) == ["particles_00000010.vtu"]
    assert main(["vtu", run_dir, "--step", "7"]) == 2


def test_xdmf_rebuild_from_run_folder(run_dir):
    xdmf = os.path.join(run_dir, "particles.xdmf")
    os.remove(xdmf)
    assert main(["xdmf", run_dir]) == 0
    grids = ET.parse(xdmf).getroot().findall("Domain/Grid/Grid")
    assert len(grids) == 3
