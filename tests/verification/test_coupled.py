"""Coupled MPM-SPH verification (seed 000 §5-6; BENCHMARKS.md scenes 8-10), each beside the
pure-MPM (and, where boundary conditions allow, pure-SPH) run of the same set-up.

Scene 9 — copper bar (cell 0.1, spacing 0.05) compressed by 1 MPa on its end particles
(MPM in [0, 0.2] and [0.8, 1], SPH inside), damped to rest. Expected strain -7.8125e-6.
  Measured: MPM particles exact (1.000 of the expected strain, 0.750 on the loaded end
  particles, which carry the load); SPH with h = 1.3 spacing exact (1.000) at every
  particle; with the seed's h = cell size (2 spacings) the SPH interior takes an odd-even
  (zero-energy) pattern of the cubic spline at q = 0.5 (strains 0.16 ... 2.2 x expected,
  mean 1.20 x expected): the seed's 1 % is NOT met with h = cell size, and is met exactly
  with h = 1.3 spacing. (Artificial viscosity alpha = beta = 1 damps the pattern to
  0.93 ... 1.07.)
  Pure SPH cannot take this load (no stress boundary in SPH: the point of the coupling).
Scene 10 — 1 x 1 plate, MPM rim 0.2 wide, SPH core, 1 MPa on the two outer particle
layers of every side (cases/coupled_biaxial.toml). Measured sigma_xx on the horizontal
centre line: 40 x 40 particles (cell 0.05): -1.000 ... -1.018 MPa (1.8 %), no step at the
MPM/SPH transitions (< 0.3 %); 20 x 20 (the seed's): -1.004 ... -1.032 (3.2 %) — the
loaded layers themselves carry less than 1 MPa, so the interior carries a little more, a
deficit that halves with the layer thickness.
Scene 8 — reversal and energy of v(x, 0) = 0.01 c sin(k pi x), 500 steps, reverse, 500:
  pure SPH (Verlet): reversal 9e-13, energy 8e-4 (test_sph_bar.py);
  pure MPM (MUSL, GIMP): k = 1: energy 1.6 %, reversal 1.6 %; k = 10 (the seed's, two cells
  per wavelength): energy 1.6 %, reversal 2.7 %;
  coupled (MUSL + Verlet, h = cell, dt = 0.1 spacing / c): k = 1: energy and reversal
  within 3 % (asserted); k = 10: energy drift 42 %, reversal 8 % — NOT conserved: the interface between the grid and the SPH
  region does not exchange a two-cell wave consistently (each side's force on the other
  comes from a different discretisation, so they are not equal and opposite).
"""
import sys
from pathlib import Path

import numpy as np
from mpi4py import MPI

from pmpmsph import load_case_file
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.simulation import Simulation

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "parallel"))
from scenes import coupled_bar_1d, coupled_stress_bar  # noqa: E402

EXPECTED = -1e6 / 128e9
C = np.sqrt(128e9 / 8790.0)
ROOT = Path(__file__).resolve().parents[2]


def _serial(sc):
    return sc.simulation(dist=Distributor(MPI.COMM_SELF))


def test_scene9_static_strain():
    """h = 1.3 spacing. With the seed's h = cell size (0.1) the SPH region's mean strain is
    1.20 x the expected one (odd-even mode, see the module docstring): not met; measure it
    with `coupled_stress_bar(h=0.1)` (tests/parallel/scenes.py)."""
    sim = _serial(coupled_stress_bar(h=0.065))
    sim.run()
    p = sim.particles
    order = np.argsort(p["x"][:, 0])
    strain = (p["F"][:, 0, 0] - 1.0)[order]
    meth = p["method"][order]
    assert list(meth) == [0] * 4 + [1] * 12 + [0] * 4
    mpm_inner = strain[2:4].tolist() + strain[-4:-2].tolist()
    assert np.all(np.abs(np.array(mpm_inner) / EXPECTED - 1) < 0.01)
    assert np.all(np.abs(strain[4:16] / EXPECTED - 1) < 0.01)  # every SPH particle


