"""Pictures of the particles: ``python -m pmpmsph plot RUN --field NAME [--step K|all]
[--movie]`` (the command line is in plot.py).

A field is named as in the snapshots (``rho``, ``pressure``, ``body``, ...), with a part
for vectors and tensors:

    v.x  v.y  v.z     a component (x, y, z or 0, 1, 2)
    sigma.xy          a tensor component
    v.norm  |v|       the Euclidean norm (``speed`` is ``v.norm``)
    pressure, mises   from the stored stress when the run did not store them
                      (io/derived_fields.py: -tr(sigma)/3 and sqrt(3/2)|dev sigma|)

Each particle is drawn as a square-ish marker of its own size (the edge of its volume,
(mass / rho)^(1/d)), coloured by the field, with a colour bar and the time. A 3D run is
drawn as a projection on a coordinate plane (``view``, nearer particles on top; the case's
SPH dummy walls left out, which would hide the rest) or as a slice one particle thick
(``slice_at``: the particles within three quarters of a particle size of that coordinate
along the plane's normal). ``bodies`` picks the bodies drawn (their indices in the case).
"""
import os

import numpy as np

from .config import load_case_text
from .io.derived_fields import derived_field
from .io.results import read

_AXES = {"x": 0, "y": 1, "z": 2, "0": 0, "1": 1, "2": 2}
_ALIASES = {"speed": "v.norm", "velocity": "v.norm"}
#: fields computed from the stress when a snapshot does not hold them
_FROM_STRESS = ("pressure", "mises")
#: resolution of the pictures (the figure is 8 inches wide)
DPI = 120


def field_values(snap, spec):
    """(values per particle, label) of the field `spec` (module docstring) in `snap`."""
    spec = _ALIASES.get(spec, spec)
    if spec.startswith("|") and spec.endswith("|"):
        spec = spec[1:-1] + ".norm"
    name, _, part = spec.partition(".")
    if name in snap:
        arr = np.asarray(snap[name], dtype=np.float64)
    elif name in _FROM_STRESS and "sigma" in snap:
        arr = derived_field(name, snap, len(snap["sigma"]), None)
    else:
        offered = sorted(set(snap) | ({"pressure", "mises"} if "sigma" in snap else set()))
        raise KeyError(f"no field {name!r} in the snapshot; fields: {', '.join(offered)}")
    if arr.ndim == 1:
        if part:
            raise KeyError(f"{name!r} is a scalar: drop the '.{part}'")
        return arr, name
    if part in ("", "norm"):
        flat = arr.reshape(len(arr), -1)
        return np.sqrt(np.einsum("ij,ij->i", flat, flat)), f"|{name}|"
    if arr.ndim == 2 and len(part) == 1 and part in _AXES:
        return arr[:, _AXES[part]], spec
    if arr.ndim == 3 and len(part) == 2 and all(c in _AXES for c in part):
        return arr[:, _AXES[part[0]], _AXES[part[1]]], spec
    raise KeyError(f"cannot take part {part!r} of {name!r} (shape {arr.shape[1:]}): use "
                   f"x, y, z for a vector, xy-style pairs for a tensor, or norm")


