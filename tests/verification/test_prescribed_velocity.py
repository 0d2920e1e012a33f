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


def test_start_positions_follow_the_particles_when_rows_are_reordered():
    """A coupled scene sorts its rows during a step (by method and cell): the positions of
    the step's start are matched back by gid, not by row (matched by row, two clamped
    particles of the SPH plate under MPM water traded places and the plate failed at step 2:
    docs/plate.md)."""
    from pmpmsph.config.case import PrescribedSpec
    from pmpmsph.particles import ParticleSet
    from pmpmsph.physics.loads import PrescribedVelocity

    p = ParticleSet(2, capacity=6)
    p.declare(PrescribedVelocity.FIELDS[0])
    p.append({"gid": np.arange(6), "x": np.arange(12.0).reshape(6, 2),
              "vpres_id": np.array([0, -1, 0, 0, -1, 0], np.int32)})
    spec = PrescribedSpec(body="b", region=None, velocity=(None, 2.0))
    held = PrescribedVelocity((spec,), p)
    before = held.positions()
    p.take(np.array([5, 4, 3, 2, 1, 0]))   # the stage reorders the rows ...
    p["x"][:] += 100.0                       # ... and moves every particle
    held.apply(0.0, 0.5, before)
    x = p["x"][np.argsort(p["gid"])]
    for gid in (0, 2, 3, 5):                 # held in y (start + dt v), free in x
        assert x[gid, 1] == 2 * gid + 1 + 1.0 and x[gid, 0] == 2 * gid + 100.0
    for gid in (1, 4):
        assert np.array_equal(x[gid], [2 * gid + 100.0, 2 * gid + 101.0])
