"""`pmpmsph.read(RUN)` (io/results.py) and `plot RUN --field` (pictures.py): snapshots sorted
by gid, a field's values and parts, and the pictures and movies written."""
import os

import numpy as np
import pytest
from PIL import Image

import pmpmsph
from pmpmsph import Scene
from pmpmsph.cli import main
from pmpmsph.io import read_snapshot
from pmpmsph.io.results import Snapshot
from pmpmsph.pictures import DPI, Frame, field_values


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    """A falling, spinning block: velocities and stresses that differ from particle to
    particle, three snapshots."""
    out = str(tmp_path_factory.mktemp("results") / "run")
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[10, 10]),
               time=dict(end=0.02, dt=1e-3), gravity=[0, -9.81],
               output=dict(every_steps=10))
    sc.material("m", model="neo_hookean", E=1e4, nu=0.3, rho=1000.0)
    sc.body(name="b", material="m", shape="box", min=[0.3, 0.3], max=[0.7, 0.6], ppc=2,
            velocity=[0.1, 0.0])
    sim = sc.simulation(out_dir=out)
    sim.run()
    sim.close()
    return out


def test_read_run(run_dir):
    run = pmpmsph.read(run_dir)
    assert len(run) == 3 and list(run.steps) == [0, 10, 20]
    np.testing.assert_allclose(run.times, [0.0, 0.01, 0.02], rtol=1e-12)
    last = run[-1]
    t, step, raw = read_snapshot(os.path.join(run_dir, "particles.h5"), -1)
    order = np.argsort(raw["gid"])
    assert (last.time, last.step) == (t, step)
    for k in raw:
        np.testing.assert_array_equal(last[k], raw[k][order], err_msg=k)
    x = run.series("x")
    assert x.shape == (3, len(order), 3)
    np.testing.assert_array_equal(x[2], last["x"])
    assert run.at_step(10).step == 10 and run.at_time(0.019).step == 20
    with pytest.raises(KeyError, match="no snapshot of step 7"):
        run.at_step(7)
    assert run.diagnostics["step"][-1] == 20
    assert run.probes == {}
    assert run.attrs["case_name"] and "sigma" in run.fields


def test_field_values_and_parts():
    sigma = np.zeros((2, 3, 3))
    sigma[0] = np.diag([-3.0, -6.0, -9.0])
    sigma[1, 0, 1] = sigma[1, 1, 0] = 2.0
    snap = Snapshot({"v": np.array([[3.0, 4.0, 0.0], [0.0, -1.0, 0.0]]), "sigma": sigma,
                     "rho": np.array([1.0, 2.0])}, 0.5, 5, 0)
    np.testing.assert_array_equal(field_values(snap, "speed")[0], [5.0, 1.0])
    np.testing.assert_array_equal(field_values(snap, "|v|")[0], [5.0, 1.0])
    np.testing.assert_array_equal(field_values(snap, "v.y")[0], [4.0, -1.0])
    np.testing.assert_array_equal(field_values(snap, "sigma.xy")[0], [0.0, 2.0])
    np.testing.assert_array_equal(field_values(snap, "rho")[0], [1.0, 2.0])
    np.testing.assert_allclose(field_values(snap, "pressure")[0], [6.0, 0.0], rtol=1e-15)
    # pure shear tau: von Mises sqrt(3) tau; the diagonal one: sqrt(3/2)|dev| = sqrt(27)
    np.testing.assert_allclose(field_values(snap, "mises")[0], [np.sqrt(27.0),
                                                                 2.0 * np.sqrt(3.0)])
    for bad, msg in (("T", "no field 'T'"), ("rho.x", "scalar"), ("v.q", "cannot take")):
        with pytest.raises(KeyError, match=msg):
            field_values(snap, bad)


def test_3d_slice_and_projection():
    """A 3x3x3 lattice of unit particles: the slice z = 1 keeps its middle layer, the xy
    projection keeps all, drawn farthest first (z ascending looks down -z)."""
    g = np.stack(np.meshgrid(*(np.arange(3.0),) * 3, indexing="ij"), -1).reshape(-1, 3)
    snap = Snapshot({"x": g, "mass": np.ones(27), "rho": np.ones(27), "gid": np.arange(27),
                     "h": g[:, 2]}, 0.0, 0, 0)
    cut = Frame(snap, "h", 3, "xy", slice_at=1.0)
    assert len(cut.values) == 9 and np.all(cut.values == 1.0)
    whole = Frame(snap, "h", 3, "xy")
    assert len(whole.values) == 27 and np.all(np.diff(whole.values) >= 0)
    halfway = Frame(snap, "h", 3, "xy", slice_at=1.5)  # between two layers: both
    assert sorted(set(halfway.values)) == [1.0, 2.0] and len(halfway.values) == 18
    snap["body"] = (g[:, 0] > 0).astype(int)  # body 0: the x = 0 face
    assert len(Frame(snap, "h", 3, "xy", bodies={1}).values) == 18
    side = Frame(snap, "h", 3, "xz", slice_at=0.0)
    assert len(side.values) == 9 and side.xy.shape == (9, 2)
    np.testing.assert_array_equal(np.sort(side.xy[:, 1]), np.repeat([0.0, 1.0, 2.0], 3))


def test_plot_field_pictures_and_movie(run_dir):
    assert main(["plot", run_dir, "--field", "v.norm"]) == 0
    png = os.path.join(run_dir, "v_norm_00000020.png")
    with Image.open(png) as im:
        assert im.size[0] == 8 * DPI and im.size[1] > 200
    assert main(["plot", run_dir, "--field", "pressure", "--step", "0", "--step", "10"]) == 0
    for step in (0, 10):
        assert os.path.exists(os.path.join(run_dir, f"pressure_{step:08d}.png"))
    assert main(["plot", run_dir, "--field", "sigma.xy", "--movie"]) == 0
    with Image.open(os.path.join(run_dir, "sigma_xy.gif")) as im:
        assert im.n_frames == 3
    assert main(["plot", run_dir, "--field", "rho", "--range", "900", "1100", "-o",
                 os.path.join(run_dir, "rho.png")]) == 0
    assert os.path.exists(os.path.join(run_dir, "rho.png"))
    assert main(["plot", run_dir, "--field", "nothing"]) == 2
    assert main(["plot", run_dir, "--field", "rho", "--step", "7"]) == 2
    assert main(["plot", run_dir, "--field", "rho", "--view", "xz"]) == 2  # a 2D run
    assert main(["plot", run_dir, "--field", "rho", "--slice", "0.5"]) == 2
    assert main(["plot", run_dir, "--field", "rho", "--body", "0", "-o",
                 os.path.join(run_dir, "body0.png")]) == 0
