"""Water on an elastic plate (BENCHMARKS.md scene 20; the static test of Fourey et al. 2017):
a water column of depth H rests on a plate of span L and thickness t clamped at both ends;
its mid-span deflection settles at the clamped beam's

    w = q L^4 / (384 D),  D = E t^3 / (12 (1 - nu^2)),  q = rho_f g H + rho_s g t

(Euler-Bernoulli; plane strain, so D carries 1 - nu^2), plus the shear deflection of a
Timoshenko beam, q L^2 / (8 kappa G t) with kappa = 5/6, which a continuum plate has too:
8 t^2 / ((1 - nu) kappa L^2) of the bending part, 3.4 % at this scene's t / L = 1/20 and
nu = 0.3; the membrane tension of clamped ends that cannot move takes about as much away
(docs/plate.md).

`water_on_plate(combo)` builds the scene: "mpm_plate" (an MPM plate under SPH water, the
plate held by fixed grid nodes beyond the span), "mpm_mpm" (the MPM plate under MPM water,
each body in its own velocity field, frictionless contact), "sph_plate" (a total-Lagrangian
SPH plate, held by a prescribed zero velocity beyond the span, under MPM water) or "sph_sph"
(an updated-Lagrangian SPH plate under SPH water). The side walls stand on the clamps. E is
chosen so that w / L = 1 % (`plate_modulus`). Both bodies are damped
(a -= alpha v, which leaves the static state alone) so that the plate settles within a few
of its periods, 2 pi sqrt(w / g) = 0.13 s. `python -m pmpmsph.bench plate [--water-ratio R]`
runs it (R: the water's spacing over the plate's).
"""
import math
import time
from argparse import Namespace
from typing import Callable

import numpy as np

from ..scene_api import Scene
from ..parallel.distributor import Distributor
from . import write_rows

RHO_WATER = 1000.0
G = 9.81


def load_per_length(depth, thickness, rho_plate, rho_water=RHO_WATER, g=G):
    """q = rho_f g H + rho_s g t."""
    return rho_water * g * depth + rho_plate * g * thickness


def bending_deflection(q, span, thickness, E, nu):
    """Euler-Bernoulli mid-span deflection of a clamped-clamped beam, q L^4 / (384 D)."""
    D = E * thickness**3 / (12.0 * (1.0 - nu**2))
    return q * span**4 / (384.0 * D)


def shear_deflection(q, span, thickness, E, nu, kappa=5.0 / 6.0):
    """Timoshenko's added mid-span deflection of the clamped beam, q L^2 / (8 kappa G t)."""
    return q * span**2 / (8.0 * kappa * E / (2.0 * (1.0 + nu)) * thickness)


def plate_modulus(span, thickness, q, nu, ratio=0.01):
    """E giving a bending deflection of `ratio` x span under q."""
    return q * span**4 * 12.0 * (1.0 - nu**2) / (384.0 * ratio * span * thickness**3)


