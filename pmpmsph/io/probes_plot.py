"""A picture of RUN/probes.csv: one panel per probe (its columns against time), matplotlib
with the Agg backend (no display needed). `plot_probes(run)` returns the PNG's path."""
import os

import numpy as np

from .diagnostics import read_diagnostics


def _csv_of(run):
    return run if run.endswith(".csv") else os.path.join(run, "probes.csv")


def probe_groups(columns):
    """{probe name: [its columns]} in file order. A column is `<name>_<quantity>`; a name
    may hold '_' itself, so the split is at the known quantity suffix."""
    groups = {}
    for c in columns:
        if c in ("time", "step"):
            continue
        name = _probe_of(c)
        groups.setdefault(name, []).append(c)
    return groups


#: the quantity suffixes of config/probes.py ProbeSpec.columns
_QUANTITIES = ("pressure", "density", "elevation", "vx", "vy", "vz", "fx", "fy", "fz",
               "sxx", "syy", "szz", "sxy", "syz", "sxz")


def _probe_of(column):
    for q in _QUANTITIES:
        if column.endswith("_" + q):
            return column[: -len(q) - 1]
    return column


def plot_probes(run, out=None):
    """Draw RUN/probes.csv (or the csv given) to `out` (default RUN/probes.png); returns
    the path. One panel per probe; a point probe's pressure, density, velocity and stress
    share its panel (each a line, labelled by quantity)."""
    import matplotlib  # noqa: PLC0415 - optional, for pictures only

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415 - after matplotlib.use

    path = _csv_of(run)
    d = read_diagnostics(path)
    if "time" not in d or len(d["time"]) == 0:
        raise ValueError(f"{path} has no rows")
    groups = probe_groups(d)
    if not groups:
        raise ValueError(f"{path} has no probe columns")
    t = d["time"]
    fig, axes = plt.subplots(len(groups), 1, figsize=(8, 2.6 * len(groups)), sharex=True,
                             constrained_layout=True, squeeze=False)
    for ax, (name, cols) in zip(axes[:, 0], groups.items()):
        for c in cols:
            y = np.asarray(d[c], float)
            ax.plot(t, y, label=c[len(name) + 1:])
        ax.set_ylabel(name)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize="small")
    axes[0, 0].set_title(os.path.basename(os.path.dirname(os.path.abspath(path))) or path)
    axes[-1, 0].set_xlabel("time")
    out = out or os.path.join(os.path.dirname(os.path.abspath(path)), "probes.png")
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out
