"""Throughput: particle-steps per second on one rank, against the peers in one invocation.

mpm: the scene of ../shared/peers/taichi_mlsmpm.py — unit square, n_grid^2 cells, a 0.4 x 0.4
block of (n_grid/2)^2 * 4 fluid particles falling at 1 m/s, quadratic B-spline, dt = 2e-4
(128/n_grid), 20 warm-up steps then 400 timed ones. Our fluid is the Tait material with
gamma = 1 and kappa = E = 400 (the peers' p = -E (J - 1) to first order) and walls that stop
only inflow, like the peers'. We carry what a real solver carries (full F, Cauchy stress,
material dispatch, boundary conditions), the peers only J and C.
mpm --dim 3: the same scene as a cube (n_grid^3 particles), ours only, for the 27-node
stencil (the peers are 2D).
small: BENCHMARKS.md scene 1 (10 particles) in steps per second, for the per-step overhead.
sph: the dam break of ../shared/peers/pysph_dam_break.sh (PySPH examples/dam_break_2d.py,
WCSPH): cases/sph_dam_break.toml at the same dx, h = 1.3 dx, c0, alpha and integrator
(predictor-corrector), timed from the state after `warmup` steps; all particles (water and
wall) count, as in PySPH's figure.
"""
import dataclasses
import os
import time

from ..config import load_case_file
from ..scene_api import Scene
from ..simulation import Simulation


def mpm_peer_scene(n_grid, shape="quadratic", transfer="usl", dim=2):
    """The peers' scene; dim = 3 is its cube version (n_grid^3 particles in a 0.4^3 block,
    no peer to compare with: they are 2D)."""
    n_side = n_grid  # (n_grid/2)^2 * 4 particles = n_grid^2 on a 0.4 x 0.4 lattice
    sc = Scene(dim, grid=dict(origin=[0.0] * dim, length=[1.0] * dim, cells=[n_grid] * dim),
               time=dict(end=1e9, dt=2e-4 * 128 / n_grid), gravity=[0.0, -9.8, 0.0][:dim],
               mpm=dict(shape=shape, transfer=transfer, flip=0.0))
    sc.material("fluid", model="tait", rho=1.0, kappa=400.0, gamma=1.0)
    sc.body(name="block", material="fluid", shape="box", min=[0.2] * dim, max=[0.6] * dim,
            spacing=0.4 / n_side, velocity=[0.0, -1.0, 0.0][:dim])
    for face in ("x-", "x+", "y-", "y+", "z-", "z+")[: 2 * dim]:
        sc.boundary(face=face, type="friction", friction=0.0)
    return sc


def time_simulation(sim: "Simulation", steps: int, warmup: int = 20,
                    repeat: int = 3) -> "tuple[float, float]":
    """Best of `repeat` timed blocks of `steps` steps after `warmup` steps (JIT included)."""
    t0 = time.perf_counter()
    sim.run(max_steps=warmup)
    warm = time.perf_counter() - t0
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        sim.run(max_steps=steps)
        best = min(best, time.perf_counter() - t0)
    return best, warm


def bench_mpm(n_grid: int = 128, steps: int = 400, repeat: int = 3, shape: str = "quadratic",
              dim: int = 2) -> dict:
    sim = mpm_peer_scene(n_grid, shape=shape, dim=dim).simulation()
    n = sim.particles.n_owned
    el, warm = time_simulation(sim, steps, repeat=repeat)
    phases = sim.timers.as_dict()
    return {"n_grid": n_grid, "particles": n, "steps": steps, "seconds": el,
            "rate": n * steps / el, "warmup_s": warm, "phases": phases}


def bench_small(steps: int = 20000) -> dict:
    here = os.path.dirname(os.path.abspath(__file__))
    case = load_case_file(os.path.join(here, "..", "..", "cases", "spring_1d.toml"))
    sim = Simulation(case)
    el, warm = time_simulation(sim, steps, warmup=100, repeat=1)
    return {"particles": sim.particles.n_owned, "steps": steps, "seconds": el,
            "steps_per_s": steps / el}


def bench_sph(dx: float = 0.02, steps: int = 500, repeat: int = 3, warmup: int = 20) -> dict:

    here = os.path.dirname(os.path.abspath(__file__))
    path = os.path.join(here, "..", "..", "cases", "sph_dam_break.toml")
    sets = [(f"bodies[{i}].spacing", dx) for i in range(4)]
    w = 4 * dx
    sets += [("bodies[1].min", [0.0, -w]), ("bodies[2].min", [-w, -w]),
             ("bodies[3].max", [4.0 + w, 4.0]), ("time.end", 1e9)]
    # the solver alone, as the peer's: the case's probes (gauges, a pressure sensor) are
    # sampled by whole-array numpy every 5 ms of simulated time, 7 % of the step here
    case = dataclasses.replace(load_case_file(path, overrides=sets), probes=())
    sim = Simulation(case)
    n = sim.particles.n_owned
    el, warm = time_simulation(sim, steps, warmup=warmup, repeat=repeat)
    return {"dx": dx, "particles": n, "steps": steps, "seconds": el, "rate": n * steps / el,
            "warmup_s": warm, "phases": sim.timers.as_dict(),
            "rebuilds": sim.sph.rebuilds, "evaluations": sim.sph.evaluations}
