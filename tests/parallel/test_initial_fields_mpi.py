"""Initial fields from expressions on N ranks equal one rank's by particle gid, bit for bit
(every rank evaluates the whole body before keeping its own particles), and a value that is
not finite in one rank's slab only stops every rank with the same error before step 1.

Run with `scripts/mpirun -n 2 .venv/bin/python -m pytest -m mpi
tests/parallel/test_initial_fields_mpi.py`; the serial reference runs on COMM_SELF.
"""
import numpy as np
import pytest

from mpi_util import assert_equals_one_rank, gathered, serial, world
from pmpmsph import Scene
from pmpmsph.errors import ConfigError

pytestmark = [pytest.mark.mpi, pytest.mark.timeout(120)]

VORTEX = ["-0.2*sin(pi*x)*cos(pi*y)", "0.2*cos(pi*x)*sin(pi*y)"]


def plate(velocity=VORTEX, stress=("-9810*(0.5 - y)", "-4905*(0.5 - y)", "100*x*y")):
    """An elastic plate across the grid's slab axis (x), with an expression velocity and
    prestress."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[2, 1], cells=[32, 16]),
               time=dict(end=1.0, cfl=0.4), parallel=dict(axis="x", balance_every=0))
    sc.material("rubber", model="neo_hookean", E=1e6, nu=0.3, rho=1000.0)
    sc.body(name="plate", material="rubber", shape="box", min=[0.25, 0.25],
            max=[1.75, 0.5], ppc=2, velocity=list(velocity), stress=list(stress))
    return sc


def test_expression_fields_equal_one_rank_by_gid():
    dist = world()
    sim = plate().simulation(dist=dist)
    ref = plate().simulation(dist=serial())
    assert dist.min(sim.particles.n_owned) > 0  # the plate lies on every rank
    assert_equals_one_rank(dist, sim, ref, (), exact=("x", "v", "sigma", "prestress"))
    mine = gathered(dist, sim, ("x", "v"))
    X, Y = mine["x"][:, 0], mine["x"][:, 1]
    assert np.array_equal(mine["v"][:, 0], -0.2 * np.sin(np.pi * X) * np.cos(np.pi * Y))
    sim.run(max_steps=20)
    ref.run(max_steps=20)
    assert_equals_one_rank(dist, sim, ref, ("x", "v", "sigma"))


def test_function_velocity_equals_one_rank_by_gid():
    def spin(x):
        return np.stack([-(x[:, 1] - 0.5), x[:, 0] - 1.0], axis=1)

    dist = world()
    sims = []
    for d in (dist, serial()):
        sc = plate()
        sc.data["bodies"][0]["velocity"] = spin
        sims.append(sc.simulation(dist=d))
    assert_equals_one_rank(dist, sims[0], sims[1], (), exact=("x", "v"))


def test_non_finite_in_one_slab_stops_every_rank():
    """log(1.5 - x) is NaN only for x > 1.5: in the second of two slabs. Every rank raises
    the same ConfigError."""
    dist = world()
    with pytest.raises(ConfigError) as info:
        plate(velocity=["log(1.5 - x)", "0"]).simulation(dist=dist)
    assert info.value.key == "bodies[0].velocity[0]"
    assert "value is not finite at 64 of 384 particles" in info.value.reason
    keys = dist.allgather((info.value.key, info.value.reason))
    assert all(k == keys[0] for k in keys)
