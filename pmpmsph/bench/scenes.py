"""Benchmark scenes as Python `Scene`s, each with its resolution knob (BENCHMARKS.md).

Shared by the accuracy bench (`bench/accuracy.py`) and the tests (tests/parallel/scenes.py
re-exports them), so a scene is defined once. The defaults are the set-ups the tests pin.
"""
from pathlib import Path

import numpy as np

from pmpmsph import Scene, load_case_file

COPPER = dict(model="linear_elastic", E=128e9, nu=0.3, rho=8790.0)


def two_disks(contact="single", shape="linear", spacing=0.02, cells=20, transfer="usl",
              dt=1e-3):
    """BENCHMARKS.md scene 3 (thesis §8.3): two neo-Hookean disks on a 1 x 1 grid."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[cells, cells]),
               time=dict(end=3.0, dt=dt),
               mpm=dict(shape=shape, contact=contact, transfer=transfer))
    sc.material("m", model="neo_hookean", E=1000.0, nu=0.3, rho=1000.0)
    sc.body(name="a", material="m", shape="disc", centre=[0.2, 0.2], radius=0.2,
            spacing=spacing, velocity=[0.1, 0.1])
    sc.body(name="b", material="m", shape="disc", centre=[0.8, 0.8], radius=0.2,
            spacing=spacing, velocity=[-0.1, -0.1])
    return sc


def sph_bar_1d(integrator="rk3", spacing=0.05):
    """BENCHMARKS.md scene 8 in pure SPH (seed 000 §5.1): copper bar on [0, 1], h = 1.3
    spacing, v(x, 0) = 0.01 c sin(10 pi x) set by the caller, Courant number 0.1."""
    sc = Scene(1, domain=dict(min=[-0.5], max=[1.5]), time=dict(end=1.0, cfl=0.1),
               sph=dict(h_factor=1.3, integrator=integrator,
                        viscosity=dict(alpha=0.0, beta=0.0)),
               parallel=dict(balance_every=0))
    sc.material("copper", **COPPER)
    sc.body(name="bar", method="sph", material="copper", shape="box", min=[0.0], max=[1.0],
            spacing=spacing)
    return sc


def sph_dam_break(dx=0.05, integrator="predictor_corrector", walls="slip", balance_every=0,
                  axis="y", end=1.0, wall_height=2.5):
    """The SPH dam break of cases/sph_dam_break.toml: 1 x 2 water column in a 4 wide tank,
    dummy-particle walls (4 layers; `wall_height` high: the water stays below it in the
    first 0.5 s), Tait water, alpha = 0.1. Slabs along y by default, so the falling column
    crosses the slab faces at once."""
    m = max(0.3, 5 * dx)  # the domain holds the 4 wall layers
    sc = Scene(2, domain=dict(min=[-m, -m], max=[4 + m, wall_height + 0.1]),
               gravity=[0, -9.81], time=dict(end=end, cfl=0.125),
               sph=dict(kernel="wendland", h_factor=1.3, integrator=integrator, walls=walls,
                        viscosity=dict(alpha=0.1, beta=0.0)),
               parallel=dict(axis=axis, balance_every=balance_every))
    sc.material("water", model="tait", rho=1000.0, kappa=560571.4, gamma=7.0, mu=0.0)
    sc.body(name="water", method="sph", material="water", shape="box", min=[0, 0],
            max=[1, 2], spacing=dx)
    w = 4 * dx
    for name, lo, hi in (("floor", [0, -w], [4, 0]), ("left", [-w, -w], [0, wall_height]),
                         ("right", [4, -w], [4 + w, wall_height])):
        sc.body(name=name, method="sph", wall=True, material="water", shape="box", min=lo,
                max=hi, spacing=dx)
    return sc


def tl_plate(n=21, corrected=True, eta=None, integrator="rk3", force="current",
             deformation="reference", k_h=1.4, cfl=0.3, end=1.2, formulation="total"):
    """BENCHMARKS.md scene 12 (seed 004 §6.1): 1 x 1 mm plane-strain plate, Hartmann-Neff
    neo-Hookean mu = 1.25 MPa, k = 5.833 MPa, rho = 3, free surface, total-Lagrangian SPH
    with n x n particles (h = k_h x spacing). The caller sets v1 = 0.8 x2 (`shear_velocity`).
    With `eta`: the Maxwell body of scene 13. `formulation="updated"`: the same plate in
    updated-Lagrangian SPH (no correction, artificial stress off, no viscosity)."""
    sph = dict(formulation=formulation, h_factor=k_h, integrator=integrator)
    if formulation == "total":
        sph.update(correction=corrected, force=force, deformation=deformation)
    else:
        sph.update(viscosity=dict(alpha=0.0, beta=0.0))
    sc = Scene(2, domain=dict(min=[-1.0, -1.0], max=[3.0, 2.0]),
               time=dict(end=end, cfl=cfl), sph=sph,
               parallel=dict(axis="x", balance_every=0))
    if eta is None:
        sc.material("rubber", model="hartmann_neff", mu=1.25, k=5.833, rho=3.0)
    else:
        sc.material("rubber", model="maxwell", mu=1.25, k=5.833, rho=3.0, eta=eta)
    sc.body(name="plate", method="sph", material="rubber", shape="box", min=[0.0, 0.0],
            max=[1.0, 1.0], count=[n, n])
    return sc


def shear_velocity(sim, rate=0.8):
    """Initial simple-shear velocity v1 = rate x2, v2 = 0 (seed 004, eq. 19)."""
    p = sim.particles
    p["v"][:, 0] = rate * p["x"][:, 1]
    p["v"][:, 1] = 0.0


def coupled_bar_1d(mode="coupled", shape="gimp", integrator="verlet", spacing=0.05,
                   transfer="usl", h=None):
    """Seed 000 §5 copper bar (cell = 2 spacings, default spacing 0.05) as `mode`:
    "coupled" (MPM in the outer fifths [0, 0.2] and [0.8, 1], SPH inside, h = cell size
    unless given), "mpm" or "sph"."""
    cell = 2.0 * spacing
    sc = Scene(1, grid=dict(origin=[-0.3], cell_size=cell, cells=[int(round(1.6 / cell))]),
               time=dict(end=1.0, cfl=0.1),
               mpm=dict(shape=shape, transfer=transfer),
               parallel=dict(balance_every=0))
    if mode != "mpm":
        sc.data["sph"] = dict(h=cell if h is None else h, integrator=integrator,
                              viscosity=dict(alpha=0.0, beta=0.0))
    sc.material("copper", **COPPER)
    sc.body(name="bar", method="sph" if mode == "sph" else "mpm", material="copper",
            shape="box", min=[0.0], max=[1.0], spacing=spacing)
    if mode == "coupled":
        sc.data["regions"] = [dict(method="sph", shape="box", min=[0.2], max=[0.8])]
    return sc


def stress_bar(mode="coupled", h=0.1, transfer="musl", alpha=0.0, shape="gimp",
               spacing=0.05):
    """Seed 000 §5.2 (BENCHMARKS.md scene 9): the copper bar compressed by 1 MPa ramped over
    2 ms on its end particle layers, damped to rest; "coupled": MPM in [0, 0.2] and
    [0.8, 1], SPH inside; "mpm": all MPM. Cell = 2 spacings."""
    cell = 2.0 * spacing
    sc = Scene(1, grid=dict(origin=[-0.2], cell_size=cell, cells=[int(round(1.4 / cell))]),
               time=dict(end=0.02, cfl=0.1),
               mpm=dict(shape=shape, damping=2000.0, transfer=transfer),
               parallel=dict(balance_every=0))
    sc.material("copper", **COPPER)
    sc.body(name="bar", material="copper", shape="box", min=[0.0], max=[1.0], spacing=spacing)
    if mode == "coupled":
        sc.data["sph"] = dict(h=h, integrator="verlet", damping=2000.0,
                              viscosity=dict(alpha=alpha, beta=alpha))
        sc.data["regions"] = [dict(method="sph", shape="box", min=[0.2], max=[0.8])]
    for lo, hi, face in ((0.0, spacing, "x-"), (1.0 - spacing, 1.0, "x+")):
        sc.load(body="bar", box=dict(min=[lo], max=[hi]), normal=face, stress=[-1e6],
                ramp=0.002)
    return sc


def coupled_stress_bar(h=0.1, transfer="musl", alpha=0.0):
    """The coupled scene-9 bar at the seed's resolution (see `stress_bar`)."""
    return stress_bar("coupled", h=h, transfer=transfer, alpha=alpha)