def test_scene10_biaxial_stress_in_both_regions():
    sets = [("grid.cell_size", 0.05), ("grid.cells", [32, 32]), ("bodies[0].spacing", 0.025),
            ("loads[0].box.max", [0.05, 1.0]), ("loads[1].box.min", [0.95, 0.0]),
            ("loads[2].box.max", [1.0, 0.05]), ("loads[3].box.min", [0.0, 0.95])]
    case = load_case_file(ROOT / "cases" / "coupled_biaxial.toml", overrides=sets)
    sim = Simulation(case, dist=Distributor(MPI.COMM_SELF))
    sim.run()
    p = sim.particles
    x, s, m = p["x"], p["sigma"] / 1e6, p["method"]
    for axis, comp in ((1, 0), (0, 1)):  # sigma_xx on y = 1/2, sigma_yy on x = 1/2
        line = np.abs(x[:, axis] - 0.4875) < 0.005
        inner = line & (np.abs(x[:, 1 - axis] - 0.5) < 0.45)  # not the loaded layers
        order = np.argsort(x[inner, 1 - axis])
        vals = s[inner, comp, comp][order]
        meth = m[inner][order]
        assert np.all(np.abs(vals + 1.0) < 0.02), vals
        assert set(meth) == {0, 1}
        jumps = np.nonzero(np.diff(meth))[0]
        assert np.all(np.abs(vals[jumps + 1] - vals[jumps]) < 0.02)
    assert sim.diagnostics()["kinetic"] < 1e-5


def _reversal(mode, k):
    sc = coupled_bar_1d(mode)
    sc.data["mpm"]["transfer"] = "musl"
    sc.data["time"].pop("cfl")
    sc.data["time"]["dt"] = 0.1 * 0.05 / C  # Courant 0.1 on the particle spacing
    sim = _serial(sc)
    p = sim.particles
    x0 = p["x"][:, 0].copy()
    v0 = 0.01 * C * np.sin(k * np.pi * x0)
    p["v"][:, 0] = v0
    gid0 = p["gid"].copy()
    e0 = sim.diagnostics()["total"]
    worst = 0.0
    for leg in range(2):
        for _ in range(500):
            sim.step()
            worst = max(worst, abs(sim.diagnostics()["total"] / e0 - 1.0))
        if leg == 0:
            p["v"][:] *= -1.0
            if sim.sph is not None:
                sim.sph.evaluated = False
    order = np.argsort(p["gid"])
    err = np.abs(p["v"][order, 0] + v0[np.argsort(gid0)]).max() / np.abs(v0).max()
    return err, worst


def test_scene8_reversal_smooth_mode_coupled_and_mpm():
    for mode in ("coupled", "mpm"):
        err, drift = _reversal(mode, 1)
        print(mode, err, drift)
        assert err < 0.03 and drift < 0.03


def test_handover_relabels_particles_that_cross_into_the_sph_region():
    from scenes import handover_bar

    sim = _serial(handover_bar())
    p = sim.particles
    n = p.n_owned
    x0 = p["x"][:, 0].copy()
    assert np.all(p["method"] == 0)
    m0 = p["mass"].sum()
    sim.run()
    t = sim.time
    assert np.all(p["method"] == 1)          # every particle crossed x = 0.6 and is SPH now
    assert sim.coupling.handed_over == n
    order = np.argsort(p["gid"])
    # a free rigid translation stays one: positions x0 + v t, velocity v, no strain
    assert np.allclose(p["x"][order, 0], x0 + 50.0 * t, rtol=0, atol=1e-9)
    assert np.allclose(p["v"][:, 0], 50.0, rtol=1e-9)
    assert np.allclose(p["F"][:, 0, 0], 1.0, atol=1e-9)
    assert p["mass"].sum() == m0
