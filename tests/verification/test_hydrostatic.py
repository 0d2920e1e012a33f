"""Scene 15 (BENCHMARKS.md): hydrostatic water column at rest (MPM, Tait fluid), 2D.

A column 0.5 wide and H = 1 high in a slip-walled box starts stress-free under g = 9.81 and is
settled by grid damping (alpha_d = 20) over T = 2. Exact at rest: the pressure at a material
point is the weight of the water above it per unit width, rho0 g (H - Y) with Y the point's
initial height, whatever the equation of state (mass above a material point is conserved);
so sigma_yy = -rho0 g (H - Y), which is -rho g (h - y) to within the compression (~1 %).

Checked away from the free surface, in the lower three quarters of the column (Y < 0.75 H,
at least 5 cells below the surface): the stress averaged over each cell's particle rows
(2 per cell) within 3 % of the local exact value and every single particle within 8 %;
everywhere, including the surface cells, within 3 % of the bottom pressure rho0 g H;
sigma_xx = sigma_yy and no shear (a fluid at rest); particles do not drift (no sideways
motion, no motion over the last 0.5 s, settlement below 0.2 cells).
Measured (this build): GIMP cell averages within 0.08 %, single particles within 3.5 %
(the two rows of a cell alternate by about +-1.5 %), everywhere within 1.5 % of rho0 g H;
linear hats cell averages within 1.9 %, single particles within 6.2 %, everywhere 2.5 %
(the error grows towards the surface: cell averages -3.5 % at 0.8-0.85 H, -27 % in the top
cell). Quadratic/cubic B-splines do not settle here (kinetic energy 0.08 / 0.5 at T against
1e-6, particles sink through the slip floor by 0.6-0.8 cells, since a slip node does not
pin a B-spline field at the wall), so they are not part of this test.
"""
from pathlib import Path

import numpy as np
import pytest

from pmpmsph import load_case_file
from pmpmsph.simulation import Simulation

CASE = Path(__file__).resolve().parents[2] / "cases" / "hydrostatic_column.toml"
RHO0, G, H = 1000.0, 9.81, 1.0


def by_gid(sim, name):
    """A particle field in gid (seeding) order: the solver re-sorts its rows by grid cell."""
    p = sim.particles
    return p[name][np.argsort(p["gid"])]


@pytest.mark.parametrize("shape", ["gimp", "linear"])
def test_hydrostatic_column_at_rest(shape):
    sim = Simulation(load_case_file(CASE, overrides=[("mpm.shape", shape)]))
    h = sim.case.grid.cell_size[0]
    X = by_gid(sim, "x").copy()
    snap = {}

    def keep(s):
        if abs(s.time - 1.5) < 0.5 * s.dt:
            snap["x"] = by_gid(s, "x").copy()

    sim.run(on_step=keep)
    assert sim.time == pytest.approx(2.0)
    x, sig = by_gid(sim, "x"), by_gid(sim, "sigma")
    assert np.all(np.isfinite(x)) and np.all(np.isfinite(sig))
    p_bottom = RHO0 * G * H
    expected = -RHO0 * G * (H - X[:, 1])

    deep = X[:, 1] < 0.75 * H
    rel = (sig[deep, 1, 1] - expected[deep]) / np.abs(expected[deep])
    # cell averages: pair the particle rows that share a cell (2 per cell)
    cell_row = np.floor(X[:, 1] / h + 1e-9).astype(int)
    cell_err = []
    for r in np.unique(cell_row[deep]):
        sel = cell_row == r
        cell_err.append(sig[sel, 1, 1].mean() / expected[sel].mean() - 1)
    cell_err = np.array(cell_err)
    print(f"scene 15, {shape}: deep particles max |error| {np.abs(rel).max():.2%}, mean "
          f"{rel.mean():+.2%}; cell-row averages max |error| {np.abs(cell_err).max():.2%}; "
          f"all particles max |error| / (rho0 g H) "
          f"{np.abs(sig[:, 1, 1] - expected).max() / p_bottom:.2%}; kinetic energy "
          f"{sim.diagnostics()['kinetic']:.2e}")
    assert np.abs(cell_err).max() < 0.03
    assert np.abs(rel).max() < 0.08
    assert np.abs(sig[:, 1, 1] - expected).max() < 0.03 * p_bottom
    # a fluid at rest: isotropic stress, no shear
    assert np.abs(sig[:, 0, 0] - sig[:, 1, 1]).max() < 1e-3 * p_bottom
    assert np.abs(sig[:, 0, 1]).max() < 1e-3 * p_bottom
    # no drift: nothing moves sideways, nothing moves over the last half second, and the
    # vertical settlement is the compression (~0.5 % of H at most, i.e. < 0.2 cells)
    assert np.abs(x[:, 0] - X[:, 0]).max() < 1e-3 * h
    assert np.abs(x - snap["x"]).max() < 1e-4 * h
    assert np.abs(x[:, 1] - X[:, 1]).max() < 0.2 * h
    assert sim.diagnostics()["kinetic"] < 1e-6 * p_bottom * H * 0.5


