"""Floating blocks in every method combination (issue 19, item 1).

A rectangular block (neo-Hookean, E = 2e5, nu = 0.3, density `ratio` x 997) of `width` x
`height` is dropped from `drop` above the surface of Tait water (rho0 = 997, kappa = 2e4,
gamma = 7, mu = 0.98) `depth` deep in a tank `tank` wide, started hydrostatic. Combinations
(block in water): "mpm_in_sph" (SPH water in a tank of dummy walls; the coupling's fluid-solid
pairs), "sph_in_mpm" (an SPH solid in MPM water; physics/sph/solid_in_fluid.py), "mpm_in_mpm" (both
MPM, one velocity field per body, frictionless contact where the particle surfaces meet),
"sph_in_sph" (both SPH).

Reference: Archimedes' principle in the Tait water at rest: the draft d of the rectangle of
the block's seeded mass m per unit thickness, width * int_0^d rho(z) dz = m with rho(z) the
hydrostatic density at depth z (physics/hydrostatic.py). Measured from the block's own
geometry: its bottom face y_b (the mean of its lowest row of points minus half a spacing)
below the far-field surface (the water's top rows, more than a block width from the block's
centre, plus half a spacing): `error`. The surface particles of MPM water keep rearranging
after the block has settled (block 0 at spacing 0.005: the top rows sink 1.2 mm from t = 1.8
to 3.9 s while the block's bottom stays within 0.1 mm and the water's volume within 1e-4;
docs/floats.md), so a second measure leaves them out, `error_level`: the draft below the
level the water has at rest with the block in it, H = H0 + width d / tank, so
d = (H0 - y_b) / (1 - width / tank), H0 the seeded depth shortened by the block's weight
spread over the floor (m g / tank over the Tait bulk modulus kappa gamma: 0.1-0.3 % of a
draft). `float_run` returns the submerged fractions d/height against the reference and the
block's settling (its centre-of-mass vertical speed over the last tenth of the run over the
impact speed sqrt(2 g drop)). Both ends of the tank have wave absorbers (`absorber`), so
the sloshing the drop excites dies out within the run.
"""
import inspect
import math
import time
from argparse import Namespace

import numpy as np

from pmpmsph import Scene

from ..parallel.distributor import Distributor
from ..physics.hydrostatic import tait_hydrostatic_density
from . import write_rows

COMBOS = ("mpm_in_sph", "sph_in_mpm", "mpm_in_mpm", "sph_in_sph")
RHO_F, KAPPA, GAMMA, MU, G = 997.0, 2.0e4, 7.0, 0.98, 9.81
#: (width, height, density ratio, drop): none is a shipped case's block, and each floats
#: upright (width/height above sqrt(6 s (1 - s)), the metacentre above the centre of mass)
BLOCKS = ((0.10, 0.06, 0.80, 0.010), (0.08, 0.04, 0.50, 0.020), (0.14, 0.04, 0.95, 0.005),
          (0.12, 0.06, 0.65, 0.015), (0.06, 0.05, 0.90, 0.010), (0.16, 0.08, 0.70, 0.005))


