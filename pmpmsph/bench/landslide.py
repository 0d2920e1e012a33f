"""Wave gauges and the picture of the landslide into water (cases/landslide.toml,
docs/landslide.md; issue 21's showcase).

    python -m pmpmsph.bench.landslide RUN_DIR [--gauges X1 X2] [--times T ...] [--png PATH]

reads RUN_DIR/particles.h5 and writes RUN_DIR/gauges.csv (t, eta1, eta2: the free-surface
elevation above still water at the two gauges, metres) and RUN_DIR/landslide.png (the
particles coloured by body at a few times, the gauges marked, and the two gauge curves).

The free surface at a gauge x_g is measured by volume, not by the highest particle: the
height of the column of moving material (water and sand, every body that is neither a wall
nor held by a [[prescribed]] condition) over x_g is

    d(x_g) = sum_i V_i w(x_i - x_g),   V_i = m_i / rho_i,
    w(s) = (1 - |s| / b) / b for |s| < b (a hat of half-width b, unit integral),

which is exact for a lattice of any spacing dividing b (the hats of the columns sum to one)
and smooth in time (a particle crossing the band's edge enters with weight 0). A drop of
spray above the gauge adds its volume, as a capacitance gauge would not; the highest water
particle in the band (`top_elevation`) is the other reading, kept for comparison. The
elevation is eta = d(t) - d(0): the still water's own compression at t = 0 (the hydrostatic
start) cancels.
"""
from __future__ import annotations

import argparse
import csv
import os
import math
from pathlib import Path

import numpy as np

from ..config.load import load_case_text
from ..io.snapshot_read import list_snapshots, read_attrs, read_snapshot

#: gauge positions (m) of cases/landslide.toml: 0.6 m and 1.2 m downstream of the slope's
#: toe at x = 0.705, beyond the sand's runout and before the absorber (x >= 2.3)
GAUGES = (1.3, 1.9)
#: half-width of the gauge's hat (m): five water spacings of the case
HALF_WIDTH = 0.05
#: snapshot times shown in the picture (s)
TIMES = (0.0, 0.3, 0.6, 1.0)
COLOURS = {"water": "#3b7dd8", "sand": "#c8912e", "slope": "#555555"}
WALL_COLOUR = "#999999"


def column_depth(x, volume, x_gauge, half_width=HALF_WIDTH):
    """Height of the material over `x_gauge`: sum_i V_i w(x_i - x_g) with the hat w of
    half-width `half_width` (module doc). `x`: (n,) or (n, dim) positions (axis 0 used)."""
    x = np.asarray(x, float)
    x = x[:, 0] if x.ndim == 2 else x
    s = np.abs(x - x_gauge) / half_width
    w = np.where(s < 1.0, (1.0 - s) / half_width, 0.0)
    return float(np.sum(np.asarray(volume, float) * w))


def top_elevation(x, x_gauge, half_width=0.5 * HALF_WIDTH):
    """The highest particle's y within |x - x_g| < half_width (nan if none)."""
    x = np.asarray(x, float)
    band = np.abs(x[:, 0] - x_gauge) < half_width
    return float(x[band, 1].max()) if band.any() else float("nan")


def case_bodies(path):
    """(names in body order, indices of the moving bodies: not walls, not held whole) from
    the case stored in a run file, read by the case loader."""
    case = load_case_text(read_attrs(path)["case"])
    held = {s.body for s in case.prescribed if all(math.isinf(v) for v in s.region.lo)}
    names = [b.name for b in case.bodies]
    moving = [i for i, b in enumerate(case.bodies) if not b.wall and b.name not in held]
    return names, moving


def gauge_series(path, gauges=GAUGES, half_width=HALF_WIDTH):
    """(t, eta (n_snapshots, n_gauges), top (same: highest water particle - its t = 0
    value)) over the snapshots of a run file."""
    names, moving = case_bodies(path)
    water = names.index("water") if "water" in names else None
    ts, depth, top = [], [], []
    for info in list_snapshots(path):
        t, _, d = read_snapshot(path, info.index, fields=["x", "body", "mass", "rho"])
        sel = np.isin(d["body"], moving)
        x = d["x"][sel].astype(float)
        vol = d["mass"][sel].astype(float) / d["rho"][sel].astype(float)
        ts.append(t)
        depth.append([column_depth(x, vol, g, half_width) for g in gauges])
        if water is not None:
            xw = d["x"][d["body"] == water].astype(float)
            top.append([top_elevation(xw, g, 0.5 * half_width) for g in gauges])
    depth = np.array(depth)
    top = np.array(top) if top else np.full_like(depth, np.nan)
    return np.array(ts), depth - depth[0], top - top[0]