def _case_file(name, overrides):
    """A case of the repository's cases/ folder with `--set`-style overrides."""

    path = Path(__file__).resolve().parents[2] / "cases" / name
    return load_case_file(path, overrides=overrides)


def spring_case(refine=1, shape="gimp", transfer="usl"):
    """Scene 1 (cases/spring_1d.toml) refined k times: 10 k particles, 21 k cells, dt / k."""
    return _case_file("spring_1d.toml", [("mpm.shape", shape), ("mpm.transfer", transfer),
                                         ("bodies[0].count", [10 * refine]),
                                         ("grid.cells", [21 * refine]),
                                         ("time.dt", 1e-4 / refine)])


# scene 14: bar length, modulus, density, velocity amplitude (cases/vibrating_bar_1d.toml)
BAR_L, BAR_E, BAR_RHO, BAR_V0 = 25.0, 100.0, 1.0, 0.1


def vibrating_bar_case(refine=1, shape="gimp", transfer="usl", end=20.0):
    """Scene 14 (cases/vibrating_bar_1d.toml) with cell h = 1/k, 2 particles per cell,
    dt = 0.01 h (Courant number 0.1). The caller sets the mode with `mode_velocity`."""
    h = 1.0 / refine
    return _case_file("vibrating_bar_1d.toml",
                      [("mpm.shape", shape), ("mpm.transfer", transfer),
                       ("grid.cell_size", h), ("grid.cells", [27 * refine]),
                       ("time.dt", 0.01 * h), ("time.end", end)])


