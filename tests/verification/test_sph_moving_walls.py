"""Walls with a velocity (kernels/sph/walls.py, physics/sph/stage.py): a `moving` wall body
translates with its velocity; a wall with a velocity but not moving (a lid) stays in place
and drags the fluid next to it (no-slip ghost velocity 2 v_wall - v~); a wall at rest
drags nothing. A column of viscous fluid at rest between a floor and a lid, no gravity,
0.2 s: the fluid row next to the lid moves with the lid's direction, the row next to the
floor far less; the moving wall ends at x0 + v t exactly."""
import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph import Scene
from pmpmsph.errors import ConfigError
from pmpmsph.parallel.distributor import Distributor

DP = 0.05


def _channel(lid_moving):
    w = 4 * DP
    sc = Scene(2, domain=dict(min=[-1.0, -w - DP], max=[2.0, 1 + w + DP]),
               time=dict(end=0.2, cfl=0.25),
               sph=dict(kernel="wendland", h_factor=1.3, viscosity=dict(alpha=0.0, beta=0.0)),
               parallel=dict(balance_every=0))
    sc.material("oil", model="tait", rho=1000.0, kappa=1000.0 * 100.0 / 7.0, gamma=7.0,
                mu=100.0)
    sc.body(name="fluid", method="sph", material="oil", shape="box", min=[0, 0], max=[1, 1],
            spacing=DP)
    sc.body(name="floor", method="sph", wall=True, material="oil", shape="box",
            min=[-0.5, -w], max=[1.5, 0], spacing=DP)
    sc.body(name="lid", method="sph", wall=True, material="oil", shape="box",
            min=[-0.5, 1], max=[1.5, 1 + w], spacing=DP, velocity=[0.5, 0.0],
            moving=lid_moving)
    return sc.simulation(dist=Distributor(MPI.COMM_SELF))


@pytest.mark.parametrize("moving", [False, True])
def test_lid_drags_the_fluid_and_moves_only_when_moving(moving):
    sim = _channel(moving)
    p = sim.particles
    lid = p["body"] == 3
    x0 = p["x"][lid].copy()
    sim.run()
    shift = p["x"][lid] - x0
    expect = 0.5 * sim.time if moving else 0.0
    assert np.allclose(shift[:, 0], expect, atol=1e-12) and np.all(shift[:, 1] == 0.0)
    fluid = p["body"] == 0
    y, u = p["x"][fluid, 1], p["v"][fluid, 0]
    top = u[y > 1 - DP].mean()
    bottom = u[y < DP].mean()
    assert top > 0.1 * 0.5  # dragged along by the lid
    assert abs(bottom) < 0.2 * top  # the floor at rest holds its row back


def test_moving_needs_a_wall():
    sc = Scene(2, domain=dict(min=[-1, -1], max=[2, 2]), time=dict(end=0.1, cfl=0.25),
               sph=dict())
    sc.material("water", model="tait", rho=1000.0, kappa=1e5)
    with pytest.raises(ConfigError, match="moving"):
        sc.body(name="b", method="sph", material="water", shape="box", min=[0, 0],
                max=[0.5, 0.5], spacing=0.05, moving=True)
        sc.simulation(dist=Distributor(MPI.COMM_SELF))
