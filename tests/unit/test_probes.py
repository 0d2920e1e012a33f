"""`[[probes]]` (config/probes.py, io/probe_sampling.py, io/probes.py; docs/probes.md):
numbers from a hydrostatic tank and a held column, the CSV, restart and bad input."""
import math

import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph.config.load import load_case_text
from pmpmsph.errors import ConfigError
from pmpmsph.io.diagnostics import read_diagnostics
from pmpmsph.io.probe_sampling import wendland
from pmpmsph.io.probes_plot import plot_probes
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.physics.hydrostatic import tait_hydrostatic_density
from pmpmsph.scene_api import Scene
from pmpmsph.simulation import Simulation

G = 9.81
KAPPA, RHO0, GAMMA, H = 140142.857, 1000.0, 7.0, 1.0
DEPTH_Y = (0.2, 0.4, 0.6, 0.8)


def _serial():
    return Distributor(MPI.COMM_SELF)


def tank_case(end=0.3, extra=""):
    """cases/sph_hydrostatic.toml (a 0.5 x 1 column of Tait water in dummy walls, spacing
    0.025, h = 0.05) started in the hydrostatic state, with probes at four heights, a gauge
    and the walls' force."""
    with open("cases/sph_hydrostatic.toml", encoding="utf-8") as fh:
        text = fh.read()
    text = text.replace("damping = 20.0", "damping = 20.0\nhydrostatic = true")
    text = text.replace("end = 2.0", f"end = {end}")
    for i, y in enumerate(DEPTH_Y):
        text += (f'\n[[probes]]\nname = "p{i}"\nkind = "point"\nposition = [0.25, {y}]\n'
                 'fields = ["pressure", "density", "velocity", "stress"]\n')
    text += ('\n[[probes]]\nname = "gauge"\nkind = "gauge"\nposition = [0.25]\n'
             '\n[[probes]]\nname = "tank"\nkind = "force"\nwalls = true\n' + extra)
    return load_case_text(text, name="tank")


def tait_pressure_at(y):
    """The exact hydrostatic pressure of the Tait column at height y (physics/hydrostatic.py:
    dp/dz = rho(p) g integrated from p = 0 at the top H)."""
    rho = tait_hydrostatic_density(RHO0, KAPPA, GAMMA, G, H - y)
    return KAPPA * ((rho / RHO0) ** GAMMA - 1.0)


@pytest.fixture(scope="module")
def tank_rows():
    sim = Simulation(tank_case(), dist=_serial(), write_output=False)
    sim.run()
    mass = float(sim.particles["mass"][: sim.particles.n_owned][
        sim.particles["body"][: sim.particles.n_owned] == 0].sum())
    return sim.probes.rows, mass, sim


def test_kernel_is_normalised():
    """The Wendland C2 kernel of the probes integrates to 1 in 1, 2 and 3 dimensions."""
    h = 0.3
    r = np.linspace(0.0, 2.0 * h, 200001)
    dr = r[1] - r[0]
    for dim, shell in ((1, 2.0 + 0 * r), (2, 2.0 * math.pi * r), (3, 4.0 * math.pi * r * r)):
        f = wendland(r, h, dim) * shell
        integral = dr * (f.sum() - 0.5 * (f[0] + f[-1]))
        assert abs(integral - 1.0) < 1e-8, dim
    assert wendland(np.array([2.0 * h, 3.0 * h]), h, 2).tolist() == [0.0, 0.0]


def test_probe_pressure_reads_the_hydrostatic_state(tank_rows):
    """Right after the hydrostatic start (step 1) the particles hold the exact Tait state,
    and the probes read it: pressure and density to 1e-4 relative at four depths (Shepard
    reproduces a linear field on the symmetric lattice; what is left is the curvature of the
    Tait profile and one step of motion; measured 1e-5 and 3e-7)."""
    rows, _, _ = tank_rows
    first = rows[1]
    assert first["step"] == 1
    for i, y in enumerate(DEPTH_Y):
        exact = tait_pressure_at(y)
        assert abs(first[f"p{i}_pressure"] / exact - 1.0) < 1e-4, (y, first[f"p{i}_pressure"])
        rho = tait_hydrostatic_density(RHO0, KAPPA, GAMMA, G, H - y)
        assert abs(first[f"p{i}_density"] / rho - 1.0) < 1e-6
        # a fluid's stress is isotropic: -p on the diagonal, no shear
        assert first[f"p{i}_syy"] == pytest.approx(-first[f"p{i}_pressure"], rel=1e-12)
        assert abs(first[f"p{i}_sxy"]) < 1e-9 * exact


