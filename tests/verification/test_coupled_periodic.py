"""Periodic coupled MPM-SPH scenes (issue 18, item 4): `[grid] periodic = ["x"]` makes the
grid periodic (`Grid.fold_periodic`) and the particles too, over the grid's length (SPH
images and the wrap of physics/sph/stage.py, the MPM wrap of physics/mpm/stage.py; the marks of the
transition zone fold across the seam, physics/coupling.py).

1. The coupled piston (bench/scenes.py `coupled_piston`: SPH water 0.2 deep on a no-slip
   dummy floor under an MPM ice layer 0.1 thick that spans the period 0.2, so the water has
   no free surface) settles where the water under it carries its weight: the drop of the
   layer against the Tait column's (`piston_equilibrium`, from the water's seeded state).
   Measured, mean bottom of the layer over t = 0.5-2 s, drop 1.20 mm exact:
       spacing 0.01: drop 6.4 % long, spacing 0.005: 3.6 % long (first order: 0.077 and
       0.043 mm), with the solid points carrying the water pressure extrapolated to them
       (kernels/sph/walls.py mirror_pressure; 2026-11-25). With the water particle's own
       pressure at both ends before that: 0.198745 against 0.198803 (4.9 % long) and
       0.198764 (3.2 %). The bound was 6 % then and is 7 % now: the extrapolation lowers the
       layer by 0.015 mm (0.0015 spacings) at spacing 0.01 while it halves the floats'
       offset (docs/floats.md).
   The layer bobs about it with an amplitude of about 1 mm that the viscosity damps slowly.
2. Moving at U = 1 along the period (floor too), every particle crosses the seam; the scene
   is uniform along x, so every row must stay uniform: the seam is invisible (measured
   spread 2e-14; the rows advance by U t to 8e-5).
3. The transition zone of a region-coupled bar wraps: SPH particles just inside one end of
   the period join the P2G of MPM points at the other end.
4. Bad input: [domain] periodic with a grid; a wall at an end of the grid's periodic axis;
   a period that is not a whole number of spacings: exit 2 naming the key.
Not covered: at zero gravity a water column at rest under the layer (zero pressure) grows an
odd-even mode of its rows from round-off within 0.15 s (the fluid-solid pair pushes only
with p > 0); with gravity (positive pressure at the interface) it does not appear.
"""
import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph import Scene
from pmpmsph.bench.scenes import coupled_piston, piston_equilibrium
from pmpmsph.errors import ConfigError
from pmpmsph.parallel.distributor import Distributor

SELF = Distributor(MPI.COMM_SELF)
PERIOD = 0.2


def _owned(sim, name):
    p = sim.particles
    return p[name][: p.n_owned]


def test_piston_settles_at_the_tait_equilibrium():
    sp = 0.01
    sim = coupled_piston(spacing=sp, end=2.0).simulation(dist=SELF)
    body = _owned(sim, "body")
    water, layer = body == 0, body == 1
    # the column's mass as its seeded state holds it (particles one spacing apart at the
    # hydrostatic density of an open column), and the layer's weight per unit width
    column = float(np.sum(_owned(sim, "rho")[water])) * sp * sp / PERIOD
    load = float(np.sum(_owned(sim, "mass")[layer])) / PERIOD * 9.81
    start = float(_owned(sim, "x")[layer, 1].min()) - 0.5 * sp
    exact = piston_equilibrium(column, load)
    bottoms = []

    def track(s):
        if s.time >= 0.5:
            b = _owned(s, "body")
            bottoms.append(float(_owned(s, "x")[b == 1, 1].min()) - 0.5 * sp)

    sim.run(on_step=track)
    assert abs(sim.time - 2.0) < 1e-9
    settled = float(np.mean(bottoms))
    drop, drop_exact = start - settled, start - exact
    print(f"layer bottom {settled:.6f} against {exact:.6f}: drop {drop * 1e3:.3f} mm, exact "
          f"{drop_exact * 1e3:.3f} mm ({drop / drop_exact - 1:+.3f})")
    assert drop_exact > 1e-3
    assert abs(drop / drop_exact - 1.0) < 0.07
    assert np.all(np.isfinite(_owned(sim, "v")))


