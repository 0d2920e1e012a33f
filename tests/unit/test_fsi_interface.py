"""The fluid-solid pair of kernels/sph/rates.py's sph_rates (a solid point as the fluid's mirror).
With the fluid's own pressure at both ends (the plain mirror) its forces do exactly the work
the fluid's continuity stores (energy neither made nor lost by the interface); with the
fluid pressure extrapolated to the solid point (`kernels.sph.walls.mirror_pressure`, what
the SPH stage uses) a fluid row next to a solid lattice feels a hydrostatic pressure field
exactly as a row inside the fluid does. Both are equal and opposite, and at uniform
pressure the interface particle is in balance."""
import numpy as np

from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.rates import sph_rates
from pmpmsph.kernels.sph.views import (pair_lists, pair_rows, rate_options, rate_terms, rates,
                                       smoothing_of)
from pmpmsph.kernels.sph.walls import mirror_pressure

MPM, SPH = 0, 1


def _rates(x, v, mass, rho, p, method, mat, fluid, h, gravity=None):
    """sph_rates' pressure forces (no gravity in them); with `gravity`, the solid rows carry
    the fluid pressure extrapolated with it (mirror_pressure), else the plain mirror."""
    n = len(x)
    start, index = neighbour_lists(x, n, 2.0 * h, half=True)
    pw = None
    if gravity is not None:
        sigma = np.zeros((n, 3, 3))
        for i in range(3):
            sigma[:, i, i] = -p
        pw = np.zeros(n)
        mirror_pressure(smoothing_of((0, 0), (0,), h), pair_lists(n, start, index), x, rho,
                        sigma, method, mat, fluid, gravity, pw)
    S = np.zeros((n, 6))
    S[:, 0] = S[:, 1] = S[:, 2] = -p / rho**2
    acc, drho, L = np.zeros((n, 2)), np.zeros(n), np.zeros((n, 3, 3))
    fsi = np.zeros((n, 2))
    sph_rates(smoothing_of((0, 0), (0,), h), pair_lists(n, start, index),
              pair_rows(x, v, v, mass, rho, S, np.ones(n), method, mat),
              rate_options((), fluid, np.zeros(3), damping=0.0, av_alpha=0.0, av_beta=0.0,
                          want_force=True, want_L=False, want_fsi=True, split=False),
              rate_terms(as_n=4.0, pw=pw), rates(acc, drho, L, fsi=fsi))
    return acc, drho, fsi


def _scene(seed=1):
    """A patch of fluid particles (SPH, material 0) above a patch of solid points (MPM,
    material 1), spacing 0.01, jittered, random velocities and pressures."""
    rng = np.random.default_rng(seed)
    dp = 0.01
    g = np.arange(8) * dp
    X, Y = np.meshgrid(g, g, indexing="ij")
    x = np.stack([X.ravel(), Y.ravel()], axis=1)
    x += rng.uniform(-0.1, 0.1, x.shape) * dp
    n = len(x)
    solid = x[:, 1] < 3.5 * dp
    method = np.where(solid, MPM, SPH).astype(np.int8)
    mat = np.where(solid, 1, 0).astype(np.int32)
    rho = np.where(solid, 917.0, 1000.0) * rng.uniform(0.98, 1.02, n)
    mass = np.where(solid, 917.0, 1000.0) * dp * dp
    v = rng.normal(0.0, 0.1, (n, 2))
    p = rng.uniform(100.0, 2000.0, n)
    return x, v, mass, rho, p, method, mat, solid


def test_interface_work_equals_the_fluid_stress_power():
    """Kinetic power (fluid forces and the reactions on the solid points, no gravity or
    viscosity) plus the fluid's stress power m p/rho^2 drho/dt is zero: the fluid-fluid pairs
    balance on their own (eq. 2.5-2.6 of seed 000), the fluid-solid pairs by the mirror
    form. The solid's own stress is not part of the pair (its MPM update stores it)."""
    x, v, mass, rho, p, method, mat, solid = _scene()
    fluid = np.array([True, False])
    acc, drho, fsi = _rates(x, v, mass, rho, p, method, mat, fluid, 0.013)
    f = ~solid
    power = np.sum(mass[f, None] * acc[f] * v[f]) + np.sum(fsi[solid] * v[solid])
    stress_power = np.sum(mass[f] * p[f] / rho[f] ** 2 * drho[f])
    scale = np.sum(np.abs(mass[f] * p[f] / rho[f] ** 2 * drho[f]))
    assert abs(power + stress_power) < 1e-12 * scale


