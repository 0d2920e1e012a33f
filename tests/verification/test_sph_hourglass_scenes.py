"""The hourglass control (`[sph] hourglass`, kernels/sph/hourglass.py) on the coupled scenes 9
and 10 (tests/verification/test_coupled.py runs them without it). Scene 11, the case it was
made for, is tests/verification/test_coupled_plate.py.

Scene 9 (copper bar, 1 MPa on the end particles, MPM ends and SPH middle, damped to rest;
expected strain -7.8125e-6), strain / expected of the 12 SPH particles:
  h = cell size (the seed's, 2 spacings), no control: 1.843 0.159 2.217 0.298 1.719 0.976 ...
      (the odd-even pattern of test_coupled.py's docstring, mean 1.202);
  h = cell size, kappa = 2: 0.987 ... 1.002 (mean 0.993); kappa = 5: 0.988 ... 1.001;
  h = 1.3 spacings, kappa = 2: 1.000 at every particle (as without the control).
Scene 10 (biaxial 1 MPa, 40 x 40, plain kernel as in cases/coupled_biaxial.toml), sigma on the
centre lines: kappa = 2: -1.001 ... -1.018 MPa (without: -1.000 ... -1.017).
"""
import sys
from pathlib import Path

import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph import load_case_file
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.simulation import Simulation

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "parallel"))
from scenes import coupled_stress_bar

EXPECTED = -1e6 / 128e9
ROOT = Path(__file__).resolve().parents[2]


def _bar_strain(h, kappa):
    sc = coupled_stress_bar(h=h)
    sc.set("sph.hourglass", kappa)
    sim = sc.simulation(dist=Distributor(MPI.COMM_SELF))
    sim.run()
    p = sim.particles
    order = np.argsort(p["x"][:, 0])
    assert list(p["method"][order]) == [0] * 4 + [1] * 12 + [0] * 4
    return ((p["F"][:, 0, 0] - 1.0)[order] / EXPECTED)[4:16]


def test_scene9_the_seeds_h_with_the_control_has_no_odd_even_pattern():
    s = _bar_strain(0.1, 2.0)
    print("strain / expected", s.round(3))
    assert np.all(np.abs(s - 1.0) < 0.015)
    assert s.mean() == pytest.approx(0.993, abs=0.002)
    s = _bar_strain(0.065, 2.0)
    assert np.all(np.abs(s - 1.0) < 1e-3)


def test_scene10_biaxial_with_the_control():
    sets = [("grid.cell_size", 0.05), ("grid.cells", [32, 32]), ("bodies[0].spacing", 0.025),
            ("loads[0].box.max", [0.05, 1.0]), ("loads[1].box.min", [0.95, 0.0]),
            ("loads[2].box.max", [1.0, 0.05]), ("loads[3].box.min", [0.0, 0.95]),
            ("sph.hourglass", 2.0)]
    case = load_case_file(ROOT / "cases" / "coupled_biaxial.toml", overrides=sets)
    sim = Simulation(case, dist=Distributor(MPI.COMM_SELF))
    sim.run()
    p = sim.particles
    x, s = p["x"], p["sigma"] / 1e6
    for axis, comp in ((1, 0), (0, 1)):  # sigma_xx on y = 1/2, sigma_yy on x = 1/2
        line = np.abs(x[:, axis] - 0.4875) < 0.005
        inner = line & (np.abs(x[:, 1 - axis] - 0.5) < 0.45)  # not the loaded layers
        vals = s[inner, comp, comp]
        assert np.all(np.abs(vals + 1.0) < 0.02), vals
        assert abs(vals.min() + 1.018) < 0.001 and abs(vals.max() + 1.001) < 0.001
    assert sim.diagnostics()["kinetic"] < 1e-5
