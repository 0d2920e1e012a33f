"""SPH in 3D: a water cube settling on a floor of dummy wall particles (Wendland C2, h = 2
spacings, damped), and an elastic SPH cube with artificial stress (the 3D principal-axis
path). The same kernels as 1D/2D with dim = 3; checks that the 3D paths are right, not a
benchmark: after settling, the pressure near the floor is rho g H within 10 %, no particle
goes through the floor, and the elastic cube's momentum is conserved."""
import numpy as np
from mpi4py import MPI

from pmpmsph import Scene
from pmpmsph.parallel.distributor import Distributor


def _serial(sc):
    return sc.simulation(dist=Distributor(MPI.COMM_SELF))


def test_water_cube_settles_on_dummy_walls_3d():
    dx, H, g = 0.05, 0.4, 9.81
    c0 = 10 * np.sqrt(g * H)
    sc = Scene(3, domain=dict(min=[-0.3, -0.3, -0.3], max=[0.7, 0.7, 0.8]),
               gravity=[0, 0, -g], time=dict(end=0.6, cfl=0.2),
               sph=dict(kernel="wendland", h_factor=2.0, integrator="predictor_corrector",
                        damping=10.0, walls="no_slip", viscosity=dict(alpha=0.1, beta=0.0)))
    sc.material("water", model="tait", rho=1000.0, kappa=c0 ** 2 * 1000.0 / 7.0, gamma=7.0)
    sc.body(name="water", method="sph", material="water", shape="box", min=[0, 0, 0],
            max=[0.4, 0.4, H], spacing=dx)
    w = 3 * dx
    for name, lo, hi in (("floor", [-w, -w, -w], [0.4 + w, 0.4 + w, 0.0]),
                         ("x-", [-w, -w, 0.0], [0.0, 0.4 + w, 0.6]),
                         ("x+", [0.4, -w, 0.0], [0.4 + w, 0.4 + w, 0.6]),
                         ("y-", [0.0, -w, 0.0], [0.4, 0.0, 0.6]),
                         ("y+", [0.0, 0.4, 0.0], [0.4, 0.4 + w, 0.6])):
        sc.body(name=name, method="sph", wall=True, material="water", shape="box", min=lo,
                max=hi, spacing=dx)
    sim = _serial(sc)
    sim.run()
    p = sim.particles
    water = p["body"] == 0
    z = p["x"][water, 2]
    assert z.min() > 0.0
    bottom = water & (p["x"][:, 2] < 1.5 * dx)
    pressure = -np.trace(p["sigma"][bottom], axis1=1, axis2=2) / 3
    expected = 1000.0 * g * (H - p["x"][bottom, 2]).mean()
    assert abs(pressure.mean() / expected - 1) < 0.1, pressure.mean() / expected


def test_elastic_cube_with_artificial_stress_conserves_momentum_3d():
    sc = Scene(3, domain=dict(min=[-1, -1, -1], max=[2, 2, 2]), time=dict(end=1.0, cfl=0.3),
               sph=dict(h_factor=1.3, integrator="rk3", artificial_stress=0.3))
    sc.material("rubber", model="neo_hookean", E=1e6, nu=0.3, rho=1000.0)
    sc.body(name="cube", method="sph", material="rubber", shape="box", min=[0, 0, 0],
            max=[0.5, 0.5, 0.5], spacing=0.05)
    sim = _serial(sc)
    p = sim.particles
    p["v"][:, 0] = 2.0 * (p["x"][:, 1] - 0.25)  # a shearing spin: tension and compression
    p0 = (p["mass"][:, None] * p["v"]).sum(axis=0)
    e0 = sim.diagnostics()["total"]
    sim.run(max_steps=300)
    p1 = (p["mass"][:, None] * p["v"]).sum(axis=0)
    assert np.all(np.isfinite(p["x"]))
    assert np.abs(p1 - p0).max() < 1e-9 * p["mass"].sum()
    e1 = sim.diagnostics()["total"]
    assert e1 <= e0 * (1 + 1e-3)  # artificial viscosity only takes energy out