def test_interface_forces_are_equal_and_opposite():
    x, v, mass, rho, p, method, mat, solid = _scene(2)
    for gravity in (None, np.array([0.0, -9.81, 0.0])):
        acc, drho, fsi = _rates(x, v, mass, rho, p, method, mat, np.array([True, False]),
                                0.013, gravity)
        f = ~solid
        total = np.sum(mass[f, None] * acc[f], axis=0) + np.sum(fsi[solid], axis=0)
        assert np.all(np.abs(total) < 1e-12 * np.sum(np.abs(fsi)))


def test_fluid_next_to_a_solid_feels_the_hydrostatic_field_as_inside():
    """A regular lattice, solid above y = 0 (a float's bottom face), water below with the
    hydrostatic pressure p = rho g (H - y) at uniform density: the pressure acceleration of
    the water row next to the solid equals that of a row deep in the water (to 1e-9 of g)
    when the solid points carry the extrapolated pressure. With the plain mirror (the row's
    own pressure at both ends) the row is pushed down by a sizeable fraction of g: what
    makes a float ride high (docs/floats.md)."""
    dp, g, rho0, H = 0.01, 9.81, 1000.0, 0.30
    xs = np.arange(-10, 11) * dp
    ys = (np.arange(-12, 9) + 0.5) * dp
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    x = np.stack([X.ravel(), Y.ravel()], axis=1)
    n = len(x)
    solid = x[:, 1] > 0.0
    method = np.where(solid, MPM, SPH).astype(np.int8)
    mat = np.where(solid, 1, 0).astype(np.int32)
    rho = np.full(n, rho0)
    mass = rho * dp * dp
    p = rho0 * g * (H - x[:, 1])
    fluid = np.array([True, False])
    centre = np.abs(x[:, 0]) < 0.03
    top = centre & (np.abs(x[:, 1] + 0.5 * dp) < 1e-9)
    deep = centre & (np.abs(x[:, 1] + 5.5 * dp) < 1e-9)
    for gravity, bound in ((np.array([0.0, -g, 0.0]), 1e-9), (None, None)):
        acc, _, _ = _rates(x, np.zeros((n, 2)), mass, rho, p, method, mat, fluid, 1.3 * dp,
                           gravity)
        gap = np.abs(acc[top, 1] - acc[deep, 1].mean())
        if bound is not None:
            assert np.all(gap < bound * g)
            # the field itself, -grad p/rho (1.05 % off: the lattice sum of the kernel moment)
            assert abs(acc[deep, 1].mean() / g - 1.0) < 0.02
        else:
            assert np.all(gap > 0.05 * g)


def test_interface_particle_in_balance_at_uniform_pressure():
    """A regular lattice (no jitter), solid below y = 0, uniform pressure and density: the
    fluid row next to the solid has no net force along y (the mirror's factor 2)."""
    dp = 0.01
    g = np.arange(-10, 11) * dp
    X, Y = np.meshgrid(g, g, indexing="ij")
    x = np.stack([X.ravel(), Y.ravel() + 0.5 * dp], axis=1)
    n = len(x)
    solid = x[:, 1] < 0.0
    method = np.where(solid, MPM, SPH).astype(np.int8)
    mat = np.where(solid, 1, 0).astype(np.int32)
    rho = np.full(n, 1000.0)
    mass = rho * dp * dp
    p = np.full(n, 1000.0)
    acc, _, _ = _rates(x, np.zeros((n, 2)), mass, rho, p, method, mat,
                       np.array([True, False]), 1.3 * dp)
    row = (~solid) & (np.abs(x[:, 1] - 0.5 * dp) < 1e-9) & (np.abs(x[:, 0]) < 0.05)
    scale = p[0] / rho[0] / dp  # the size of one pair's pressure acceleration
    assert np.all(np.abs(acc[row, 1]) < 1e-3 * scale)
