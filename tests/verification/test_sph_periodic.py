"""Periodic axes of SPH scenes (`[domain] periodic = ["x"]`; parallel/particle_halo.py
images, the wrap in physics/sph/stage.py) and the analytic viscous flow of issue 18.

1. A uniform fluid at rest in a doubly periodic box (no walls, no gravity) stays at rest:
   with images every particle has a full support; without them the edges would pull in.
2. Couette flow start-up (bench/scenes.py `sph_couette`: unit depth, the top wall sliding at
   U, periodic along the flow, nu = 0.5): the row-averaged u(y, t) against the series
   solution within 2 % of U at t = 0.1, 0.5 and 2.5 (steady). This is the proof that the
   no-slip dummy walls transmit shear (the Morris viscosity with the walls' ghost velocity
   2 v_wall - v~). Measured: 1.15 %, 0.55 %, 0.04 % (20 across), 0.97 %, 0.51 %, 0.04 %
   (40 across). The stress form (`laminar = "stress"`) does not hold this low-Reynolds
   flow: 8 %, 7 % and 36 % at 20 across (its viscous term is a first derivative of a first
   derivative, which leaves the odd-even particle mode without damping).
3. Bad input: a period that is not a whole number of spacings, one shorter than three kernel
   supports, periodic axes with total-Lagrangian SPH: exit 2 naming the key.
"""
import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph import Scene
from pmpmsph.bench.scenes import couette_exact, sph_couette
from pmpmsph.errors import ConfigError
from pmpmsph.parallel.distributor import Distributor

SELF = Distributor(MPI.COMM_SELF)


def _box(length=0.5, spacing=0.025, **sph):
    sc = Scene(2, domain=dict(min=[0.0, 0.0], max=[length, length], periodic=["x", "y"]),
               time=dict(end=0.05, cfl=0.25), sph=dict(kernel="wendland", h_factor=1.3, **sph),
               parallel=dict(balance_every=0))
    sc.material("water", model="tait", rho=1000.0, kappa=1000.0 * 100.0 / 7.0, gamma=7.0)
    sc.body(name="water", method="sph", material="water", shape="box", min=[0, 0],
            max=[length, length], spacing=spacing)
    return sc


def test_fluid_at_rest_in_a_periodic_box_stays_at_rest():
    sim = _box().simulation(dist=SELF)
    x0 = sim.particles["x"].copy()
    sim.run(max_steps=200)
    p = sim.particles
    assert np.abs(p["v"]).max() < 1e-12
    assert np.abs(p["x"] - x0).max() < 1e-12
    assert np.abs(p["rho"] / 1000.0 - 1.0).max() < 1e-12


@pytest.mark.parametrize("t", [0.1, 0.5, 2.5])
def test_couette_start_up_against_the_series(t):
    n, nu = 20, 0.5
    sim = sph_couette(n=n, nu=nu, end=t).simulation(dist=SELF)
    sim.run()
    p = sim.particles
    fluid = p["body"] == 0
    rows = np.floor(p["x"][fluid, 1] * n).astype(int)
    u = np.bincount(rows, p["v"][fluid, 0]) / np.bincount(rows)
    y = (np.arange(n) + 0.5) / n
    assert np.abs(u - couette_exact(y, sim.time, nu)).max() < 0.02


def test_wrapped_particles_stay_in_the_period():
    sim = sph_couette(n=20, end=0.5).simulation(dist=SELF)
    sim.run()
    x = sim.particles["x"][:, 0]
    assert x.min() >= 0.0 and x.max() <= 16 / 20


@pytest.mark.parametrize("kw,match", [
    (dict(length=0.51), "whole number"),
    (dict(length=0.1, spacing=0.025), "shorter than 6 h"),
    (dict(formulation="total"), "total-Lagrangian")])
def test_bad_periodic_input(kw, match):
    sph = {k: v for k, v in kw.items() if k == "formulation"}
    box = {k: v for k, v in kw.items() if k != "formulation"}
    with pytest.raises(ConfigError, match=match) as err:
        _box(**box, **sph).simulation(dist=SELF)
    assert err.value.key == "domain.periodic"