def test_probe_pressure_stays_hydrostatic(tank_rows):
    """Over the run (0.3 s, two sound periods 4H/c0) the probe pressure stays within 2.5 % of
    rho0 g H of the exact one at every depth and row: what the weakly compressible column
    itself holds (its pressure waves, and an equilibrium 1 % of rho0 g H above the exact
    one at the bottom after settling, measured 1.3 % relative at y = 0.2; the probe reads the
    particles there: see the next test)."""
    rows, _, _ = tank_rows
    scale = RHO0 * G * H
    for row in rows[1:]:
        for i, y in enumerate(DEPTH_Y):
            assert abs(row[f"p{i}_pressure"] - tait_pressure_at(y)) < 0.025 * scale
    last = rows[-1]
    for i, y in enumerate(DEPTH_Y):
        assert abs(last[f"p{i}_pressure"] - tait_pressure_at(y)) < 0.015 * scale
        assert abs(last[f"p{i}_vx"]) < 1e-3 and abs(last[f"p{i}_vy"]) < 1e-2


def test_probe_reads_the_particles_around_it(tank_rows):
    """At the end the probe equals the mean pressure of the two particle rows around its
    height (y +- dp/2: 40 particles across the tank) to 0.1 % of rho0 g H."""
    rows, _, sim = tank_rows
    p = sim.particles
    n = p.n_owned
    water = p["body"][:n] == 0
    x = p["x"][:n][water]
    pressure = -np.trace(p["sigma"][:n][water], axis1=1, axis2=2) / 3.0
    for i, y in enumerate(DEPTH_Y):
        layer = np.abs(x[:, 1] - y) < 0.013
        assert layer.sum() == 40
        assert abs(rows[-1][f"p{i}_pressure"] - pressure[layer].mean()) < 1e-3 * RHO0 * G * H


def test_gauge_reads_the_water_height(tank_rows):
    """The gauge reads the column's height H = 1 (top row at H - dp/2) to 0.04 spacings
    (1e-3) at every row: the surface moves by the compression only (measured 4e-4)."""
    rows, _, _ = tank_rows
    for row in rows:
        assert abs(row["gauge_elevation"] - H) < 1e-3


def test_force_on_the_walls_is_the_weight(tank_rows):
    """The walls carry the water: the force on them is M g (mean over each row's step) to
    2.5 % while the start rings (measured -1.5 % at step 1, +0.5 % at 0.07 s) and 1e-3 over
    the last 50 steps (the column still rings a little: measured 4e-4); nan in the first
    row."""
    rows, mass, _ = tank_rows
    assert math.isnan(rows[0]["tank_fy"])
    weight = mass * G
    for row in rows[1:]:
        assert abs(row["tank_fy"] + weight) < 0.025 * weight
        assert abs(row["tank_fx"]) < 1e-6 * weight
    tail = np.mean([r["tank_fy"] for r in rows[-50:]])
    assert abs(tail + weight) < 1e-3 * weight


def _held_column(tmp_path, probes_every=None, checkpoint_every=0, end=0.06):
    """An elastic MPM column on a held foot (tests/unit/test_reaction.py), with a force probe
    on the constraint and a point probe in the column."""
    out = dict(diagnostics_every=1, checkpoint_every=checkpoint_every)
    if probes_every is not None:
        out["probes_every"] = probes_every
    sc = Scene(2, time=dict(end=end, cfl=0.3), gravity=[0.0, -G],
               grid=dict(origin=[0.0, 0.0], length=[1.0, 1.0], cells=[20, 20]), output=out,
               prescribed=[dict(body="col", box=dict(min=[0.0, 0.0], max=[1.0, 0.3]),
                                velocity=[0.0, 0.0])],
               probes=[dict(name="foot", kind="force", prescribed=0),
                       dict(name="mid", kind="point", position=[0.5, 0.5],
                            fields=["stress", "velocity"])])
    sc.material("rubber", model="neo_hookean", E=1e5, nu=0.3, rho=1000.0)
    sc.body(name="col", material="rubber", shape="box", min=[0.4, 0.2], max=[0.6, 0.8],
            spacing=0.025)
    return sc


