"""Command line: `python -m pmpmsph CASE.toml`, `--restart`, `check`, `xdmf`, `vtu`, `plot`
(DESIGN.md §1, §6).

Bad input ends every rank with one line naming the TOML key and exit status 2; a failure
during the run ends every rank with step, particle and cause, output left readable, exit 3.
"""
import argparse
import logging
import os
import sys
import time

from .errors import EXIT_CONFIG, EXIT_RUNTIME, ConfigError, RunError, RunStopped

log = logging.getLogger("pmpmsph")


class _Parser(argparse.ArgumentParser):
    """argparse that reports a bad option as bad input (one line naming the option, exit 2
    on every rank) instead of printing its usage on each rank and exiting."""

    def error(self, message):
        option, sep, reason = message.partition(": ")
        if not (sep and option.startswith("argument ")):
            raise ConfigError("<command line>", message)
        names = option[len("argument "):].split("/")
        raise ConfigError(max(names, key=len), reason)


def _parser():
    p = _Parser(prog="python -m pmpmsph",
                                description="Coupled MPM-SPH solver. Commands: run (default), "
                                "check, xdmf RUN.h5, vtu RUN, plot RUN.")
    p.add_argument("case", nargs="?", help="case file (TOML); with --restart optional (the "
                   "checkpoint holds the case)")
    p.add_argument("--out", help="output folder (default: output/<case name>; with --restart "
                   "the checkpoint's folder, whose particles.h5/diagnostics.csv are continued)")
    p.add_argument("--restart", metavar="CHECKPOINT",
                   help="continue from a checkpoint (e.g. output/NAME/checkpoint.h5) on any "
                   "number of ranks")
    p.add_argument("--max-steps", type=int, default=None, help="stop after this many steps")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override a case value, e.g. --set mpm.shape=\"cubic\"")
    p.add_argument("--overwrite", action="store_true", help="replace existing output")
    p.add_argument("--no-output", action="store_true", help="write no files")
    p.add_argument("--progress", type=int, default=None, metavar="N",
                   help="progress line every N steps (default: about 20 lines per run)")
    return p


def _check_parser():
    """`check` takes the case and its overrides only: it builds the scene, runs no step."""
    p = _Parser(prog="python -m pmpmsph check",
                description="Load and validate a case without running it (on any number of "
                "ranks): bad input stops with one line naming the key, exit 2; a good case "
                "prints its particles, grid, time step, step count and memory.")
    p.add_argument("case", nargs="?", help="case file (TOML)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="override a case value, e.g. --set mpm.shape=\"cubic\"")
    p.add_argument("--max-steps", type=int, default=None,
                   help="the step limit a run would use (checked like the run's)")
    p.set_defaults(progress=None)
    return p


def _check_options(args):
    """Values argparse accepts by type but the run cannot use."""
    if args.max_steps is not None and args.max_steps < 0:
        raise ConfigError("--max-steps", f"must be 0 or more, got {args.max_steps}")
    if args.progress is not None and args.progress < 1:
        raise ConfigError("--progress", f"must be 1 or more, got {args.progress}")


def _load(args, dist):
    """The case, read by every rank; bad input on any rank stops every rank."""
    from .config import load_case_file, parse_set

    def load():
        _check_options(args)
        if args.case is None:
            raise ConfigError("<case>", "give a case file (or --restart CHECKPOINT)")
        return load_case_file(args.case, overrides=parse_set(args.set))

    return dist.agree("case", load)


def _load_for_restart(args, dist):
    """The case of a restart: the case file if given, else the checkpoint's case text with
    its stored --set overrides followed by this command's. Returns (case, overrides)."""
    from .config import load_case_text, parse_set
    from .io.checkpoint import read_header

    def header():
        try:
            return read_header(args.restart)
        except Exception as exc:  # noqa: BLE001 - bad input, whatever the reader raised
            raise ConfigError("--restart",
                              f"cannot read checkpoint {args.restart}: {exc}") from None

    head = dist.agree("restart", header, root_only=True)
    if args.case is not None:
        return _load(args, dist), parse_set(args.set)

    def load():
        _check_options(args)
        if not head.get("case"):
            raise ConfigError("--restart", "the checkpoint holds no case text (a scene built "
                              "in Python): give the case file as well")
        overrides = list(head["case_overrides"]) + parse_set(args.set)
        return load_case_text(head["case"], name=head.get("case_name", "case"),
                              overrides=overrides,
                              base_dir=head.get("case_dir") or None), overrides

    return dist.agree("case", load)


def _memory_estimate(sim):
    p = sim.particles
    total = sum(a.nbytes for a in p.arrays.values())
    if sim.mpm is not None:
        g = sim.mpm.grid
        total += sum(a.nbytes for a in (g.mass, g.mom, g.force, g.vel, g.dv, g.mgrad))
    return total