def _undamped_column(hydrostatic):
    """The column without the grid damping, 0.5 s, started stress-free or hydrostatic."""
    sets = [("mpm.damping", 0.0), ("time.end", 0.5), ("mpm.hydrostatic", hydrostatic)]
    sim = Simulation(load_case_file(CASE, overrides=sets))
    X = by_gid(sim, "x").copy()
    vmax = [0.0]

    def watch(s):
        vmax[0] = max(vmax[0], float(np.abs(s.particles["v"]).max()))

    sim.run(on_step=watch)
    return sim, X, vmax[0]


def test_mpm_hydrostatic_start_is_at_rest():
    """`[mpm] hydrostatic = true` (issue 19, item 2): the MPM fluid starts at the Tait
    hydrostatic density and pressure below its top (physics/hydrostatic.py), so without
    any damping the column stays at rest; started stress-free it drops by its compression
    and rings. Measured (GIMP, 0.5 s): largest speed 2.2e-3 m/s against 0.35 m/s
    stress-free; the deep stress within 1.6 % of rho0 g (H - Y)."""
    sim, X, v_rest = _undamped_column(True)
    _, _, v_ring = _undamped_column(False)
    h = sim.case.grid.cell_size[0]
    x, sig = by_gid(sim, "x"), by_gid(sim, "sigma")
    deep = X[:, 1] < 0.75 * H
    expected = -RHO0 * G * (H - X[deep, 1])
    print(f"largest speed: hydrostatic start {v_rest:.3e}, stress-free {v_ring:.3e}; "
          f"deep stress error {np.abs(sig[deep, 1, 1] / expected - 1).max():.2%}")
    assert v_rest < 0.05 * v_ring
    assert np.abs(x - X).max() < 0.02 * h
    assert np.abs(sig[deep, 1, 1] / expected - 1).max() < 0.08


def test_mpm_hydrostatic_needs_an_mpm_fluid_and_gravity():
    from pmpmsph.errors import ConfigError
    from pmpmsph.scene_api import Scene

    with pytest.raises(ConfigError) as err:
        load_case_file(CASE, overrides=[("mpm.hydrostatic", True), ("gravity", [0.0, 0.0])])
    assert err.value.key == "mpm.hydrostatic"
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[10, 10]),
               time=dict(end=0.1, dt=1e-3), gravity=[0, -9.81], mpm=dict(hydrostatic=True))
    sc.material("steel", model="linear_elastic", E=1e6, nu=0.3, rho=1000.0)
    sc.body(name="block", material="steel", shape="box", min=[0.2, 0.2], max=[0.6, 0.6],
            ppc=2)
    with pytest.raises(ConfigError) as err:
        sc.case()
    assert err.value.key == "mpm.hydrostatic"


def _pressure_noise(sim, spacing):
    """std and mean of p / (rho0 g (H - y)) - 1 over the particles deeper than two spacings,
    H the top row plus half a spacing (issue 18's tank metric, as for SPH)."""
    p = sim.particles
    y = p["x"][:, 1]
    pressure = -np.trace(p["sigma"], axis1=1, axis2=2) / 3.0
    top = y.max() + 0.5 * spacing
    deep = y < top - 2.0 * spacing
    r = pressure[deep] / (RHO0 * G * (top - y[deep])) - 1.0
    return float(r.std()), float(r.mean())


@pytest.mark.parametrize("shape", ["gimp", "linear"])
def test_mpm_tank_pressure_noise_below_one_percent(shape):
    """Issue 18's hydrostatic tank in MPM: started hydrostatic (`[mpm] hydrostatic`), no
    damping, 1 s: the pressure noise (std of p / (rho0 g (h - y)) - 1 below the top two
    rows) stays below 1 %. Started stress-free and settled by the grid damping (the case),
    the same column ends at 3.9 % (GIMP) / 5.6 % (linear): the two particle rows of a cell
    alternate. Measured: GIMP 0.25 % (mean +0.66 %), linear 0.20 % (+0.72 %); GIMP with
    APIC 0.48 %. (Quadratic B-splines do not hold the column: module doc.)"""
    spacing = 0.025  # 2 particles per 0.05 cell
    sets = [("mpm.shape", shape), ("mpm.damping", 0.0), ("mpm.hydrostatic", True),
            ("time.end", 1.0)]
    sim = Simulation(load_case_file(CASE, overrides=sets))
    X = by_gid(sim, "x").copy()
    sim.run()
    std, mean = _pressure_noise(sim, spacing)
    print(f"{shape}: pressure noise {std:.4f}, mean {mean:+.4f}")
    assert std < 0.01
    assert abs(mean) < 0.01
    assert np.abs(by_gid(sim, "x") - X).max() < 0.05 * spacing

    settled = Simulation(load_case_file(CASE, overrides=[("mpm.shape", shape)]))
    settled.run()
    assert _pressure_noise(settled, spacing)[0] > 0.03