def test_moving_piston_stays_uniform_across_the_seam():
    sim = coupled_piston(spacing=0.01, end=0.3, velocity=[1.0, 0.0]).simulation(dist=SELF)
    rows = dict(zip(_owned(sim, "gid"), np.round(_owned(sim, "x")[:, 1], 6)))
    x0 = dict(zip(_owned(sim, "gid"), _owned(sim, "x")[:, 0]))
    sim.run()
    gid, x, v = _owned(sim, "gid"), _owned(sim, "x"), _owned(sim, "v")
    row = np.array([rows[g] for g in gid])
    start = np.array([x0[g] for g in gid])
    assert sim.time > 1.4 * PERIOD  # every particle crossed the seam at least once
    assert x[:, 0].min() >= 0.0 and x[:, 0].max() < PERIOD
    # all moved by U t along x (to 8e-5: MPM is not exactly Galilean invariant, the layer's
    # points sit elsewhere in their cells than at rest)
    shift = (x[:, 0] - start - sim.time) % PERIOD
    assert np.max(np.minimum(shift, PERIOD - shift)) < 2e-4
    spread = max(max(np.ptp(x[row == y, 1]), np.ptp(v[row == y], axis=0).max())
                 for y in np.unique(row))
    assert spread < 1e-12
    assert np.abs(v[:, 1]).max() > 1e-3  # the layer is bobbing: the rows do move


def test_transition_zone_wraps_the_seam():
    """A copper ring of period 1 in 1D: MPM points on [0.5, 1), SPH on [0, 0.5), both
    sharing one material (the region coupling of seed 000): the SPH particles within one
    cell of the MPM points join their P2G at both interfaces, x = 0.5 and the seam."""
    sc = Scene(1, grid=dict(origin=[0.0], cell_size=0.05, cells=[20], periodic=["x"]),
               time=dict(end=1e-6, cfl=0.2), mpm=dict(shape="gimp", transfer="musl"),
               sph=dict(integrator="verlet", viscosity=dict(alpha=0.0, beta=0.0)),
               parallel=dict(balance_every=0))
    sc.material("copper", model="linear_elastic", E=128e9, nu=0.3, rho=8790.0)
    sc.body(name="sph", method="sph", material="copper", shape="box", min=[0.0], max=[0.5],
            spacing=0.025)
    sc.body(name="mpm", method="mpm", material="copper", shape="box", min=[0.5], max=[1.0],
            spacing=0.025)
    sim = sc.simulation(dist=SELF)
    sim.coupling.prepare()
    x = _owned(sim, "x")[:, 0]
    joined = x[sim.mpm.n_g2p:sim.mpm.n_stress]
    assert np.any(joined < 0.1) and np.any((joined > 0.4) & (joined < 0.5))
    assert np.all((joined < 0.1) | (joined > 0.4))


def _bad(kind):
    sc = coupled_piston(spacing=0.01, end=0.1)
    if kind == "domain":
        sc.data["domain"] = dict(min=[0.0, -0.1], max=[PERIOD, 0.4], periodic=["x"])
    elif kind == "wall":
        sc.body(name="side", method="sph", wall=True, material="water", shape="box",
                min=[0.0, 0.0], max=[0.04, 0.1], spacing=0.01)
    else:
        sc.data["bodies"][0]["spacing"] = 0.0095
    return sc


@pytest.mark.parametrize("kind,key,match", [
    ("domain", "domain.periodic", "grid's periodic axes"),
    ("wall", "grid.periodic", "a periodic axis has no ends"),
    ("spacing", "grid.periodic", "whole number")])
def test_bad_periodic_coupled_input(kind, key, match):
    with pytest.raises(ConfigError, match=match) as err:
        _bad(kind).simulation(dist=SELF)
    assert err.value.key == key
