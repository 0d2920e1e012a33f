"""`python -m pmpmsph.bench throughput mpm [--n-grid N ...] [--dim 3] [--no-peers]
[--install-peers]`; `... accuracy [--quick]` (accuracy.py), `... scaling`, `... io`,
`... floats` (floats.py), `... plate` (plate_fsi.py), `... exchange CASE` (exchange.py),
`... plastic` (plastic_cost.py).

Prints particle-steps per second for our solver and for the peers of ../shared/peers run in
the same invocation (machines are shared and noisy: ratios taken together hold, absolute
figures drift), and writes the figures to bench_results/throughput_mpm.json.
"""
import argparse
import os
import sys

from . import write_json


def main(argv: "list[str] | None" = None) -> None:
    ap = argparse.ArgumentParser(prog="python -m pmpmsph.bench")
    sub = ap.add_subparsers(dest="command", required=True)
    tp = sub.add_parser("throughput", help="particle-steps/s against the peers")
    tp.add_argument("method", choices=["mpm", "sph"])
    tp.add_argument("--dx", type=float, nargs="+", default=[0.02],
                    help="sph: particle spacing(s) of the dam break")
    tp.add_argument("--n-grid", type=int, nargs="+", default=None,
                    help="cells per side (default 128 256 in 2D, 32 48 in 3D)")
    tp.add_argument("--dim", type=int, choices=[2, 3], default=2,
                    help="mpm: 3 runs the peers' scene as a cube (ours only: the peers are 2D)")
    tp.add_argument("--steps", type=int, default=400)
    tp.add_argument("--repeat", type=int, default=3)
    tp.add_argument("--no-peers", action="store_true")
    tp.add_argument("--install-peers", action="store_true")
    tp.add_argument("--out", default="bench_results")
    sc = sub.add_parser("scaling", help="strong or weak scaling 1..N ranks, per-phase times, "
                        "messages and bytes per step; scaling.json and scaling.png")
    sc.add_argument("--case", default=None,
                    help="any case file (MPM, SPH, TL-SPH, coupled; 1D-3D) instead of --scene")
    sc.add_argument("--set", action="append", default=[], dest="sets", metavar="KEY=VALUE",
                    help="--case: override a key, as `python -m pmpmsph --set` (repeatable)")
    sc.add_argument("--weak", action="store_true",
                    help="weak scaling: N copies of the scene side by side along the slab "
                         "axis on N ranks (fixed particles per rank)")
    sc.add_argument("--warmup", type=int, default=10,
                    help="steps before the timing (compile/cache load, first balance)")
    sc.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    sc.add_argument("--scene", default="column", choices=["column", "coupled_dam"],
                    help="the MPM water column (--particles) or the coupled dam break on "
                         "an obstacle (--spacing)")
    sc.add_argument("--spacing", type=float, default=0.0033,
                    help="coupled_dam: of every body (0.0033: 55,231 particles, walls 4 layers)")
    sc.add_argument("--particles", type=int, default=500_000)
    sc.add_argument("--steps", type=int, default=100)
    sc.add_argument("--repeat", type=int, default=3,
                    help="rounds over the rank counts; each count's best round is tabulated")
    sc.add_argument("--out", default="bench_results")
    sc.add_argument("--output-every", type=int, default=0,
                    help="also write a snapshot every N steps (output phase)")
    sc.add_argument("--corun", action="store_true",
                    help="also time two independent 1-rank runs of half the scene at once "
                         "against one alone: what sharing the machine costs without MPI")
    ex = sub.add_parser("exchange", help="time per step spent exchanging between ranks, "
                        "per rank, on a case (run it under mpirun; exchange.py)")
    ex.add_argument("case")
    ex.add_argument("--steps", type=int, default=500)
    ex.add_argument("--repeat", type=int, default=3)
    io = sub.add_parser("io", help="output overhead and write bandwidth (bench/io.py)")
    io.add_argument("--ranks", type=int, default=2)
    io.add_argument("--particles", type=int, default=1_000_000)
    io.add_argument("--steps", type=int, default=200)
    io.add_argument("--every", type=int, default=100, help="snapshot every N steps")
    io.add_argument("--out", default="bench_results")
    pc = sub.add_parser("plastic", help="cost of the plastic materials per particle-step "
                        "against neo-Hookean (plastic_cost.py)")
    pc.add_argument("--n", type=int, default=128, help="particles per side of the block")
    pc.add_argument("--steps", type=int, default=200)
    pc.add_argument("--warmup", type=int, default=200)
    pc.add_argument("--repeat", type=int, default=3)
    pc.add_argument("--out", default="bench_results")
    ac = sub.add_parser("accuracy", help="error against cost for every method (accuracy.py)")
    ac.add_argument("--quick", action="store_true", help="coarse levels only (CI smoke)")
    ac.add_argument("--scenes", nargs="+", help="study keys (default: all), e.g. spring")
    ac.add_argument("--out", default=os.path.join("bench_results", "accuracy"))
    ac.add_argument("--readme", action="store_true",
                    help="copy the figures to docs/accuracy/ and rewrite the summary in "
                    "docs/speed_vs_error.md")
    ac.add_argument("--report-only", action="store_true",
                    help="rebuild plots and summary from the CSVs in --out")
    fl = sub.add_parser("floats", help="floating blocks in every method combination "
                        "against Archimedes (floats.py)")
    fl.add_argument("--combos", nargs="+", default=None, help="e.g. mpm_in_sph (default: all)")
    fl.add_argument("--blocks", type=int, nargs="+", default=None,
                    help="indices into floats.BLOCKS (default: all)")
    fl.add_argument("--spacing", type=float, default=0.005)
    fl.add_argument("--end", type=float, default=4.0)
    fl.add_argument("--velocity-update", default="apic", choices=["apic", "pic", "flip"],
                    help="of the MPM bodies (pic: the FLIP blend at 0)")
    fl.add_argument("--cell-spacings", type=int, default=None,
                    help="grid cell size in particle spacings (default: 2 in MPM water, "
                    "4 in SPH water)")
    fl.add_argument("--shape", default=None, help="the MPM bodies' shape function (default: "
                    "quadratic in MPM water, gimp in SPH water)")
    fl.add_argument("--absorber", type=float, default=0.1,
                    help="width of the wave absorbers at the tank's ends (0: none)")
    fl.add_argument("--out", default="bench_results")
    pl = sub.add_parser("plate", help="water on an elastic clamped plate, mid-span deflection "
                        "against the clamped beam (plate_fsi.py)")
    pl.add_argument("--combos", nargs="+", default=["mpm_plate", "mpm_mpm", "sph_plate"],
                    choices=["mpm_plate", "mpm_mpm", "sph_plate", "sph_sph"],
                    help="plate / water: MPM / SPH, MPM / MPM, TL-SPH / MPM, UL-SPH / SPH")
    pl.add_argument("--spacing", type=float, nargs="+", default=[0.01, 0.005, 0.0025])
    pl.add_argument("--end", type=float, default=0.5)
    pl.add_argument("--hourglass", type=float, default=None,
                    help="the SPH plate's [sph] hourglass (default: 0 for the TL-SPH plate, "
                    "whose mirror clamps need none; 2, quadratic fit, for the UL-SPH plate)")
    pl.add_argument("--water-ratio", type=float, default=1.0,
                    help="the water's spacing over the plate's (an SPH water then takes h = "
                    "1.3 of its own spacing; MPM water points per cell fall with it)")
    pl.add_argument("--out", default="bench_results")
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == "io-worker":
        from .io import worker

        return worker(argv[1:])
    if argv and argv[0] == "scaling-worker":
        from .scaling import worker

        return worker(argv[1:])
    args = ap.parse_args(argv)
    if args.command == "accuracy":
        from ..parallel.distributor import Distributor
        from .accuracy import run

        return run(args, Distributor())
    if args.command == "exchange":
        from .exchange import run

        return run(args)
    if args.command == "plastic":
        from .plastic_cost import run

        return run(args)
    if args.command == "floats":
        from .floats import run

        return run(args)
    if args.command == "plate":
        from .plate_fsi import run

        return run(args)
    if args.command == "io":
        from .io import run

        run(args.ranks, args.particles, args.steps, args.every, args.out)
        return 0
    if args.command == "scaling":
        from .scaling import run

        run(args.ranks, args.particles, args.steps, args.out, args.output_every,
            repeat=args.repeat, scene=args.scene, spacing=args.spacing, case=args.case,
            sets=args.sets, weak=args.weak, warmup=args.warmup)
        if args.corun:
            from .scaling import corun

            corun(args.particles, args.steps, args.out)
        return 0

    from .peers import install_peers, run_peer
    from .throughput import bench_mpm, bench_small

    if args.install_peers:
        install_peers()
    if args.method == "sph":
        return throughput_sph(args, run_peer)
    results = {"ours": [], "peers": [], "small": None, "dim": args.dim}
    grids = args.n_grid or ([128, 256] if args.dim == 2 else [32, 48])
    peers = not args.no_peers and args.dim == 2
    label = "pmpmsph (USL, quadratic)" if args.dim == 2 else "pmpmsph 3D (USL, quadratic)"
    print(f"{'program':<28}{'n_grid':>7}{'particles':>11}{'M particle-steps/s':>20}")
    for n_grid in grids:
        r = bench_mpm(n_grid, args.steps, args.repeat, dim=args.dim)
        results["ours"].append(r)
        print(f"{label:<28}{n_grid:>7}{r['particles']:>11}"
              f"{r['rate'] / 1e6:>20.2f}", flush=True)
        if not peers:
            continue
        for peer in ("taichi_mlsmpm.py", "numba_minimal_mlsmpm.py"):
            rate, note = run_peer(peer, [n_grid])
            results["peers"].append({"peer": peer, "n_grid": n_grid, "rate": rate,
                                     "note": note})
            shown = f"{rate / 1e6:>20.2f}" if rate else f"  ({note})"
            print(f"{peer:<28}{n_grid:>7}{'':>11}{shown}", flush=True)
    small = bench_small()
    results["small"] = small
    print(f"scene 1 (10 particles): {small['steps_per_s']:.0f} steps/s")
    if peers:
        print("\nratios (ours / peer, same invocation):")
        for r in results["ours"]:
            for p in results["peers"]:
                if p["n_grid"] == r["n_grid"] and p["rate"]:
                    print(f"  n_grid {r['n_grid']}: / {p['peer']}: {r['rate'] / p['rate']:.2f}")
    write_json(args.out, "throughput_mpm.json" if args.dim == 2 else "throughput_mpm_3d.json",
               results)
    return 0


