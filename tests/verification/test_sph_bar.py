"""Scene 8 (BENCHMARKS.md; seed 000 §5.1) in pure SPH: conservation and reversibility.

Copper bar on [0, 1] (rho = 8790, E = 128 GPa; 1D: c = sqrt(E/rho) = 3816 m/s), particle
spacing 0.05 (20 particles, free ends), initial velocity v(x, 0) = 0.01 c sin(10 pi x),
Courant number 0.1 (fixed dt = 0.1 h / c), 500 steps, all velocities reversed, 500 steps
more: the final velocity must be -v(x, 0) and the total energy conserved. No artificial
viscosity (it is dissipative and would break reversibility by design).

Measured (this build, h = 1.3 spacing / h = 0.1 = the paper's cell size):
  verlet (velocity Verlet with mid-step F by the implicit midpoint rule):
      reversal error max|v + v0|/max|v0| = 7.7e-13 / 8.9e-13, positions back to 2e-15;
      energy within 0.23 % / 0.08 % of its initial value throughout
  rk3 (TVD-RK3):            reversal 5.2e-3 / 2.5e-3, energy within 0.76 % / 0.13 %
  predictor_corrector:      reversal 3.2e-2 / 1.5e-2, energy within 4.8 % / 0.8 %
Only the Verlet step is time-reversible; the other two are accurate to their order.
"""
import sys
from pathlib import Path

import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph.parallel.distributor import Distributor

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "parallel"))
from scenes import sph_bar_1d  # noqa: E402

C = np.sqrt(128e9 / 8790.0)


def reversal(integrator, h=None, steps=500):
    sc = sph_bar_1d(integrator)
    if h is not None:
        sc.data["sph"].pop("h_factor")
        sc.data["sph"]["h"] = h
    sc.data["time"].pop("cfl")
    sc.data["time"]["dt"] = 0.1 * (h or 1.3 * 0.05) / C
    sim = sc.simulation(dist=Distributor(MPI.COMM_SELF))
    p = sim.particles
    x0 = p["x"][:, 0].copy()
    v0 = 0.01 * C * np.sin(10 * np.pi * x0)
    p["v"][:, 0] = v0
    e0 = sim.diagnostics()["total"]
    worst = 0.0
    for leg in range(2):
        for _ in range(steps):
            sim.step()
            worst = max(worst, abs(sim.diagnostics()["total"] / e0 - 1.0))
        if leg == 0:
            p["v"][:] *= -1.0
            sim.sph.evaluated = False  # rates again from the reversed state
    order = np.argsort(p["gid"])
    v_err = np.abs(p["v"][order, 0] + v0).max() / np.abs(v0).max()
    x_err = np.abs(p["x"][order, 0] - x0).max()
    return v_err, x_err, worst


@pytest.mark.parametrize("h", [None, 0.1])
def test_verlet_is_time_reversible_and_conserves_energy(h):
    v_err, x_err, drift = reversal("verlet", h)
    assert v_err < 1e-10
    assert x_err < 1e-12
    assert drift < 5e-3


def test_rk3_reversal_and_energy():
    v_err, _, drift = reversal("rk3")
    assert v_err < 1e-2
    assert drift < 1e-2


def test_predictor_corrector_reversal_and_energy_at_the_paper_smoothing_length():
    v_err, _, drift = reversal("predictor_corrector", h=0.1)
    assert v_err < 3e-2
    assert drift < 2e-2