def mode_velocity(sim):
    """First axial mode of the fixed-free bar, v = v0 sin(beta x), beta = pi / (2 L)."""
    x = sim.particles["x"][:, 0]
    sim.particles["v"][:, 0] = BAR_V0 * np.sin(np.pi / (2 * BAR_L) * x)


def sph_cavity(n=30, end=20.0, laminar="morris", reynolds=100.0, c0=10.0):
    """Lid-driven cavity (Ghia, Ghia & Shin 1982): a unit square of water-like Tait fluid
    (rho0 = 1000, c0 = 10 x the lid speed U = 1, mu = rho0 U / Re) in no-slip dummy walls
    (4 layers) whose top layer slides at U (wall particles that stay in place and carry the
    velocity: Adami et al.'s ghost velocity 2 U - v~), n x n particles, Wendland C2 kernel
    at h = 1.3 spacings, no artificial viscosity, delta-SPH, predictor-corrector at
    Courant number 0.25, no gravity."""
    dp = 1.0 / n
    w = 4 * dp
    rho0 = 1000.0
    sc = Scene(2, domain=dict(min=[-w - dp, -w - dp], max=[1 + w + dp, 1 + w + dp]),
               time=dict(end=end, cfl=0.25),
               sph=dict(kernel="wendland", h_factor=1.3, integrator="predictor_corrector",
                        walls="no_slip",
                        viscosity=dict(alpha=0.0, beta=0.0, laminar=laminar)),
               parallel=dict(balance_every=0))
    sc.material("water", model="tait", rho=rho0, kappa=c0 * c0 * rho0 / 7.0, gamma=7.0,
                mu=rho0 / reynolds)
    sc.body(name="fluid", method="sph", material="water", shape="box", min=[0, 0],
            max=[1, 1], spacing=dp)
    for name, lo, hi in (("floor", [-w, -w], [1 + w, 0]), ("left", [-w, 0], [0, 1]),
                         ("right", [1, 0], [1 + w, 1])):
        sc.body(name=name, method="sph", wall=True, material="water", shape="box", min=lo,
                max=hi, spacing=dp)
    sc.body(name="lid", method="sph", wall=True, material="water", shape="box",
            min=[-w, 1], max=[1 + w, 1 + w], spacing=dp, velocity=[1.0, 0.0])
    return sc