def float_scene(combo: str, width: float = 0.1, height: float = 0.06, ratio: float = 0.8,
                drop: float = 0.01, tank: float = 0.5, depth: float = 0.2,
                spacing: float = 0.005, end: float = 4.0,
                cell_spacings: "float | None" = None, velocity_update: str = "apic",
                contact: str = "multi", shape: "str | None" = None, transfer: str = "musl",
                absorber: float = 0.1) -> Scene:
    """The scene of one float (module doc); grid cells of `cell_spacings` spacings and the MPM
    bodies' `shape` function, by default (None) those that do best in each water: in MPM
    water quadratic B-splines on cells of 2 spacings (docs/floats.md), in SPH water GIMP on
    cells of 4 (the grid carries the block alone); the MPM
    bodies' `velocity_update` ("apic", or "pic": the FLIP blend at 0); with MPM water, the
    `contact` "multi" (one velocity field per body, frictionless contact) or "single" (one
    velocity field for water and block); the MPM bodies' `transfer` scheme; wave absorbers
    (`[[damping]]`, rate 10/s) `absorber` wide at both ends of the tank (0: none), so the
    sloshing the drop excites dies out and the block settles."""
    block_method, water_method = combo.split("_in_")
    sp = spacing
    if cell_spacings is None:
        cell_spacings = 2 if water_method == "mpm" else 4
    if shape is None:
        shape = "quadratic" if water_method == "mpm" else "gimp"
    cell = tank / round(tank / (cell_spacings * sp))  # nodes on the tank's faces
    walls = 4 * sp if water_method == "sph" else 0.0
    # MPM water: the tank's walls are the grid's faces, whose slip condition mirrors the
    # nodes beyond them (a wall inside a padded grid leaves those nodes free, and quadratic
    # weights reach them: water leaked out at a corner after 4 s, docs/floats.md)
    pad = 0 if water_method == "mpm" else int(math.ceil(walls / cell)) + 1
    top = max(depth, depth + drop + height) + 2 * cell
    cells = [int(round(tank / cell)) + 2 * pad, int(math.ceil(top / cell)) + pad]
    origin = [-pad * cell, -pad * cell]
    coupled = block_method != water_method
    sections = dict(grid=dict(origin=origin, cell_size=cell, cells=cells),
                    time=dict(end=end, cfl=0.2), gravity=[0.0, -G],
                    parallel=dict(balance_every=0))
    if "mpm" in combo:
        mpm = dict(shape=shape, transfer=transfer)
        if velocity_update == "pic":
            mpm["flip"] = 0.0
        else:
            mpm["velocity_update"] = velocity_update
        if water_method == "mpm":
            if contact == "multi":  # one velocity field per body, frictionless contact
                mpm.update(contact="multi", friction=0.0)
            if not coupled:
                mpm["hydrostatic"] = True
        sections["mpm"] = mpm
    if "sph" in combo:
        sections["sph"] = dict(h_factor=1.3, integrator="predictor_corrector",
                               hydrostatic=True, viscosity=dict(alpha=0.1, beta=0.0))
        if water_method == "sph":
            sections["sph"]["walls"] = "no_slip"
    if block_method == water_method == "sph":  # no grid: a [domain] box
        del sections["grid"]
        sections["domain"] = dict(min=origin, max=[origin[0] + cells[0] * cell,
                                                   origin[1] + cells[1] * cell])
    sc = Scene(2, **sections)
    sc.material("ice", model="neo_hookean", E=2e5, nu=0.3, rho=ratio * RHO_F)
    sc.material("water", model="tait", rho=RHO_F, kappa=KAPPA, gamma=GAMMA, mu=MU)
    sc.body(name="water", method=water_method, material="water", shape="box",
            min=[0.0, 0.0], max=[tank, depth], spacing=sp)
    x0 = 0.5 * (tank - width)
    sc.body(name="block", method=block_method, material="ice", shape="box",
            min=[x0, depth + drop], max=[x0 + width, depth + drop + height], spacing=sp)
    if water_method == "sph":
        for name, lo, hi in (("floor", [-walls, -walls], [tank + walls, 0.0]),
                             ("left", [-walls, 0.0], [0.0, top]),
                             ("right", [tank, 0.0], [tank + walls, top])):
            sc.body(name=name, method="sph", wall=True, material="water", shape="box",
                    min=lo, max=hi, spacing=sp)
    if absorber > 0:
        for lo, hi, direction in (([0.0, -walls], [absorber, top], "x-"),
                                  ([tank - absorber, -walls], [tank, top], "x+")):
            sc.damping(box=dict(min=lo, max=hi), direction=direction)
    if water_method == "mpm":
        for face in ("x-", "x+", "y-"):
            sc.boundary(face=face, type="slip")
    elif block_method == "mpm":  # the tank's walls on the padded grid, for the MPM block
        span = [origin[1] - cell, origin[1] + (cells[1] + 1) * cell]
        wide = [origin[0] - cell, origin[0] + (cells[0] + 1) * cell]
        eps = 1e-3 * sp
        for box, normal in ((dict(min=[wide[0], -eps], max=[wide[1], eps]), [0.0, -1.0]),
                            (dict(min=[-eps, span[0]], max=[eps, span[1]]), [-1.0, 0.0]),
                            (dict(min=[tank - eps, span[0]], max=[tank + eps, span[1]]),
                             [1.0, 0.0])):
            sc.boundary(box=box, type="slip", normal=normal)
    return sc


def archimedes_fraction(mass, width, height):
    """Submerged fraction d/height of a rectangle of `mass` per unit thickness floating in
    the Tait water at rest (module doc), by bisection on d."""
    lo, hi = 0.0, 2.0 * height
    z = np.linspace(0.0, 1.0, 2001)
    for _ in range(60):
        d = 0.5 * (lo + hi)
        rho = tait_hydrostatic_density(RHO_F, KAPPA, GAMMA, G, d * z)
        displaced = width * d * float(np.sum(0.5 * (rho[1:] + rho[:-1]) * np.diff(z)))
        lo, hi = (d, hi) if displaced < mass else (lo, d)
    return 0.5 * (lo + hi) / height


