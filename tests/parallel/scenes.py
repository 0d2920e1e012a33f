"""Small scenes shared by the parallel tests (Python Scene API, seconds to run)."""
import numpy as np

from pmpmsph import Scene
from pmpmsph.bench.scenes import (coupled_bar_1d, coupled_stress_bar, shear_velocity,
                                   sph_bar_1d, sph_dam_break, tl_plate, two_disks)

# the scenes the accuracy bench shares live in pmpmsph/bench/scenes.py; the tests import
# them from here as before
__all__ = ["coupled_bar_1d", "coupled_stress_bar", "dam_break", "handover_bar", "loaded_bar",
           "shear_velocity", "sph_bar_1d", "sph_block_on_walls", "sph_dam_break", "tl_plate",
           "two_disks"]


def dam_break(shape="quadratic", transfer="usl", barrier=True, balance_every=0,
              balance_by="work", balance_threshold=0.1, velocity_update="flip"):
    """BENCHMARKS.md scene 4 set-up (thesis §8.4): 4 x 2 column behind a gate removed at
    t = 0, slip walls, a barrier at x = 6 inside a grid extended to x = 8."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[8, 8], cells=[24, 24]),
               time=dict(end=2.0, dt=1e-3), gravity=[0, -9.81],
               mpm=dict(shape=shape, transfer=transfer, velocity_update=velocity_update),
               parallel=dict(axis="x", balance_every=balance_every, balance_by=balance_by,
                             balance_threshold=balance_threshold))
    sc.material("water", model="tait", rho=997.5, kappa=2e6, gamma=7.0, mu=0.01)
    sc.body(name="water", material="water", shape="box", min=[0, 0], max=[4, 2], ppc=2)
    for face in ("x-", "x+", "y-", "y+"):
        sc.boundary(face=face, type="slip")
    if barrier:
        sc.boundary(box=dict(min=[6, 0], max=[6, 1]), type="slip", normal=[1, 0])
    return sc


def loaded_bar(shape="gimp", transfer="usf", velocity_update="flip"):
    """An elastic bar across every slab face with the features a slab face must not change:
    fixed face, traction load with a ramp, prescribed velocity, a gate, damping, gravity."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[2.0, 0.5], cells=[40, 10]),
               time=dict(end=1.0, dt=2e-4), gravity=[0, -9.81],
               mpm=dict(shape=shape, transfer=transfer, damping=2.0,
                        velocity_update=velocity_update,
                        **({"flip": 0.9} if velocity_update == "flip" else {})),
               parallel=dict(axis="x", balance_every=0))
    sc.material("steel", model="stvk", E=2e5, nu=0.3, rho=1000.0)
    sc.body(name="bar", material="steel", shape="box", min=[0.0, 0.1], max=[1.8, 0.3], ppc=2)
    sc.boundary(face="x-", type="fixed")
    sc.boundary(box=dict(min=[0.0, 0.0], max=[2.0, 0.1]), type="slip", normal=[0, -1],
                until=0.02)
    sc.load(body="bar", box=dict(min=[1.77, 0.1], max=[1.8, 0.3]), normal="x+",
            traction=[1e3, 0.0], ramp=0.01)
    sc.data.setdefault("prescribed", []).append(
        dict(body="bar", box=dict(min=[0.9, 0.1], max=[0.95, 0.3]), velocity=["free", 0.0],
             until=0.01))
    return sc


def handover_bar(v=50.0):
    """A copper bar on [0.3, 0.5] moving at v through the boundary x = 0.6 of an SPH region
    (MPM elsewhere) with `handover`: its particles turn from MPM to SPH as they cross."""
    sc = Scene(1, grid=dict(origin=[0.0], cell_size=0.05, cells=[30]),
               time=dict(end=0.006, cfl=0.2),
               mpm=dict(shape="gimp", transfer="musl"),
               sph=dict(integrator="verlet", viscosity=dict(alpha=0.0, beta=0.0)),
               parallel=dict(balance_every=0))
    sc.material("copper", model="linear_elastic", E=128e9, nu=0.3, rho=8790.0)
    sc.body(name="bar", material="copper", shape="box", min=[0.3], max=[0.5], spacing=0.025,
            velocity=[v])
    sc.data["regions"] = [dict(method="sph", shape="box", min=[0.6], max=[1.5])]
    sc.data["coupling"] = dict(handover=True)
    return sc


def sph_block_on_walls(theta=30.0, dp=0.005, friction=0.3):
    """A neo-Hookean SPH block sliding down a rough floor of contact walls (gravity tilted
    by `theta` degrees; tests/verification/test_sph_wall_friction.py), slabs cut along x
    through the block: the contact and its friction cross the slab faces."""
    th = np.radians(theta)
    sc = Scene(2, domain=dict(min=[-0.1, -0.1], max=[0.8, 0.2]),
               gravity=[9.81 * np.sin(th), -9.81 * np.cos(th)], time=dict(end=0.1, cfl=0.3),
               sph=dict(kernel="wendland"), parallel=dict(axis="x", balance_every=0))
    sc.material("floor", model="tait", rho=1000.0, kappa=1.0e5)
    sc.material("block", model="neo_hookean", E=2.0e6, nu=0.3, rho=2000.0)
    sc.body(name="block", method="sph", material="block", shape="box", min=[0.15, 0.0],
            max=[0.55, 0.05], spacing=dp)  # (the slab faces of 2 or 3 ranks cut it)
    sc.body(name="floor", method="sph", material="floor", wall=True, friction=friction,
            shape="box", min=[-0.05, -4 * dp], max=[0.75, 0.0], spacing=dp)
    return sc
