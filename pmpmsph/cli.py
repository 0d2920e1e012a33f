"""Command line: `python -m pmpmsph CASE.toml`, `check`, `xdmf` (DESIGN.md §1).

Bad input ends every rank with one line naming the TOML key and exit status 2; a failure
during the run ends every rank with step, particle and cause, output left readable, exit 3.
"""
import argparse
import logging
import os
import sys
import time

from .errors import EXIT_CONFIG, EXIT_RUNTIME, ConfigError, RunError

log = logging.getLogger("pmpmsph")


def _parser():
    p = argparse.ArgumentParser(prog="python -m pmpmsph",
                                description="Coupled MPM-SPH solver. Commands: run (default), "
                                "check, xdmf.")
    p.add_argument("case", help="case file (TOML)")
    p.add_argument("--out", help="output folder (default: output/<case name>)")
    p.add_argument("--max-steps", type=int, default=None, help="stop after this many steps")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override a case value, e.g. --set mpm.shape=\"cubic\"")
    p.add_argument("--overwrite", action="store_true", help="replace existing output")
    p.add_argument("--no-output", action="store_true", help="write no files")
    p.add_argument("--progress", type=int, default=None, metavar="N",
                   help="progress line every N steps (default: about 20 lines per run)")
    return p


def _load(args):
    from .config import load_case_file, parse_set

    return load_case_file(args.case, overrides=parse_set(args.set))


def _memory_estimate(sim):
    p = sim.particles
    total = sum(a.nbytes for a in p.arrays.values())
    if sim.mpm is not None:
        g = sim.mpm.grid
        total += sum(a.nbytes for a in (g.mass, g.mom, g.force, g.vel, g.dv, g.mgrad))
    return total


def cmd_check(args, dist):
    from .simulation import Simulation

    case = _load(args)
    sim = Simulation(case, dist=dist, write_output=False)
    n = dist.sum(sim.particles.n_owned)
    nodes = sim.mpm.grid.n_nodes if sim.mpm else 0
    steps = int(round(case.time.end / sim.dt))
    if dist.is_root:
        print(f"case       {case.name} ({case.dim}D)")
        print(f"particles  {n} in {len(case.bodies)} bodies")
        print(f"grid nodes {nodes} (with padding)" if nodes else "grid       none (no MPM)")
        print(f"dt         {sim.dt:.4g} ({'fixed' if case.time.dt else 'CFL'}; stable limit "
              f"{sim.stable_dt():.4g}), about {steps} steps to t = {case.time.end:g}")
        print(f"memory     about {_memory_estimate(sim) / 2**20:.1f} MiB")
    return 0


def cmd_run(args, dist):
    from .simulation import Simulation

    t0 = time.perf_counter()
    case = _load(args)
    out = None if args.no_output else (args.out or os.path.join("output", case.name))
    sim = Simulation(case, dist=dist, out_dir=out, overwrite=args.overwrite)
    n = dist.sum(sim.particles.n_owned)
    est = int(round(case.time.end / sim.dt))
    if args.max_steps is not None:
        est = min(est, args.max_steps)
    every = args.progress or max(est // 20, 1)
    log.info("pmpmsph: %s, %dD, %d particles, %d rank(s), dt %.3g, about %d steps%s", case.name,
             case.dim, n, dist.size, sim.dt, est, f", output in {out}" if out else "")
    try:
        summary = sim.run(max_steps=args.max_steps, progress_every=every)
    finally:
        sim.close()
    t = summary["timers"]
    rate = summary["particles"] * summary["steps"] / max(t.get("run", 0), 1e-9)
    log.info("done: t = %.6g after %d steps; setup %.2f s, JIT warm-up %.2f s, run %.2f s "
             "(%.3g particle-steps/s); total %.2f s", summary["time"], summary["steps"],
             t.get("setup", 0), t.get("jit_warmup", 0), t.get("run", 0), rate,
             time.perf_counter() - t0)
    phases = {k: v for k, v in t.items() if k not in ("setup", "jit_warmup", "run")}
    if phases:
        log.info("phases: %s", ", ".join(f"{k} {v:.2f} s" for k, v in sorted(phases.items())))
    return 0


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    from .parallel.distributor import configure_numba_cache

    configure_numba_cache()
    from .logs import setup_logging
    from .parallel.distributor import Distributor

    dist = Distributor()
    setup_logging(dist.rank, dist.size)
    if argv and argv[0] == "xdmf":
        from .io.xdmf import rebuild_xdmf_main

        return rebuild_xdmf_main(argv[1:]) if dist.is_root else 0
    command = cmd_run
    if argv and argv[0] in ("run", "check"):
        command = cmd_check if argv[0] == "check" else cmd_run
        argv = argv[1:]
    args = _parser().parse_args(argv)
    try:
        return command(args, dist)
    except ConfigError as exc:
        if dist.is_root:
            print(f"error: {exc}", file=sys.stderr)
        return EXIT_CONFIG
    except FileExistsError as exc:
        if dist.is_root:
            print(f"error: invalid input at '--out': {exc} (pass --overwrite)", file=sys.stderr)
        return EXIT_CONFIG
    except RunError as exc:
        if dist.is_root:
            print(f"error: {exc}", file=sys.stderr)
        return EXIT_RUNTIME
    except Exception:  # a bug or fault on this rank only: take every rank down, never hang
        import traceback

        print(f"[rank {dist.rank}] internal error, stopping all ranks:\n"
              + traceback.format_exc(), file=sys.stderr, flush=True)
        if dist.size > 1:
            dist.comm.Abort(EXIT_RUNTIME)
        return EXIT_RUNTIME
