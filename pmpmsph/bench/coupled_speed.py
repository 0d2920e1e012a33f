"""`python -m pmpmsph.bench coupled [--spacing S] [--steps N]` under `mpirun -n R`: the time
per step of cases/coupled_dam_obstacle.toml (SPH water, MPM rubber obstacle, SPH walls)
with every body seeded at spacing S, on the R ranks of this job, for issue 19's two-rank
efficiency (run it with -n 1 and -n 2 on an otherwise idle machine; efficiency =
t1 / (2 t2)). Ten untimed steps first (the first balance, the caches), then N timed; the
slowest rank's time and its phases (ms per step) are printed."""
import os
import time

CASE = os.path.join(os.path.dirname(__file__), "..", "..", "cases", "coupled_dam_obstacle.toml")


def run(args, dist):
    from .. import load_case_file
    from ..simulation import Simulation

    sets = [(f"bodies[{i}].spacing", args.spacing) for i in range(5)]
    sim = Simulation(load_case_file(os.path.normpath(CASE), overrides=sets), dist=dist,
                     write_output=False)
    particles = int(dist.sum(sim.particles.n_owned))
    for _ in range(10):
        sim.step()
    before = dict(sim.timers.total)
    dist.barrier()
    t0 = time.perf_counter()
    for _ in range(args.steps):
        sim.step()
    dist.barrier()
    per_step = dist.max(time.perf_counter() - t0) / args.steps
    phases = {k: dist.max(v - before.get(k, 0.0)) / args.steps * 1e3
              for k, v in sorted(sim.timers.total.items())}
    if dist.is_root:
        print(f"ranks {dist.size}  particles {particles}  {per_step * 1e3:.2f} ms/step  "
              f"{particles / per_step / 1e6:.3f} M particle-steps/s")
        print("  ms/step by phase (slowest rank): "
              + ", ".join(f"{k} {v:.2f}" for k, v in phases.items() if v >= 0.01))
    return 0
