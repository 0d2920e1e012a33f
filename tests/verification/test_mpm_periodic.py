"""Periodic MPM grids (`[grid] periodic = ["x", ...]`, `Grid.fold_periodic`).

Node i and node i + cells of a periodic axis are one node: P2G's sums on the padded layers
beyond each end are added into the nodes they stand for, and particles that leave through
one end re-enter at the other.

1. A water layer on a slip floor, periodic along x, moving at u = 0.7 along the period under
   gravity: every particle keeps u = 0.7 and sits at x0 + u t (mod 1) to rounding after it
   has crossed the wrap (no seam: nothing slows or deflects it at the ends).
2. Shear-wave decay in a doubly periodic box (no walls at all): u = U sin(2 pi y) of a
   viscous fluid decays as exp(-nu (2 pi)^2 t). At t = 0.5 (amplitude 0.37 U), 32 x 32
   cells, 4 particles per cell, quadratic B-splines, USL: APIC within 0.5 % and MLS-MPM within
   0.5 % of the exact amplitude; APIC at 16 x 16 within 5 % (measured: APIC -3.16 %, +0.24 %,
   +0.23 % at 16, 32, 64 cells; MLS +0.03 % and FLIP +2.18 % at 32).
3. Couette start-up between a floor at rest and a lid (`[[boundaries]] type = "fixed"` with a
   `velocity`: the lid's nodes take it, the nodes beyond see 2 U - v), periodic along the
   flow (bench/scenes.py `mpm_couette`, Re = 2): row-averaged u(y, t) against the series
   solution within 2 % of U at t = 0.1, 0.5 and 2.5 (steady) at 32 cells across, APIC and
   MLS. Measured: APIC 2.20 / 1.01 / 0.76 % at 16, 1.26 / 0.57 / 0.45 % at 32, 0.66 / 0.28 /
   0.22 % at 64 cells (first order); MLS 0.69 / 0.31 / 0.25 %; FLIP 5.6 / 2.9 / 2.6 % at 32.
4. Bad input names the key: a boundary on an end of a periodic axis, fewer than 8 cells
   along a periodic axis, a lid velocity with a normal
   component or on a face that is not `fixed`.
"""
import dataclasses

import numpy as np
import pytest

from pmpmsph.bench.scenes import couette_exact, mpm_couette
from pmpmsph.errors import ConfigError
from pmpmsph.scene_api import Scene


def _layer():
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[16, 16], periodic=["x"]),
               time=dict(end=1e9, cfl=0.3), gravity=[0, -9.81],
               mpm=dict(shape="quadratic", transfer="usl", velocity_update="apic"))
    sc.material("water", model="tait", rho=1000.0, kappa=2e5, gamma=7.0, mu=0.0)
    sc.body(name="w", material="water", shape="box", min=[0, 0], max=[1, 0.5], ppc=2,
            velocity=[0.7, 0.0])
    sc.boundary(face="y-", type="slip")
    return sc


def test_layer_translates_across_the_wrap():
    sim = _layer().simulation(write_output=False)
    p = sim.particles
    x0 = p["x"][np.argsort(p["gid"])].copy()
    sim.run(max_steps=400)
    o = np.argsort(p["gid"])
    assert sim.time * 0.7 > 0.1  # every particle near the ends has crossed
    assert np.abs(p["v"][o, 0] - 0.7).max() < 1e-12
    shift = np.mod(p["x"][o, 0] - x0[:, 0] - 0.7 * sim.time + 0.5, 1.0) - 0.5
    assert np.abs(shift).max() < 1e-12
    assert np.all((p["x"][:, 0] >= 0.0) & (p["x"][:, 0] < 1.0))


def shear_wave(velocity_update, n, nu=0.05, U=0.1, end=0.5):
    """Relative error of the shear wave's amplitude at `end` (module docstring, 2)."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[n, n],
                            periodic=["x", "y"]),
               time=dict(end=end, cfl=0.3), gravity=[0, 0],
               mpm=dict(shape="quadratic", transfer="usl", velocity_update=velocity_update))
    # c0 = 5 = 50 U: a weakly compressible fluid
    sc.material("oil", model="tait", rho=1000.0, kappa=1000.0 * 25 / 7, gamma=7.0,
                mu=1000.0 * nu)
    sc.body(name="w", material="oil", shape="box", min=[0, 0], max=[1, 1], ppc=2)
    sim = sc.simulation(write_output=False)
    p = sim.particles
    k = 2 * np.pi
    p["v"][:, 0] = U * np.sin(k * p["x"][:, 1])
    if "C" in p:  # the affine part of the initial field
        p["C"][:, 0, 1] = U * k * np.cos(k * p["x"][:, 1])
    sim.run()
    amp = 2 * np.sum(p["mass"] * p["v"][:, 0] * np.sin(k * p["x"][:, 1])) / p["mass"].sum()
    return amp / (U * np.exp(-nu * k * k * sim.time)) - 1.0


@pytest.mark.parametrize("velocity_update, n, tol", [("apic", 16, 0.05), ("apic", 32, 0.005),
                                                     ("mls", 32, 0.005)])
def test_shear_wave_decays_at_the_viscous_rate(velocity_update, n, tol):
    assert abs(shear_wave(velocity_update, n)) < tol


def couette_errors(velocity_update, n):
    """Max |u_row - u_exact| / U at t = 0.1, 0.5, 2.5, rows by the particles' first y."""
    sim = mpm_couette(n=n, velocity_update=velocity_update).simulation(write_output=False)
    p = sim.particles
    y0 = p["x"][np.argsort(p["gid"]), 1].copy()
    rows = np.round(y0 * 2 * n - 0.5).astype(int)
    errors = []
    for end in (0.1, 0.5, 2.5):
        sim.case = dataclasses.replace(sim.case, time=dataclasses.replace(sim.case.time,
                                                                          end=end))
        sim.run()
        o = np.argsort(p["gid"])
        y, u = p["x"][o, 1], p["v"][o, 0]
        ym = np.array([y[rows == r].mean() for r in range(2 * n)])
        um = np.array([u[rows == r].mean() for r in range(2 * n)])
        errors.append(np.abs(um - couette_exact(ym, sim.time, 0.5)).max())
    return errors


@pytest.mark.parametrize("velocity_update", ["apic", "mls"])
def test_couette_start_up_under_a_lid(velocity_update):
    assert max(couette_errors(velocity_update, 32)) < 0.02


def _bad(change):
    sc = _layer()
    change(sc)
    with pytest.raises(ConfigError) as e:
        sc.simulation(write_output=False)
    return e.value.key


def test_bad_periodic_grids_and_lids_name_the_key():
    assert _bad(lambda sc: sc.boundary(face="x+", type="slip")) == "boundaries[1].face"
    # a lid moves along itself, and only a fixed face takes a velocity
    assert _bad(lambda sc: sc.boundary(face="y+", type="fixed",
                                       velocity=[1.0, 0.5])) == "boundaries[1].velocity"
    assert _bad(lambda sc: sc.boundary(face="y+", type="slip",
                                       velocity=[1.0, 0.0])) == "boundaries[1].velocity"
    assert _bad(lambda sc: sc.data["grid"].update(cells=[6, 16], length=[0.375, 1.0])) == \
        "grid.periodic"
    # (SPH and coupled scenes with a periodic grid: tests/verification/test_coupled_periodic.py)