def test_force_probe_equals_the_diagnostics_reaction(tmp_path):
    """With rows at the same steps, the probe's force on the [[prescribed]] foot is the
    diagnostics' reaction0 to the last bit (the same impulses, summed apart)."""
    sim = _held_column(tmp_path).simulation(dist=_serial(), out_dir=str(tmp_path),
                                            overwrite=True)
    sim.run()
    sim.close()
    diag = read_diagnostics(tmp_path / "diagnostics.csv")
    probes = read_diagnostics(tmp_path / "probes.csv")
    assert list(probes) == ["time", "step", "foot_fx", "foot_fy", "mid_sxx", "mid_syy",
                            "mid_szz", "mid_sxy", "mid_vx", "mid_vy"]
    assert np.array_equal(diag["step"], probes["step"]) and len(probes["step"]) > 10
    assert np.isnan(probes["foot_fy"][0])
    np.testing.assert_array_equal(probes["foot_fx"][1:], diag["reaction0_x"][1:])
    np.testing.assert_array_equal(probes["foot_fy"][1:], diag["reaction0_y"][1:])
    assert np.all(probes["foot_fy"][1:] > 0.0)  # the foot holds the column up
    assert probes["mid_syy"][-1] < 0.0  # in compression under its weight


def test_force_probe_on_its_own_interval(tmp_path):
    """probes_every = 0.01: rows at 0 and past each multiple of 0.01 and at the end; the
    force is the mean reaction over the row's interval: sum of the diagnostics reactions
    times their steps, over the interval."""
    sim = _held_column(tmp_path, probes_every=0.01).simulation(
        dist=_serial(), out_dir=str(tmp_path), overwrite=True)
    sim.run()
    sim.close()
    diag = read_diagnostics(tmp_path / "diagnostics.csv")
    probes = read_diagnostics(tmp_path / "probes.csv")
    t = probes["time"]
    assert t[0] == 0.0 and t[-1] == pytest.approx(0.06)
    marks = np.floor(t / 0.01 + 1e-9)
    assert np.all(np.diff(marks[:-1]) == 1)  # one row per multiple (the end may share one)
    steps = list(diag["step"])
    dt = np.diff(diag["time"])
    for k in range(1, len(t)):
        a, b = steps.index(probes["step"][k - 1]), steps.index(probes["step"][k])
        mean = np.dot(diag["reaction0_y"][a + 1: b + 1], dt[a:b]) / (t[k] - t[k - 1])
        assert probes["foot_fy"][k] == pytest.approx(mean, rel=1e-10)


def test_restart_continues_probes_csv(tmp_path):
    """A run stopped at step 30 with a checkpoint and restarted writes the uninterrupted
    run's probes.csv: the same steps, no row twice, values equal (same rank count: bit for
    bit up to the CSV's round-trip floats)."""
    ref_dir, run_dir = tmp_path / "ref", tmp_path / "run"
    ref = _held_column(ref_dir).simulation(dist=_serial(), out_dir=str(ref_dir))
    ref.run()
    ref.close()
    first = _held_column(run_dir, checkpoint_every=30).simulation(dist=_serial(),
                                                                  out_dir=str(run_dir))
    first.run(max_steps=30)
    first.close()
    again = Simulation(_held_column(run_dir, checkpoint_every=30).case(), dist=_serial(),
                       write_output=False)
    again.restore_checkpoint(str(run_dir / "checkpoint.h5"))
    assert again.open_restart_output(str(run_dir))
    again.run()
    again.close()
    a = read_diagnostics(ref_dir / "probes.csv")
    b = read_diagnostics(run_dir / "probes.csv")
    assert len(set(b["step"])) == len(b["step"])
    assert np.array_equal(a["step"], b["step"])
    for key in a:
        np.testing.assert_allclose(b[key], a[key], rtol=1e-12, atol=0.0, equal_nan=True,
                                   err_msg=key)


def test_plot_probes(tmp_path):
    pytest.importorskip("matplotlib")
    (tmp_path / "probes.csv").write_text("time,step,a_b_pressure,g_elevation,f_fx,f_fy\n"
                                         "0.0,0,1.0,0.5,nan,nan\n0.1,1,2.0,0.6,1.0,2.0\n")
    out = plot_probes(str(tmp_path))
    assert out.endswith("probes.png") and (tmp_path / "probes.png").stat().st_size > 1000


def test_no_probes_no_object():
    sim = _held_column(None).simulation(dist=_serial(), write_output=False)
    assert sim.probes is not None
    sc = _held_column(None)
    del sc.data["probes"]
    plain = sc.simulation(dist=_serial(), write_output=False)
    assert plain.probes is None and plain.prescribed.tap is None


