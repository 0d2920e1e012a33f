"""SPH on N ranks equals SPH on one rank (DESIGN.md §4 invariant), to 1e-10 relative.

Run under `mpirun -n 2` and `-n 3`; the serial reference runs on MPI.COMM_SELF in the same
processes. Scenes: the copper bar of scene 8 (1D, all three integrators), the dam break
with dummy walls (2D, slab faces crossed by water and walls), and the rubber rings
(artificial stress).
"""
import numpy as np
import pytest

from mpi_util import assert_equals_one_rank, serial, world
from scenes import sph_bar_1d, sph_dam_break

pytestmark = pytest.mark.mpi

FIELDS = ("x", "v", "rho", "sigma", "F")


def _bar_velocity(sim):
    x = sim.particles["x"][:, 0]
    sim.particles["v"][:, 0] = 0.01 * np.sqrt(128e9 / 8790.0) * np.sin(10 * np.pi * x)


def _compare(dist, sim, ref):
    assert_equals_one_rank(dist, sim, ref, FIELDS)


@pytest.mark.parametrize("integrator", ["verlet", "predictor_corrector", "rk3"])
def test_sph_bar_equals_one_rank(integrator):
    dist = world()
    sim = sph_bar_1d(integrator).simulation(dist=dist)
    ref = sph_bar_1d(integrator).simulation(dist=serial())
    _bar_velocity(sim)
    _bar_velocity(ref)
    sim.run(max_steps=300)
    ref.run(max_steps=300)
    _compare(dist, sim, ref)


@pytest.mark.parametrize("walls,balance,axis", [("slip", 0, "y"), ("no_slip", 25, "x")])
def test_sph_dam_break_equals_one_rank(walls, balance, axis):
    dist = world()
    sim = sph_dam_break(walls=walls, balance_every=balance, axis=axis).simulation(dist=dist)
    ref = sph_dam_break(walls=walls).simulation(dist=serial())
    sim.run(max_steps=1000)
    ref.run(max_steps=1000)
    assert dist.sum(sim.migrated) > 0
    _compare(dist, sim, ref)


@pytest.mark.parametrize("kw", [dict(), dict(force="reference", integrator="verlet"),
                                dict(eta=0.2, integrator="predictor_corrector"),
                                dict(deformation="rate")])
def test_tl_plate_equals_one_rank(kw):
    from scenes import shear_velocity, tl_plate

    dist = world()
    sim = tl_plate(n=11, **kw).simulation(dist=dist)
    ref = tl_plate(n=11, **kw).simulation(dist=serial())
    shear_velocity(sim)
    shear_velocity(ref)
    sim.run(max_steps=60)
    ref.run(max_steps=60)
    assert dist.sum(sim.migrated) > 0
    _compare(dist, sim, ref)