def water_on_plate(combo: str = "mpm_plate", spacing: float = 0.005, span: float = 0.4,
                   thickness: float = 0.02, depth: float = 0.1, rho_plate: float = 7800.0,
                   nu: float = 0.3, damping: float = 40.0, end: float = 0.6,
                   clamp_cells: int = 2, hourglass: "float | None" = None,
                   water_spacing: "float | None" = None) -> "tuple[Scene, dict]":
    """The scene, and the reference dict (q, E, w_bending, w_shear). `spacing` is the
    plate's particle spacing (the grid's cells are two of them), `water_spacing` the water's
    and its walls' (None: the same; an SPH water takes h = 1.3 of its own). `hourglass`: the
    SPH plate's `[sph] hourglass` (None: 0 for the total-Lagrangian plate, which needs none with
    mirror clamps, 2 with the quadratic fit for the updated one, whose columns pair up
    under SPH water without it; docs/plate.md)."""
    sp = spacing
    wsp = spacing if water_spacing is None else water_spacing
    cell = 2.0 * sp
    wall = 3 * wsp
    clamp = clamp_cells * cell
    q = load_per_length(depth, thickness, rho_plate)
    E = plate_modulus(span, thickness, q, nu)
    c0 = 10.0 * math.sqrt(2.0 * G * depth)
    kappa = c0**2 * RHO_WATER / 7.0
    below = 3 * cell                        # room for the plate to bend into
    x0 = -clamp - 2 * cell
    nx = int(round((span + 2 * clamp + 4 * cell) / cell))
    ny = int(round((below + thickness + depth + 4 * cell) / cell))
    top = thickness + depth + 2 * cell
    fluid_method, plate_method = {"mpm_plate": ("sph", "mpm"), "sph_plate": ("mpm", "sph"),
                                  "mpm_mpm": ("mpm", "mpm"), "sph_sph": ("sph", "sph")}[combo]
    mpm = dict(shape="gimp", transfer="musl", damping=damping)
    if fluid_method == "sph":
        sph = dict(h=1.3 * wsp, integrator="predictor_corrector", walls="slip",
                   damping=damping, hydrostatic=True, viscosity=dict(alpha=0.1, beta=0.0))
        if plate_method == "sph":  # an updated-Lagrangian plate beside the water: Liu's
            # corrected kernel (it reads bending, Bonet-Lok's does not), mirror clamps and the
            # quadratic-fit hourglass control, which leaves bending alone (docs/plate.md)
            sph.update(correction="liu", integrator="verlet", hourglass_fit="quadratic",
                       hourglass=2.0 if hourglass is None else hourglass)
    else:  # a total-Lagrangian SPH plate (the formulation that bends well, BENCHMARKS 12)
        sph = dict(formulation="total", h_factor=1.4, integrator="rk3", damping=damping,
                   hourglass=hourglass or 0.0)
        # water and plate each in their own velocity field, in frictionless contact (an
        # SPH solid takes part in P2G as a body of its own: physics/sph/solid_in_fluid.py)
        mpm.update(hydrostatic=True, velocity_update="apic", contact="multi")
        if plate_method == "mpm":
            sph = None
    space = (dict(grid=dict(origin=[x0, -below], cell_size=cell, cells=[nx, ny]), mpm=mpm)
             if "mpm" in (fluid_method, plate_method) else
             dict(domain=dict(min=[x0, -below], max=[x0 + nx * cell, -below + ny * cell])))
    sc = Scene(2, time=dict(end=end, cfl=0.2), gravity=[0.0, -G],
               parallel=dict(balance_every=0), **space, **({"sph": sph} if sph else {}))
    sc.material("plate", model="neo_hookean", E=E, nu=nu, rho=rho_plate)
    sc.material("water", model="tait", rho=RHO_WATER, kappa=kappa, gamma=7.0, mu=0.0)
    sc.body(name="water", method=fluid_method, material="water", shape="box",
            min=[0.0, thickness], max=[span, thickness + depth], spacing=wsp)
    sc.body(name="plate", method=plate_method, material="plate", shape="box",
            min=[-clamp, 0.0], max=[span + clamp, thickness], spacing=sp)
    eps = 1e-3 * cell
    if fluid_method == "sph":
        for name, lo, hi in (("left", -wall, 0.0), ("right", span, span + wall)):
            sc.body(name=name, method="sph", wall=True, material="water", shape="box",
                    min=[lo, thickness], max=[hi, top], spacing=wsp)
    if fluid_method == "sph" and plate_method == "mpm":
        for lo, hi in ((x0 - cell, eps), (span - eps, x0 + (nx + 1) * cell)):
            sc.data.setdefault("boundaries", []).append(
                dict(box=dict(min=[lo, -below - cell], max=[hi, top + cell]), type="fixed"))
    elif plate_method == "mpm":  # clamps up to the plate's top, slip walls above
        for lo, hi, nx_ in ((x0 - cell, eps, -1.0), (span - eps, x0 + (nx + 1) * cell, 1.0)):
            sc.data.setdefault("boundaries", []).extend([
                dict(box=dict(min=[lo, -below - cell], max=[hi, thickness + eps]),
                     type="fixed"),
                dict(box=dict(min=[lo, thickness + eps], max=[hi, top + cell]), type="slip",
                     normal=[nx_, 0.0])])
    if plate_method == "sph":
        for lo, hi, face in ((-clamp - sp, 0.0, "x+"), (span, span + clamp + sp, "x-")):
            held = dict(body="plate", box=dict(min=[lo, -sp], max=[hi, thickness + sp]),
                        velocity=[0.0, 0.0], mirror=face)  # physics/sph/mirror_clamp.py
            sc.data.setdefault("prescribed", []).append(held)
    if plate_method == "sph" and fluid_method == "mpm":  # slip grid walls for the water
        for lo, hi, nx_ in ((x0 - cell, eps, -1.0), (span - eps, x0 + (nx + 1) * cell, 1.0)):
            sc.data.setdefault("boundaries", []).append(
                dict(box=dict(min=[lo, thickness - eps], max=[hi, top + cell]), type="slip",
                     normal=[nx_, 0.0]))
    ref = dict(q=q, E=E, w_bending=bending_deflection(q, span, thickness, E, nu),
               w_shear=shear_deflection(q, span, thickness, E, nu), span=span)
    return sc, ref


