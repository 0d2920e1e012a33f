"""``python -m pmpmsph plot RUN [-o PNG]``: the diagnostics of a run at a glance.

Reads ``RUN/diagnostics.csv`` and writes ``RUN/diagnostics.png`` (matplotlib, Agg backend,
no display needed): kinetic, strain, potential and total energy; the momentum components;
and the time step, all against time.
"""
import argparse
import os
import sys

import numpy as np

from .io.diagnostics import read_diagnostics


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


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m pmpmsph plot",
                                 description="Plot RUN/diagnostics.csv to RUN/diagnostics.png.")
    ap.add_argument("run", help="run folder (or its diagnostics.csv)")
    ap.add_argument("-o", "--output", default=None, help="image path (default "
                    "RUN/diagnostics.png)")
    args = ap.parse_args(argv)
    try:
        out = plot_diagnostics(args.run, args.output)
    except (OSError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(out)
    return 0