def _block_state(sim, spacing, width, tank, depth, mass):
    """(draft below the far-field top rows, draft below the water's rest level, the block's
    centre-of-mass vertical velocity) of the float (module doc)."""
    p = sim.particles
    n = p.n_owned
    x, body, v, m = p["x"][:n], p["body"][:n], p["v"][:n], p["mass"][:n]
    block = body == 1
    yb = x[block, 1]
    bottom = float(yb[yb < yb.min() + 0.5 * spacing].mean()) - 0.5 * spacing
    # the rest level: the seeded water, compressed by the block's weight spread over the
    # tank's floor, raised by the volume the block displaces
    seeded = depth * (1.0 - mass * G / (tank * KAPPA * GAMMA))
    level_draft = (seeded - bottom) / (1.0 - width / tank)
    xc = float(np.average(x[block, 0], weights=m[block]))
    far = (body == 0) & (np.abs(x[:, 0] - xc) > width) & (x[:, 0] > 2 * spacing) & (
        x[:, 0] < tank - 2 * spacing)
    # the far-field surface: the mean of the top particles of column bins two spacings wide
    bins = np.floor(x[far, 0] / (2 * spacing)).astype(np.int64)
    bins -= bins.min()
    tops = np.full(bins.max() + 1, -np.inf)
    np.maximum.at(tops, bins, x[far, 1])
    surface = float(np.mean(tops[np.isfinite(tops)])) + 0.5 * spacing
    return surface - bottom, level_draft, float(np.average(v[block, 1], weights=m[block]))


def float_run(combo: str, dist: "Distributor | None" = None, **kw: float) -> dict:
    """Run one float (one rank; `kw` as `float_scene`); returns a dict: fraction (mean over
    the last fifth of the run), reference, error (relative), error_level, settle (max
    |v_com| over the last tenth / impact speed), drift (the least-squares slope of the
    rest-level draft over the last fifth, over the draft: its relative change per second;
    a block creeping at 1 mm/s passes `settle` for these drops but shows here), steps,
    particles."""
    call = inspect.signature(float_scene).bind(combo, **kw)
    call.apply_defaults()
    a = call.arguments  # the scene's arguments, defaults included
    sim = float_scene(**a).simulation(dist=dist or Distributor.serial(),
                                      write_output=False)
    block = sim.particles["body"] == 1
    mass = float(sim.particles["mass"][block].sum())
    drafts, speeds, times = [], [], []

    def track(s):
        if s.time >= 0.8 * a["end"]:
            *draft, vcom = _block_state(s, a["spacing"], a["width"], a["tank"], a["depth"],
                                        mass)
            drafts.append(draft)
            times.append(s.time)
            if s.time >= 0.9 * a["end"]:
                speeds.append(abs(vcom))

    sim.run(on_step=track)
    fraction, fraction_level = np.mean(drafts, axis=0) / a["height"]
    level = np.array(drafts)[:, 1]
    drift = float(np.polyfit(times, level, 1)[0] / np.mean(level)) if len(times) > 1 else 0.0
    reference = archimedes_fraction(mass, a["width"], a["height"])
    impact = math.sqrt(2.0 * G * a["drop"])
    return dict(combo=combo, fraction=float(fraction), reference=reference,
                error=float(fraction / reference - 1.0),
                settle=max(speeds) / impact if impact > 0 else math.nan,
                error_level=float(fraction_level / reference - 1.0), drift=drift,
                steps=sim.step_count, particles=sim.particles.n_owned)


def run(args: Namespace) -> int:
    """`python -m pmpmsph.bench floats`: every block of BLOCKS in every combination; a table
    and `<out>/floats.csv`."""
    combos = args.combos or COMBOS
    blocks = args.blocks if args.blocks is not None else range(len(BLOCKS))
    rows = []
    print(f"{'combination':<12}{'block (w, h, s, drop)':>28}{'fraction':>10}{'Archimedes':>11}"
          f"{'error':>9}{'settle':>9}{'level':>9}{'drift/s':>9}{'wall s':>8}")
    for combo in combos:
        for i in blocks:
            w, h, s, drop = BLOCKS[i]
            t0 = time.perf_counter()
            try:
                r = float_run(combo, width=w, height=h, ratio=s, drop=drop,
                              spacing=args.spacing, end=args.end,
                              velocity_update=args.velocity_update,
                              cell_spacings=args.cell_spacings, shape=args.shape,
                              absorber=args.absorber)
            except Exception as exc:  # a failed run is a row of the table, not the end
                r = dict(combo=combo, fraction=float("nan"), reference=float("nan"),
                         error=float("nan"), settle=float("nan"),
                         error_level=float("nan"), drift=float("nan"), failure=str(exc))
            r.update(block=i, wall=time.perf_counter() - t0)
            rows.append(r)
            print(f"{combo:<12}{str(BLOCKS[i]):>28}{r['fraction']:>10.4f}"
                  f"{r['reference']:>11.4f}{r['error']:>+9.2%}{r['settle']:>9.3f}"
                  f"{r['error_level']:>+9.2%}{r['drift']:>+9.2%}"
                  f"{r['wall']:>8.1f} {r.get('failure', '')}", flush=True)
    write_rows(args.out, "floats.csv", rows)
    return 0