def midspan_deflection(sim, plate_body, span, y0):
    """Mean vertical displacement of the plate's particles in the two columns either side
    of mid-span (the whole thickness: its centre line), from their start heights `y0`
    (by gid)."""
    p = sim.particles
    n = p.n_owned
    mine = (p["body"][:n] == plate_body)
    x = p["x"][:n]
    spacing = float(np.min(sim.case.bodies[plate_body].spacing))
    near = mine & (np.abs(x[:, 0] - 0.5 * span) < 0.75 * spacing)
    gid = p["gid"][:n][near]
    s = sim.dist.sum(np.array([np.sum(x[near, 1] - y0[gid]), float(near.sum())]))
    return s[0] / max(s[1], 1.0)



def start_heights(sim):
    """Every particle's height now, indexed by gid, on every rank (collective)."""
    p = sim.particles
    gid = p["gid"][:p.n_owned]
    y0 = np.full(int(sim.dist.max(int(gid.max()) if len(gid) else 0)) + 1, -np.inf)
    y0[gid] = p["x"][:p.n_owned, 1]
    return sim.dist.max_array(y0)


def plate_run(combo: str = "mpm_plate", on_sample: "Callable | None" = None,
              sample_every: float = 0.01, dist: "Distributor | None" = None,
              **kw: float) -> "tuple[np.ndarray, np.ndarray, dict]":
    """Run the scene; returns (times, mid-span deflections, reference dict)."""
    sc, ref = water_on_plate(combo, **kw)
    sim = sc.simulation(dist=dist) if dist is not None else sc.simulation()
    names = [b.name for b in sim.case.bodies]
    body = names.index("plate")
    y0 = start_heights(sim)
    times, w = [], []
    next_t = [0.0]

    def sample(s):
        if s.time + 1e-12 >= next_t[0]:
            times.append(s.time)
            w.append(midspan_deflection(s, body, ref["span"], y0))
            next_t[0] += sample_every
            if on_sample is not None:
                on_sample(times[-1], w[-1])

    sim.run(on_step=sample)
    sim.close()
    return np.array(times), np.array(w), ref


def settled(times, w, window=0.1):
    """(mean, spread) of the mid-span deflection over the last `window` seconds; the spread
    is (max - min) / |mean|."""
    last = w[times >= times[-1] - window - 1e-12]
    mean = float(np.mean(last))
    return mean, float((last.max() - last.min()) / abs(mean))


def run(args: Namespace) -> int:
    """`python -m pmpmsph.bench plate`: each spacing of each combination; a table and
    `<out>/plate.csv`."""
    rows = []
    if args.hourglass is not None:
        print(f"(the SPH plate with [sph] hourglass = {args.hourglass:g})")
    print(f"{'combination':<12}{'spacing':>9}{'w (mm)':>9}{'EB (mm)':>9}{'error':>9}"
          f"{'Timosh.':>9}{'error':>9}{'spread':>8}{'wall s':>8}")
    for combo in args.combos:
        for sp in args.spacing:
            t0 = time.perf_counter()
            try:
                t, w, ref = plate_run(combo, spacing=sp, end=args.end,
                                      hourglass=args.hourglass,
                                      water_spacing=args.water_ratio * sp)
                mean, spread = settled(t, w)
                failure = ""
            except Exception as exc:  # a failed run is a row of the table, not the end
                ref = water_on_plate(combo, spacing=sp)[1]
                mean, spread, failure = float("nan"), float("nan"), str(exc)
            wb, ws = ref["w_bending"], ref["w_shear"]
            r = dict(combo=combo, spacing=sp, w=-mean, w_bending=wb, w_timoshenko=wb + ws,
                     error=-mean / wb - 1.0, error_timoshenko=-mean / (wb + ws) - 1.0,
                     spread=spread, wall=time.perf_counter() - t0, failure=failure,
                     water_spacing=args.water_ratio * sp)
            rows.append(r)
            print(f"{combo:<12}{sp:>9g}{1e3 * r['w']:>9.4f}{1e3 * wb:>9.4f}{r['error']:>+9.2%}"
                  f"{1e3 * (wb + ws):>9.4f}{r['error_timoshenko']:>+9.2%}{spread:>8.3f}"
                  f"{r['wall']:>8.1f} {failure}", flush=True)
    write_rows(args.out, "plate.csv", rows)
    return 0
