"""``python -m pmpmsph plot RUN [--field NAME [--step K|all] [--movie]] [-o PATH]``.

Without ``--field``: reads ``RUN/diagnostics.csv`` and writes ``RUN/diagnostics.png``
(matplotlib, Agg backend, no display needed): kinetic, strain, potential and total energy;
the momentum components; and the time step, all against time; and ``RUN/probes.png`` when
the run has ``probes.csv``. With ``--field``: the particles coloured by a field
(pictures.py), one PNG per snapshot asked for, or an animation with ``--movie``.
"""
import argparse
import os
import sys

import numpy as np

from .io.diagnostics import read_diagnostics
from .pictures import movie, plot_field


def _csv_of(run):
    return run if run.endswith(".csv") else os.path.join(run, "diagnostics.csv")


def plot_diagnostics(run, out=None):
    """Write the figure; returns its path."""
    import matplotlib  # noqa: PLC0415 - optional, for pictures only

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415 - after matplotlib.use

    path = _csv_of(run)
    d = read_diagnostics(path)
    if "time" not in d or len(d["time"]) == 0:
        raise ValueError(f"{path} has no rows")
    t = d["time"]
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True, constrained_layout=True)
    ax = axes[0]
    for key, style in (("kinetic", "-"), ("strain", "-"), ("potential", "-"), ("total", "k--")):
        if key in d:
            ax.plot(t, d[key], style, label=key)
    ax.set_ylabel("energy")
    ax.legend(loc="best")
    ax.set_title(os.path.basename(os.path.dirname(os.path.abspath(path))) or path)
    ax = axes[1]
    for key in ("px", "py", "pz"):
        if key in d and np.any(np.isfinite(d[key])):
            ax.plot(t, d[key], label=key)
    ax.set_ylabel("momentum")
    ax.legend(loc="best")
    ax = axes[2]
    if "dt" in d:
        ax.plot(t, d["dt"], label="dt")
    ax.set_ylabel("dt")
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.set_xlabel("time")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    out = out or os.path.join(os.path.dirname(os.path.abspath(path)), "diagnostics.png")
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out


def _steps(value):
    """--step: 'all', or a step number (repeatable)."""
    if value == "all":
        return value
    try:
        return int(value)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected a step number or 'all', got {value!r}") from None


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="python -m pmpmsph plot",
        description="Without --field: RUN/diagnostics.csv to RUN/diagnostics.png (and "
        "RUN/probes.csv to RUN/probes.png when the case has probes). With --field: the "
        "particles coloured by that field, e.g. --field pressure, --field v.norm, "
        "--field sigma.xy, --field v.y (pmpmsph/pictures.py).")
    ap.add_argument("run", help="run folder (or its diagnostics.csv)")
    ap.add_argument("-o", "--output", default=None, help="image path (default: in RUN)")
    ap.add_argument("--field", default=None, help="particle field to colour by (name, "
                    "name.x, name.xy, name.norm; pressure and mises from the stress)")
    ap.add_argument("--step", type=_steps, action="append", default=None, metavar="K|all",
                    help="snapshot of step K (repeatable) or all (default: the last)")
    ap.add_argument("--movie", action="store_true", help="an animation over every snapshot "
                    "(GIF; MP4 when -o ends in .mp4 and ffmpeg exists)")
    ap.add_argument("--view", default="xy", choices=("xy", "xz", "yz", "yx", "zx", "zy"),
                    help="3D: the plane to project on (default xy)")
    ap.add_argument("--slice", type=float, default=None, metavar="COORD",
                    help="3D: only the particles within 3/4 of a particle of this coordinate "
                    "along the view's normal")
    ap.add_argument("--body", type=int, action="append", default=None, metavar="I",
                    help="draw only body I (its index in the case; repeatable). Default: all "
                    "bodies, but in a 3D projection not the SPH walls")
    ap.add_argument("--range", type=float, nargs=2, default=None, metavar=("MIN", "MAX"),
                    help="colour range (default: the range over the snapshots drawn)")
    args = ap.parse_args(argv)
    try:
        if args.field is None:
            paths = [plot_diagnostics(args.run, args.output)]
            probes = os.path.join(os.path.dirname(_csv_of(args.run)), "probes.csv")
            if os.path.exists(probes):
                from .io.probes_plot import plot_probes  # noqa: PLC0415 - only with probes

                paths.append(plot_probes(os.path.dirname(probes)))
        elif args.movie:
            paths = [movie(_run_of(args.run), args.field, args.output, args.view, args.slice,
                           limits=args.range, bodies=args.body)]
        else:
            steps = args.step
            if steps is not None and "all" in steps:
                steps = "all"
            paths = plot_field(_run_of(args.run), args.field, steps, args.output, args.view,
                               args.slice, limits=args.range, bodies=args.body)
    except (OSError, ValueError, KeyError) as exc:
        msg = exc.args[0] if isinstance(exc, KeyError) and exc.args else exc
        print(f"error: {msg}", file=sys.stderr)
        return 2
    print("\n".join(paths))
    return 0


def _run_of(path):
    return os.path.dirname(path) if path.endswith(".csv") else path