def peak(t, eta):
    """(peak height, its time, arrival time): the arrival is the first time eta reaches
    10 % of the peak."""
    t, eta = np.asarray(t), np.asarray(eta)
    k = int(np.argmax(eta))
    arrival = float(t[np.argmax(eta >= 0.1 * eta[k])])
    return float(eta[k]), float(t[k]), arrival


def write_gauges(path, t, eta):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t"] + [f"eta{j + 1}" for j in range(eta.shape[1])])
        for k in range(len(t)):
            w.writerow([f"{t[k]:.6g}"] + [f"{v:.6e}" for v in eta[k]])


def picture(path, png, t, eta, gauges=GAUGES, times=TIMES):
    """Particles coloured by body at `times` (the nearest snapshots) over the gauge curves."""
    import matplotlib  # noqa: PLC0415 - only the picture needs it

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415

    names, _ = case_bodies(path)
    case = load_case_text(read_attrs(path)["case"])
    walls = {i for i, b in enumerate(case.bodies) if b.wall}
    infos = list_snapshots(path)
    snap_t = np.array([i.time for i in infos])
    fig = plt.figure(figsize=(10, 2.9 * len(times) + 3.2))
    grid = fig.add_gridspec(len(times) + 1, 1, height_ratios=[1] * len(times) + [1.1],
                            hspace=0.25)
    for row, want in enumerate(times):
        k = int(np.argmin(np.abs(snap_t - want)))
        ts, _, d = read_snapshot(path, k, fields=["x", "body"])
        ax = fig.add_subplot(grid[row])
        colour = np.array([WALL_COLOUR if b in walls else COLOURS.get(names[b], "#2a9d5c")
                           for b in range(len(names))])
        ax.scatter(d["x"][:, 0], d["x"][:, 1], s=1.0, c=colour[d["body"]], linewidths=0,
                   rasterized=True)
        for g in gauges:
            ax.axvline(g, color="crimson", lw=0.8, ls="--")
        ax.set_aspect("equal")
        ax.set_xlim(-0.05, 2.8)
        ax.set_ylim(-0.05, 0.75)
        ax.text(0.45, 0.85, f"t = {ts:.2f} s", transform=ax.transAxes)
        if row == 0:
            ax.set_title("landslide into water: MPM sand (Drucker-Prager) on a held MPM slope, "
                         "SPH water; gauges dashed")
        ax.tick_params(labelsize=8)
    ax = fig.add_subplot(grid[len(times)])
    for j, g in enumerate(gauges):
        ax.plot(t, 1000.0 * eta[:, j], label=f"gauge {j + 1}, x = {g:g} m")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("eta (mm)")
    ax.legend(loc="upper left", fontsize=9)
    ax.grid(alpha=0.3)
    fig.savefig(png, dpi=110, bbox_inches="tight")
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m pmpmsph.bench.landslide",
                                 description="wave gauges and picture of a landslide run")
    ap.add_argument("run_dir", help="the run's output folder (holds particles.h5)")
    ap.add_argument("--gauges", type=float, nargs="+", default=list(GAUGES))
    ap.add_argument("--half-width", type=float, default=HALF_WIDTH)
    ap.add_argument("--times", type=float, nargs="+", default=list(TIMES))
    ap.add_argument("--png", default=None, help="picture path (default RUN_DIR/landslide.png)")
    args = ap.parse_args(argv)
    path = os.path.join(args.run_dir, "particles.h5")
    t, eta, top = gauge_series(path, args.gauges, args.half_width)
    write_gauges(os.path.join(args.run_dir, "gauges.csv"), t, eta)
    for j, g in enumerate(args.gauges):
        h, tp, ta = peak(t, eta[:, j])
        ht, tt, _ = peak(t, np.nan_to_num(top[:, j], nan=-np.inf))
        print(f"gauge {j + 1} at x = {g:g}: peak {1000 * h:.1f} mm at t = {tp:.3f} s, "
              f"arrival (10 % of peak) t = {ta:.3f} s; highest water particle: "
              f"{1000 * ht:.1f} mm at t = {tt:.3f} s")
    png = args.png or os.path.join(args.run_dir, "landslide.png")
    Path(png).parent.mkdir(parents=True, exist_ok=True)
    picture(path, png, t, eta, args.gauges, args.times)
    print(f"wrote {os.path.join(args.run_dir, 'gauges.csv')} and {png}")


if __name__ == "__main__":
    main()