BAD = [
    ({"kind": "probe", "position": [0.5, 0.5]}, "probes[0].kind"),
    ({"kind": "point", "position": [0.5, 1.5]}, "probes[0].position[1]"),
    ({"kind": "point", "position": [0.5]}, "probes[0].position"),
    ({"kind": "point", "position": [0.5, 0.5], "fields": ["pressure", "heat"]},
     "probes[0].fields[1]"),
    ({"kind": "point", "position": [0.5, 0.5], "fields": []}, "probes[0].fields"),
    ({"kind": "point", "position": [0.5, 0.5], "body": "nope"}, "probes[0].body"),
    ({"kind": "point", "position": [0.5, 0.5], "colour": 1}, "probes[0].colour"),
    ({"kind": "point", "position": [0.5, 0.5], "name": "1st"}, "probes[0].name"),
    ({"kind": "gauge", "position": [2.0]}, "probes[0].position[0]"),
    ({"kind": "gauge", "position": [0.5], "bottom": 0.6, "top": 0.4}, "probes[0].top"),
    ({"kind": "gauge", "position": [0.5], "step": 1e-9}, "probes[0].step"),
    ({"kind": "force", "prescribed": 1}, "probes[0].prescribed"),
    ({"kind": "force"}, "probes[0].prescribed"),
    ({"kind": "force", "walls": True}, "probes[0].walls"),  # MPM scene, no SPH walls
    ({"kind": "force", "prescribed": 0, "h": 0.1}, "probes[0].h"),
]


@pytest.mark.parametrize("probe,key", BAD)
def test_bad_probe_names_the_key(probe, key):
    sc = _held_column(None)
    sc.data["probes"] = [probe]
    with pytest.raises(ConfigError) as err:
        sc.case()
    assert err.value.key == key


def test_probes_every_without_probes():
    sc = _held_column(None, probes_every=0.1)
    del sc.data["probes"]
    with pytest.raises(ConfigError) as err:
        sc.case()
    assert err.value.key == "output.probes_every"


def test_walls_force_refused_with_a_damping_zone():
    text = ('\n[[damping]]\nbox = { min = [0.0, 0.0], max = [0.1, 1.0] }\n'
            'direction = "x-"\n')
    with pytest.raises(ConfigError) as err:
        tank_case(extra=text)
    assert err.value.key == "probes[5].walls"


class _Rows(dict):
    """The few particle fields the sampler reads, as a stand-in for a ParticleSet."""

    def __init__(self, x, vol, sigma, v):
        n = len(x)
        super().__init__(x=x, vol=vol, mass=1000.0 * vol, sigma=sigma, v=v,
                         body=np.zeros(n, np.int32), method=np.zeros(n, np.int8))
        self.n_owned = n


def test_sampler_in_3d_reads_a_linear_field_and_the_surface():
    """A 3D lattice (spacing 0.05, 1 x 1 x 0.6, gravity along -z) with the stress of a
    linear pressure field: a point probe away from the faces reads it to round-off (the
    symmetric lattice), a gauge at (x, y) reads the top, z = 0.6, to 0.02 spacings."""
    sc = Scene(3, grid=dict(origin=[0, 0, 0], length=[1, 1, 1], cells=[10, 10, 10]),
               time=dict(end=0.1, dt=1e-3), gravity=[0, 0, -G],
               probes=[dict(name="p", kind="point", position=[0.5, 0.45, 0.3],
                            fields=["pressure", "velocity"]),
                       dict(name="g", kind="gauge", position=[0.4, 0.6])])
    sc.material("water", model="tait", rho=1000.0, kappa=2e5, gamma=7.0, mu=0.0)
    sc.body(name="water", material="water", shape="box", min=[0, 0, 0], max=[1, 1, 0.6],
            spacing=0.05)
    case = sc.case()
    dx = 0.05
    axes = [np.arange(dx / 2, top, dx) for top in (1.0, 1.0, 0.6)]
    x = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
    pressure = 1000.0 + 200.0 * x[:, 0] - 50.0 * x[:, 1] + 9810.0 * (0.6 - x[:, 2])
    sigma = -pressure[:, None, None] * np.eye(3)
    v = np.stack([x[:, 2], -x[:, 0], np.zeros(len(x))], -1)
    from pmpmsph.io.probe_sampling import ProbeSampler  # noqa: PLC0415 - with the stand-in

    sampler = ProbeSampler(case, _Rows(x, np.full(len(x), dx ** 3), sigma, v))
    assert sampler.hs[0] == pytest.approx(0.1)  # MPM scene: the cell size
    row = sampler.values(sampler.local(), 0.0, 0)
    exact = 1000.0 + 200.0 * 0.5 - 50.0 * 0.45 + 9810.0 * 0.3
    assert row["p_pressure"] == pytest.approx(exact, rel=1e-12)
    assert row["p_vx"] == pytest.approx(0.3, rel=1e-12)
    assert row["p_vy"] == pytest.approx(-0.5, rel=1e-12)
    assert abs(row["g_elevation"] - 0.6) < 0.02 * dx