def mpm_cavity(n=32, end=20.0, velocity_update="apic", reynolds=100.0, c0=10.0,
               shape="quadratic"):
    """The lid-driven cavity of `sph_cavity` in MPM: n x n cells over the unit square filled
    with the same fluid (2 x 2 particles per cell), no-slip grid walls (`fixed`, mirrored
    beyond the wall) and a lid that is the face y = 1 with velocity (1, 0) (the wall nodes
    take it, the nodes beyond see 2 U - v); the side walls are listed after the lid, so the
    two top corner nodes are at rest. USL at Courant number 0.3."""
    rho0 = 1000.0
    sc = Scene(2, grid=dict(origin=[0.0, 0.0], length=[1.0, 1.0], cells=[n, n]),
               time=dict(end=end, cfl=0.3),
               mpm=dict(shape=shape, transfer="usl", velocity_update=velocity_update),
               parallel=dict(balance_every=0))
    sc.material("water", model="tait", rho=rho0, kappa=c0 * c0 * rho0 / 7.0, gamma=7.0,
                mu=rho0 / reynolds)
    sc.body(name="fluid", material="water", shape="box", min=[0, 0], max=[1, 1], ppc=2)
    sc.boundary(face="y+", type="fixed", velocity=[1.0, 0.0])
    for face in ("x-", "x+", "y-"):
        sc.boundary(face=face, type="fixed")
    return sc


def mpm_couette(n=32, nu=0.5, end=2.5, velocity_update="apic", shape="quadratic"):
    """The Couette start-up of `sph_couette` in MPM: a grid of 8 x n cells (periodic along
    x, 8 cells long) filled with the fluid (2 x 2 particles per cell) between a no-slip floor
    (`fixed`) and a lid that is the face y = 1 with velocity (1, 0). No corners: the lid
    only drags. USL at Courant number 0.3."""
    length = 8.0 / n
    rho0 = 1000.0
    sc = Scene(2, grid=dict(origin=[0.0, 0.0], length=[length, 1.0], cells=[8, n],
                            periodic=["x"]),
               time=dict(end=end, cfl=0.3),
               mpm=dict(shape=shape, transfer="usl", velocity_update=velocity_update),
               parallel=dict(balance_every=0))
    sc.material("oil", model="tait", rho=rho0, kappa=100.0 * rho0 / 7.0, gamma=7.0,
                mu=rho0 * nu)
    sc.body(name="fluid", material="oil", shape="box", min=[0, 0], max=[length, 1], ppc=2)
    sc.boundary(face="y-", type="fixed")
    sc.boundary(face="y+", type="fixed", velocity=[1.0, 0.0])
    return sc


def sph_couette(n=20, nu=0.5, end=2.5, laminar="morris", periods=16):
    """Couette flow start-up: a fluid layer of unit depth between a wall at rest (y = 0) and
    a wall sliding at U = 1 (y = 1), periodic along x over `periods` spacings, from rest;
    Tait fluid rho0 = 1000, c0 = 10 U, kinematic viscosity `nu` (Re = U H / nu = 2 for 0.5;
    the flow is steady after about H^2 / (pi^2 nu) x 10 = 2 s), Wendland C2 at h = 1.3
    spacings, no artificial viscosity. Exact: `couette_exact`."""
    dp = 1.0 / n
    w = 4 * dp
    length = periods * dp
    rho0 = 1000.0
    sc = Scene(2, domain=dict(min=[0.0, -w - dp], max=[length, 1 + w + dp], periodic=["x"]),
               time=dict(end=end, cfl=0.25),
               sph=dict(kernel="wendland", h_factor=1.3,
                        viscosity=dict(alpha=0.0, beta=0.0, laminar=laminar)),
               parallel=dict(balance_every=0))
    sc.material("oil", model="tait", rho=rho0, kappa=100.0 * rho0 / 7.0, gamma=7.0,
                mu=rho0 * nu)
    sc.body(name="fluid", method="sph", material="oil", shape="box", min=[0, 0],
            max=[length, 1], spacing=dp)
    sc.body(name="floor", method="sph", wall=True, material="oil", shape="box",
            min=[0, -w], max=[length, 0], spacing=dp)
    sc.body(name="lid", method="sph", wall=True, material="oil", shape="box",
            min=[0, 1], max=[length, 1 + w], spacing=dp, velocity=[1.0, 0.0])
    return sc


