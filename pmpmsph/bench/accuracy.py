"""`python -m pmpmsph.bench accuracy [--quick] [--scenes KEY ...] [--out DIR] [--readme]`.

The accuracy-cost map of BENCHMARKS.md "Speed against error": for scenes 1, 3, 8, 9, 12, 14,
the dam-break front, the Prandtl footing and the granular column collapse, every method that
applies is run at every resolution of the scene's knob (the studies in `accuracy_1d`,
`accuracy_2d`, ... define the metric, reference and methods), and each point's error, wall
time, particle-steps and memory are recorded.

Every point runs on the communicator it is given (all ranks of `mpirun -n N` together, the
normal `Simulation`), wall time is the slowest rank's, rank 0 writes: DIR/<scene>.csv,
DIR/<scene>.png (error against wall time and against particle-steps, one curve per method),
DIR/orders.csv and DIR/summary.md (observed orders, fastest method to 1 % and 0.1 %,
methods that do not converge and why). `--readme` also copies the figures to docs/accuracy/
and rewrites the section between the accuracy markers of docs/speed_vs_error.md with the summary.
"""
import csv
import json
import os
import time
from argparse import Namespace

import numpy as np

from ..errors import RunError
from ..parallel.distributor import Distributor
from . import accuracy_report as report
from .accuracy_1d import BAR, REVERSAL, SPRING, STRESS
from .accuracy_2d import DAM, DISKS, PLATE
from .accuracy_core import COLUMNS, cost
from .accuracy_fluids import CAVITY, COUETTE
from .accuracy_fsi import PLATE_FSI
from .accuracy_granular import COLUMN
from .accuracy_plastic import FOOTING


def studies():
    return [SPRING, DISKS, REVERSAL, STRESS, PLATE, BAR, DAM, CAVITY, COUETTE, PLATE_FSI,
            FOOTING, COLUMN]


def run_point(dist, study, method, level, quick):
    """One row of the scene's CSV. A run that fails (det F <= 0, NaN: a RunError, raised
    on every rank alike) is a row with error = nan and the cause in `note`."""
    row = {"scene": study["key"], "method": method["label"], "family": method["family"],
           "level": level, "knob": study["knob_of"](level), "note": ""}
    try:
        sim, secs, res = study["run"](dist, method, level, quick)
        row.update(cost(sim, secs), error=res["error"], aux=res["aux"],
                   series=res.get("series"))
    except RunError as exc:
        row.update(error=np.nan, aux=np.nan, note=f"failed: {exc}")
    return row


# --quick runs two MPM variants per scene (and every other method) at the coarse levels
QUICK_MPM = {("gimp", "usl"), ("quadratic", "musl")}


def chosen_methods(study, quick):
    if not quick:
        return study["methods"]
    return [m for m in study["methods"]
            if m.get("quick") or m["family"] != "MPM"
            or (m["shape"], m["transfer"]) in QUICK_MPM]


def sweep(dist, study, quick, log):
    rows = []
    for method in chosen_methods(study, quick):
        levels = method.get("levels", study["levels"])  # a method may stop sooner
        for level in levels["quick" if quick else "full"]:
            t0 = time.perf_counter()
            row = run_point(dist, study, method, level, quick)
            rows.append(row)
            log(f"{study['key']:<14}{method['label']:<34}{level:>8}  error "
                f"{row['error']:.3e}  wall {row.get('wall', np.nan):8.2f} s  "
                f"({time.perf_counter() - t0:.1f} s) {row['note'][:60]}")
            if row["note"]:  # finer levels of a method that failed are not tried
                break
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in COLUMNS})


def run(args: Namespace, dist: Distributor) -> int:
    chosen = [s for s in studies() if not args.scenes or s["key"] in args.scenes]
    root = dist.is_root
    if root:
        os.makedirs(args.out, exist_ok=True)

    def log(msg):
        if root:
            print(msg, flush=True)

    t0 = time.perf_counter()
    for study in chosen if not args.report_only else []:
        rows = sweep(dist, study, args.quick, log)
        if root:
            write_csv(os.path.join(args.out, f"{study['key']}.csv"), rows)
            if study.get("series"):  # a time series per run (the dam break's wall gauge)
                report.plot_series(args.out, study, rows, readme=args.readme)
    wall = dist.max(time.perf_counter() - t0)
    if root:
        meta = os.path.join(args.out, "sweep.json")
        if args.report_only and os.path.exists(meta):  # the figures of the sweep itself
            with open(meta) as fh:
                m = json.load(fh)
        else:
            m = {"quick": args.quick, "ranks": dist.size, "wall": wall,
                 "date": time.strftime("%Y-%m-%d")}
            with open(meta, "w") as fh:
                json.dump(m, fh)
        report.build(args.out, chosen, quick=m["quick"], ranks=m["ranks"], wall=m["wall"],
                     readme=args.readme, date=m["date"])
        print(f"accuracy sweep: {wall:.0f} s on {dist.size} rank(s); written {args.out}")
    return 0
