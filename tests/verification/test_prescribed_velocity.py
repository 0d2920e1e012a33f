"""A prescribed particle velocity moves the particle with that velocity (not the grid's)."""
import numpy as np
import pytest

from pmpmsph import Scene


@pytest.mark.parametrize("shape", ["linear", "gimp"])
def test_prescribed_end_moves_at_its_velocity(shape):
    sc = Scene(1, grid=dict(origin=[0.0], length=[2.0], cells=[40]),
               time=dict(end=0.1, dt=1e-4), mpm=dict(shape=shape))
    sc.material("m", model="linear_elastic", E=1e4, nu=0.0, rho=1000.0)
    sc.body(name="bar", material="m", shape="box", min=[0.0], max=[1.0], count=[200])
    sc.boundary(face="x-", type="fixed")
    sc.data.setdefault("prescribed", []).append(
        dict(body="bar", box=dict(min=[0.99], max=[1.0]), velocity=[0.1]))
    sim = sc.simulation()
    order = np.argsort(sim.particles["gid"])
    x0 = sim.particles["x"][order, 0].copy()
    sim.run()
    x = sim.particles["x"][np.argsort(sim.particles["gid"]), 0]
    assert x[-1] - x0[-1] == pytest.approx(0.1 * 0.1, rel=1e-9)
    assert sim.particles["v"][np.argsort(sim.particles["gid"])][-1, 0] == pytest.approx(0.1)
    assert 0.0 < x[-2] - x0[-2] < 0.01  # the bar behind it is pulled along, less far