def couette_exact(y, t, nu, terms=400):
    """u / U of the Couette start-up between y = 0 (at rest) and y = 1 (sliding at U), from
    rest: y - 2/pi sum_k (-1)^(k+1)/k sin(k pi y) exp(-k^2 pi^2 nu t) (separation of
    variables; the series of y itself at t = 0)."""
    k = np.arange(1, terms + 1)[:, None]
    y = np.asarray(y, float)[None, :]
    return (y - 2.0 / np.pi * np.sum((-1.0) ** (k + 1) / k * np.sin(k * np.pi * y)
                                     * np.exp(-(k * np.pi) ** 2 * nu * t), axis=0))[0]


def coupled_piston(spacing=0.01, period=0.2, depth=0.2, thickness=0.1, kappa=2e4,
                   end=1.0, velocity=None, gravity=-9.81, axis="y"):
    """A coupled scene periodic along x: SPH water (Tait, rho0 = 997) of `depth` on a
    no-slip dummy floor, under an MPM ice layer (neo-Hookean, rho = 917) of `thickness`
    that spans the period, so the water has no free surface: the layer is a piston on a
    compressible column. Started in the hydrostatic state of an open column, it sinks and
    settles where the water's pressure under it carries its weight (`piston_equilibrium`).
    `velocity`: an initial velocity of water and layer, and the floor's (moving) one
    (without gravity: a uniform translation through the period). Grid cells of two
    spacings, periodic along x; the slabs cut along `axis`."""
    sp = spacing
    cell = 2.0 * sp
    floor = 4 * sp
    below = 2 * cell + floor
    cells_y = int(round((below + depth + thickness + 2 * cell) / cell))
    motion = {} if velocity is None else {"velocity": list(velocity)}
    sc = Scene(2, grid=dict(origin=[0.0, -below], cell_size=cell,
                            cells=[int(round(period / cell)), cells_y], periodic=["x"]),
               time=dict(end=end, cfl=0.2), gravity=[0.0, gravity],
               mpm=dict(shape="gimp", transfer="musl", flip=0.0),
               sph=dict(h_factor=1.3, integrator="predictor_corrector", walls="no_slip",
                        hydrostatic=gravity != 0.0, viscosity=dict(alpha=0.1, beta=0.0)),
               parallel=dict(axis=axis, balance_every=0))
    sc.material("ice", model="neo_hookean", E=2e5, nu=0.3, rho=917.0)
    sc.material("water", model="tait", rho=997.0, kappa=kappa, gamma=7.0, mu=0.98)
    sc.body(name="water", method="sph", material="water", shape="box", min=[0.0, 0.0],
            max=[period, depth], spacing=sp, **motion)
    sc.body(name="layer", method="mpm", material="ice", shape="box", min=[0.0, depth],
            max=[period, depth + thickness], spacing=sp, **motion)
    sc.body(name="floor", method="sph", wall=True, material="water", shape="box",
            min=[0.0, -floor], max=[period, 0.0], spacing=sp,
            **(dict(motion, moving=True) if motion else {}))
    return sc


def piston_equilibrium(water_mass, load, rho0=997.0, kappa=2e4, gamma=7.0, g=9.81):
    """Height of a Tait water column of `water_mass` per unit width under the pressure
    `load` at its top, at rest: dp/dy = -rho g with rho = rho0 (1 + p/kappa)^(1/gamma)
    (seed 003, eq. 50) holds m(p) = (int of rho dy from the top) = (p - load)/g of water
    above the level at pressure p, so the bottom is at p_b = load + g water_mass and the
    height is int_load^p_b dp / (rho g)."""
    p = np.linspace(load, load + g * water_mass, 20001)
    inv = 1.0 / (rho0 * (1.0 + p / kappa) ** (1.0 / gamma) * g)
    return float(np.sum(0.5 * (inv[1:] + inv[:-1]) * np.diff(p)))