def particle_size(snap, dim):
    """Each particle's edge length: (mass / rho)^(1/dim) when the snapshot has both, else
    per body the median distance from a sample of its particles to their nearest neighbour
    (a run that did not write `mass`)."""
    if "mass" in snap and "rho" in snap:
        vol = np.asarray(snap["mass"], float) / np.maximum(np.asarray(snap["rho"], float), 1e-300)
        return vol ** (1.0 / dim)
    x = np.asarray(snap["x"], float)[:, :dim]
    body = np.asarray(snap["body"]) if "body" in snap else np.zeros(len(x), int)
    size = np.zeros(len(x))
    rng = np.random.default_rng(0)
    for b in np.unique(body):
        rows = np.flatnonzero(body == b)
        pts = x[rows]
        sample = pts[rng.choice(len(pts), min(len(pts), 300), replace=False)]
        nearest = []
        for chunk in np.array_split(sample, max(len(sample) // 50, 1)):
            d2 = ((chunk[:, None, :] - pts[None, :, :]) ** 2).sum(-1)
            d2[d2 == 0.0] = np.inf  # the particle itself
            nearest.append(np.sqrt(d2.min(axis=1)))
        nn = np.concatenate(nearest)
        size[rows] = np.median(nn[np.isfinite(nn)]) if np.isfinite(nn).any() else 1.0
    return size


def run_dimension(run, snap):
    """2 or 3 (1 for a line): the run file's `dim`, else from the spread of z."""
    dim = run.attrs.get("dim")
    if dim is not None:
        return int(dim)
    x = np.asarray(snap["x"], float)
    return 3 if np.ptp(x[:, 2]) > 0 else 2


class Frame:
    """What one picture shows: the projected positions, sizes, values and depth order."""

    def __init__(self, snap, spec, dim, view="xy", slice_at=None, bodies=None):
        values, self.label = field_values(snap, spec)
        x = np.asarray(snap["x"], float)
        size = particle_size(snap, dim)
        a, b = _AXES[view[0]], _AXES[view[1]]
        keep = np.ones(len(x), bool)
        if bodies is not None and "body" in snap:
            keep = np.isin(snap["body"], list(bodies))
        order = np.arange(len(x))
        if dim == 3:
            normal = 3 - a - b
            if slice_at is not None:  # three quarters of a particle: a slice between two
                # lattice layers takes both rather than neither (a flow's particles sit a
                # little closer than their seeded spacing)
                keep &= np.abs(x[:, normal] - slice_at) <= 0.75 * size
            # a right-handed view looks down -normal: larger coordinates are nearer
            sign = 1.0 if (a, b) in ((0, 1), (1, 2), (2, 0)) else -1.0
            order = np.argsort(sign * x[:, normal], kind="stable")
        order = order[keep[order]]
        self.xy = x[order][:, [a, b]]
        self.size = size[order]
        self.values = values[order]
        self.time, self.step = snap.time, snap.step
        self.view = view


def _marker_area(ax, fig, frame):
    """Marker areas in points^2 so each particle covers its own size on the axes."""
    fig.canvas.draw()
    box = ax.get_window_extent()
    x0, x1 = ax.get_xlim()
    points_per_unit = box.width * 72.0 / fig.dpi / max(x1 - x0, 1e-300)
    # 15 % larger than the particle, at least a pixel: no seams of background between
    # neighbours that antialiasing would draw at a few pixels a particle
    side = np.maximum(1.15 * frame.size * points_per_unit, 72.0 / fig.dpi)
    return side ** 2


def _limits(frames):
    xy = np.concatenate([f.xy for f in frames]) if frames else np.zeros((1, 2))
    pad = 0.5 * max(float(np.max(f.size)) if len(f.size) else 0.0 for f in frames)
    lo, hi = xy.min(axis=0) - pad, xy.max(axis=0) + pad
    return lo, hi


def _colour_range(frames):
    vals = np.concatenate([f.values for f in frames])
    vals = vals[np.isfinite(vals)]
    if not len(vals):
        return 0.0, 1.0
    lo, hi = float(vals.min()), float(vals.max())
    return (lo, hi) if hi > lo else (lo - 0.5, hi + 0.5)


def _figure(frames, title, limits=None):
    import matplotlib  # noqa: PLC0415 - optional, for pictures only

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415 - after matplotlib.use

    lo, hi = _limits(frames)
    aspect = (hi[1] - lo[1]) / max(hi[0] - lo[0], 1e-300)
    width = 8.0
    fig, ax = plt.subplots(figsize=(width, min(max(width * aspect * 0.85, 2.5), 9.0)),
                           constrained_layout=True)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel(frames[0].view[0])
    ax.set_ylabel(frames[0].view[1])
    vmin, vmax = limits if limits is not None else _colour_range(frames)
    art = ax.scatter(frames[0].xy[:, 0], frames[0].xy[:, 1], c=frames[0].values, s=1.0,
                     marker="s", linewidths=0, cmap="viridis", vmin=vmin, vmax=vmax)
    fig.colorbar(art, ax=ax, label=frames[0].label, shrink=0.9)
    heading = ax.set_title("")

    def show(frame):
        art.set_offsets(frame.xy)
        art.set_array(frame.values)
        art.set_sizes(_marker_area(ax, fig, frame))
        heading.set_text(f"{title}: {frame.label}, t = {frame.time:.4g} (step {frame.step})")
        return art, heading

    return fig, show, plt


def _frames(run, spec, steps, view, slice_at, bodies):
    picked = _pick(run, steps)
    first = run[picked[0]]
    dim = run_dimension(run, first)
    if dim < 3 and (view != "xy" or slice_at is not None):
        raise ValueError(f"--view and --slice are for 3D runs; this run is {dim}D")
    if bodies is None and dim == 3 and slice_at is None:
        bodies = _not_walls(run)
    return [Frame(first if k == picked[0] else run[k], spec, dim, view, slice_at, bodies)
            for k in picked]


def _not_walls(run):
    """The bodies of the run's case that are not SPH dummy walls (a 3D projection through
    a tank shows its walls only), or None (all) when the case text cannot be read back."""
    try:
        case = load_case_text(run.case_text)
    except Exception:  # noqa: BLE001 - a Python-built scene or a mesh file not found: draw all
        return None
    return {i for i, body in enumerate(case.bodies) if not body.wall}


def _pick(run, steps):
    """Snapshot indices for `steps`: None (the last), 'all', or a list of step numbers."""
    if not len(run):
        raise ValueError(f"{run.h5} holds no snapshots")
    if steps is None:
        return [len(run) - 1]
    if steps == "all":
        return list(range(len(run)))
    by_step = {int(s): k for k, s in enumerate(run.steps)}
    missing = [s for s in steps if s not in by_step]
    if missing:
        raise ValueError(f"no snapshot of step {missing[0]}; steps: "
                         f"{', '.join(str(s) for s in run.steps)}")
    return [by_step[s] for s in steps]


def _title(run):
    return run.attrs.get("case_name") or os.path.basename(os.path.normpath(run.folder))


def plot_field(run_path, spec, steps=None, out=None, view="xy", slice_at=None, limits=None,
               bodies=None):
    """One PNG per chosen snapshot (same colour range for all: `limits` (vmin, vmax), by
    default the range over the chosen snapshots); returns their paths."""
    run = read(run_path)
    frames = _frames(run, spec, steps, view, slice_at, bodies)
    fig, show, plt = _figure(frames, _title(run), limits)
    safe = spec.replace("|", "").replace(".", "_")
    paths = []
    for frame in frames:
        show(frame)
        path = out if (out and len(frames) == 1) else os.path.join(
            out or run.folder, f"{safe}_{frame.step:08d}.png")
        fig.savefig(path, dpi=DPI)
        paths.append(path)
    plt.close(fig)
    return paths


def movie(run_path, spec, out=None, view="xy", slice_at=None, fps=10, limits=None,
          bodies=None):
    """An animation over every snapshot: MP4 when ffmpeg exists and `out` ends in .mp4,
    else a GIF (Pillow). Returns its path."""
    import matplotlib.animation as animation  # noqa: PLC0415 - optional, for movies only

    run = read(run_path)
    frames = _frames(run, spec, "all", view, slice_at, bodies)
    fig, show, plt = _figure(frames, _title(run), limits)
    safe = spec.replace("|", "").replace(".", "_")
    out = out or os.path.join(run.folder, f"{safe}.gif")
    if out.endswith(".mp4") and animation.FFMpegWriter.isAvailable():
        writer = animation.FFMpegWriter(fps=fps)
    elif out.endswith(".mp4"):
        raise ValueError("writing .mp4 needs ffmpeg on the PATH; give a .gif name instead")
    else:
        writer = animation.PillowWriter(fps=fps)
    anim = animation.FuncAnimation(fig, lambda k: show(frames[k]), frames=len(frames),
                                   blit=False)
    anim.save(out, writer=writer, dpi=DPI * 2 // 3)
    plt.close(fig)
    return out