def throughput_sph(args, run_peer):
    """Our SPH dam break against PySPH's at the same dx, in one invocation."""
    from .throughput import bench_sph

    results = {"ours": [], "peers": []}
    print(f"{'program':<28}{'dx':>7}{'particles':>11}{'M particle-steps/s':>20}")
    for dx in args.dx:
        r = bench_sph(dx, args.steps, args.repeat)
        results["ours"].append(r)
        print(f"{'pmpmsph (WCSPH, PEC)':<28}{dx:>7}{r['particles']:>11}"
              f"{r['rate'] / 1e6:>20.2f}", flush=True)
        ph = r["phases"]
        print("   phases per step (ms): " + ", ".join(
            f"{k} {1e3 * v / (args.repeat * args.steps + 20):.3f}" for k, v in sorted(ph.items())
            if k not in ("setup", "jit_warmup", "run")))
        if args.no_peers:
            continue
        rate, note = run_peer("pysph_dam_break.sh", [dx, args.steps])
        results["peers"].append({"peer": "pysph_dam_break.sh", "dx": dx, "rate": rate,
                                 "note": note})
        shown = f"{rate / 1e6:>20.2f}" if rate else f"  ({note})"
        print(f"{'pysph dam_break_2d':<28}{dx:>7}{'':>11}{shown}", flush=True)
        if rate:
            print(f"  ratio ours / PySPH at dx {dx}: {r['rate'] / rate:.2f}")
    write_json(args.out, "throughput_sph.json", results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