def cmd_check(args, dist):
    from .simulation import Simulation

    case = _load(args, dist)
    sim = Simulation(case, dist=dist, write_output=False, max_steps=args.max_steps,
                     check_steps=True)
    n = dist.sum(sim.particles.n_owned)
    nodes = sim.mpm.grid.n_nodes if sim.mpm else 0
    steps = int(round(sim.steps_to_end()))
    limit = sim.stable_dt()  # collective (global max of the signal speed): on every rank
    if dist.is_root:
        print(f"case       {case.name} ({case.dim}D)")
        print(f"particles  {n} in {len(case.bodies)} bodies")
        print(f"grid nodes {nodes} (with padding)" if nodes else "grid       none (no MPM)")
        print(f"dt         {sim.dt:.4g} ({'fixed' if case.time.dt else 'CFL'}; stable limit "
              f"{limit:.4g}), about {steps} steps to t = {case.time.end:g}")
        print(f"memory     about {_memory_estimate(sim) / 2**20:.1f} MiB")
    return 0


def cmd_run(args, dist):
    from .config import parse_set
    from .io.checkpoint import STOP
    from .simulation import Simulation

    t0 = time.perf_counter()
    if args.restart:
        case, overrides = _load_for_restart(args, dist)
        default_out = os.path.dirname(os.path.abspath(args.restart))
    else:
        case, overrides = _load(args, dist), parse_set(args.set)
        default_out = os.path.join(case.output.folder, case.name)
    out = None if args.no_output else (args.out or default_out)
    sim = Simulation(case, dist=dist, out_dir=None if args.restart else out,
                     overwrite=args.overwrite,
                     out_key="--out" if args.out or args.restart else "output.folder",
                     max_steps=args.max_steps, check_steps=True)
    sim.case_overrides = tuple(overrides)
    sim.case_dir = os.path.dirname(os.path.abspath(args.case)) if args.case else None
    if args.restart:
        head = sim.restore_checkpoint(args.restart)
        if args.case is None:
            sim.case_dir = head.get("case_dir") or None
        if out:
            appended = sim.open_restart_output(out, overwrite=args.overwrite)
            log.info("restart output %s %s", "continues" if appended else "starts in", out)
        sim.check_step_count(args.max_steps)  # from the restored time on
    n = dist.sum(sim.particles.n_owned)
    est = int(round(sim.steps_to_end()))
    if args.max_steps is not None:
        est = min(est, args.max_steps)
    every = args.progress or max(est // 20, 1)
    log.info("pmpmsph: %s, %dD, %d particles, %d rank(s), dt %.3g, about %d steps%s", case.name,
             case.dim, n, dist.size, sim.dt, est, f", output in {out}" if out else "")
    try:
        with STOP:  # SIGTERM/SIGINT/SIGUSR1: checkpoint + snapshot after the step, exit 3
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
    if out and dist.is_root:
        files = [f for f in ("particles.h5", "particles.xdmf", "diagnostics.csv",
                             "probes.csv", "checkpoint.h5") if os.path.exists(os.path.join(out, f))]
        size = sum(os.path.getsize(os.path.join(out, f)) for f in files)
        log.info("output: %s in %s (%.1f MiB); plot with: python -m pmpmsph plot %s",
                 ", ".join(files), out, size / 2**20, out)
    return 0


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    from .logs import setup_logging
    from .parallel.distributor import Distributor

    dist = Distributor()
    setup_logging(dist.rank, dist.size)
    if argv and argv[0] == "xdmf":
        from .io.xdmf import rebuild_xdmf_main

        return rebuild_xdmf_main(argv[1:]) if dist.is_root else 0
    if argv and argv[0] in ("plot", "vtu"):
        if argv[0] == "plot":
            from .plot import main as tool
        else:
            from .io.vtu import main as tool
        return tool(argv[1:]) if dist.is_root else 0
    command = cmd_run
    if argv and argv[0] in ("run", "check"):
        command = cmd_check if argv[0] == "check" else cmd_run
        argv = argv[1:]
    try:
        args = (_check_parser() if command is cmd_check else _parser()).parse_args(argv)
        return command(args, dist)
    except ConfigError as exc:
        if dist.is_root:
            print(f"error: {exc}", file=sys.stderr)
        return EXIT_CONFIG
    except RunError as exc:
        if dist.is_root:
            print(f"error: {exc}", file=sys.stderr)
        return EXIT_RUNTIME
    except RunStopped as exc:
        if dist.is_root:
            print(str(exc), file=sys.stderr, flush=True)
        return EXIT_RUNTIME
    except Exception:  # a bug or fault on this rank only: take every rank down, never hang
        import traceback

        print(f"[rank {dist.rank}] internal error, stopping all ranks:\n"
              + traceback.format_exc(), file=sys.stderr, flush=True)
        if dist.size > 1:
            dist.abort(EXIT_RUNTIME)
        return EXIT_RUNTIME
