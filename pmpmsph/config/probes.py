"""`[[probes]]`: time series at points, written to RUN/probes.csv (docs/probes.md); part of
config/load.py, whose rules they keep: every error is a `ConfigError` naming the dotted
TOML key, raised before step 1.

Three kinds:
    point   Shepard-interpolated particle values at a fixed position (`fields`)
    gauge   the free-surface elevation along a vertical line (a wave gauge)
    force   the reaction of a `[[prescribed]]` constraint, or the force of the fluid on the
            SPH walls (`walls = true`)
The sampling itself is in io/probe_sampling.py; nothing here knows particles or MPI.
"""
import re
from dataclasses import dataclass
from typing import Optional

from ..errors import ConfigError

KINDS = ("point", "gauge", "force")
#: `fields` of a point probe -> the CSV columns they give, by dimension
POINT_FIELDS = ("pressure", "density", "velocity", "stress")
#: stress components in each dimension (2D: plane strain keeps szz)
STRESS_COMPONENTS = {1: ("xx",), 2: ("xx", "yy", "zz", "xy"),
                     3: ("xx", "yy", "zz", "xy", "yz", "xz")}
#: default fluid fraction at which a gauge puts the free surface (half a kernel below)
GAUGE_THRESHOLD = 0.5
#: a point probe reads nan where the particles cover less than this of its kernel
MIN_FRACTION = 0.1
#: most samples along one gauge line (a typo in `step` must not allocate gigabytes)
MAX_GAUGE_SAMPLES = 100_000

_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


@dataclass(frozen=True)
class ProbeSpec:
    name: str
    kind: str
    key: str                          # dotted key, "probes[i]", for messages
    position: tuple = ()              # point: dim coordinates; gauge: the horizontal ones
    fields: tuple = ()                # point: from POINT_FIELDS
    body: Optional[str] = None        # point/gauge: only this (non-wall) body
    h: Optional[float] = None         # smoothing length of the interpolation (None: scene's)
    min_fraction: float = MIN_FRACTION
    bottom: Optional[float] = None    # gauge: the line's ends along the vertical axis
    top: Optional[float] = None
    step: Optional[float] = None      # gauge: sample spacing (None: h / 4)
    threshold: float = GAUGE_THRESHOLD
    prescribed: Optional[int] = None  # force: index of the [[prescribed]] constraint
    walls: bool = False               # force: the fluid's force on all SPH wall bodies

    def columns(self, dim):
        """This probe's CSV columns, `<name>_<quantity>`."""
        q = []
        if self.kind == "point":
            for f in self.fields:
                if f == "velocity":
                    q += [f"v{c}" for c in "xyz"[:dim]]
                elif f == "stress":
                    q += [f"s{c}" for c in STRESS_COMPONENTS[dim]]
                else:
                    q.append(f)
        elif self.kind == "gauge":
            q.append("elevation")
        else:
            q += [f"f{c}" for c in "xyz"[:dim]]
        return tuple(f"{self.name}_{s}" for s in q)


def vertical_axis(gravity, dim):
    """(axis, up sign) of the vertical: the axis gravity points along (up = against it),
    else the last axis (y in 2D, z in 3D) pointing to +."""
    if any(g != 0.0 for g in gravity):
        a = max(range(dim), key=lambda i: abs(gravity[i]))
        return a, (-1.0 if gravity[a] > 0.0 else 1.0)
    return dim - 1, 1.0


def _inside(key, values, axes, domain):
    """Every coordinate within the domain box along its axis."""
    if domain is None:
        return
    lo, hi = domain
    for i, (v, a) in enumerate(zip(values, axes)):
        if not lo[a] <= v <= hi[a]:
            raise ConfigError(f"{key}[{i}]", f"{v:g} lies outside the domain along "
                              f"{'xyz'[a]} ({lo[a]:g} to {hi[a]:g})")


def _sampled_body(t, bodies):
    """The optional `body` of a point or gauge probe: a known body that is not a wall."""
    if not t.has("body"):
        return None
    name = t.string("body")
    match = [b for b in bodies if b.name == name]
    if not match:
        raise ConfigError(t.key("body"), f"unknown body {name!r}")
    if match[0].wall:
        raise ConfigError(t.key("body"), f"{name!r} is a wall: probes sample the fluids and "
                          "solids (a wall's force: kind = \"force\", walls = true)")
    return name


def _point(t, dim, bodies, domain):
    position = t.vector("position", dim)
    _inside(t.key("position"), position, range(dim), domain)
    raw = t.raw("fields", ["pressure"])
    if not isinstance(raw, list) or not raw:
        raise ConfigError(t.key("fields"), "expected a non-empty list of "
                          f"{', '.join(POINT_FIELDS)}")
    for i, f in enumerate(raw):
        if f not in POINT_FIELDS:
            raise ConfigError(f"{t.key('fields')}[{i}]", f"unknown field {f!r}; choose from "
                              f"{', '.join(POINT_FIELDS)}")
    if len(set(raw)) != len(raw):
        raise ConfigError(t.key("fields"), "a field is listed twice")
    return dict(position=position, fields=tuple(raw), body=_sampled_body(t, bodies),
                min_fraction=t.number("min_fraction", MIN_FRACTION, min=0.0, max_open=1.0))


def _gauge(t, dim, bodies, domain, gravity):
    if dim == 1:
        raise ConfigError(t.key("kind"), "a gauge reads a free surface along a vertical "
                          "line: 2D or 3D scenes")
    axis, _ = vertical_axis(gravity, dim)
    horizontal = [a for a in range(dim) if a != axis]
    position = t.vector("position", dim - 1)
    _inside(t.key("position"), position, horizontal, domain)
    ends = {}
    for end, i in (("bottom", 0), ("top", 1)):
        if t.has(end):
            ends[end] = t.number(end)
            _inside(t.key(end), [ends[end]], [axis], domain)
        elif domain is not None:
            ends[end] = domain[i][axis]
        else:
            raise ConfigError(t.key(end), "required: the scene has no domain box")
    if ends["top"] <= ends["bottom"]:
        raise ConfigError(t.key("top"), f"must be above bottom ({ends['bottom']:g})")
    step = t.number("step", None, min_open=0.0)
    if step is not None and (ends["top"] - ends["bottom"]) / step > MAX_GAUGE_SAMPLES:
        raise ConfigError(t.key("step"), f"gives more than {MAX_GAUGE_SAMPLES} samples "
                          "along the line")
    return dict(position=position, body=_sampled_body(t, bodies), step=step,
                threshold=t.number("threshold", GAUGE_THRESHOLD, min_open=0.0, max_open=1.0),
                **ends)


def _force(t, bodies, prescribed, damping, has_mpm):
    if t.has("prescribed") == t.has("walls"):
        raise ConfigError(t.key("prescribed"), "give either prescribed = <index of a "
                          "[[prescribed]] entry> or walls = true")
    if t.has("prescribed"):
        j = t.number("prescribed", integer=True, min=0)
        if j >= len(prescribed):
            raise ConfigError(t.key("prescribed"), f"names no [[prescribed]] constraint "
                              f"(the scene has {len(prescribed)})")
        return dict(prescribed=j)
    if not t.boolean("walls"):
        raise ConfigError(t.key("walls"), "only walls = true is meaningful")
    # the walls' force is read from the momentum balance of the non-wall particles
    # (io/probe_sampling.py): every other force on them must be known
    if not any(b.wall for b in bodies):
        raise ConfigError(t.key("walls"), "the scene has no SPH wall body (wall = true)")
    if has_mpm:
        raise ConfigError(t.key("walls"), "reads the walls' force from the momentum of "
                          "the SPH particles: not in a scene with MPM bodies")
    if prescribed or damping:
        raise ConfigError(t.key("walls"), "reads the walls' force from the momentum of "
                          "the particles: not with [[prescribed]] or [[damping]], which "
                          "change it too")
    return dict(walls=True)


def probes_from(tables, dim, bodies, prescribed, damping, gravity, domain, has_mpm):
    """`[[probes]]` tables -> tuple of ProbeSpec (checked: module docstring)."""
    out = []
    for i, t in enumerate(tables):
        name = t.string("name", f"probe{i}")
        if not _NAME.match(name):
            raise ConfigError(t.key("name"), f"{name!r} is not a plain name (a letter, then "
                              "letters, digits or _): it prefixes the CSV columns")
        if name in (p.name for p in out):
            raise ConfigError(t.key("name"), f"duplicate probe name {name!r}")
        kind = t.string("kind", choices=KINDS)
        h = t.number("h", None, min_open=0.0)
        if kind == "point":
            extra = _point(t, dim, bodies, domain)
        elif kind == "gauge":
            extra = _gauge(t, dim, bodies, domain, gravity)
        else:
            if h is not None:
                raise ConfigError(t.key("h"), "a force probe interpolates nothing")
            extra = _force(t, bodies, prescribed, damping, has_mpm)
        t.finish()
        out.append(ProbeSpec(name=name, kind=kind, key=t.path, h=h, **extra))
    return tuple(out)


def probes_interval(t):
    """`[output] probes_every` (seconds between probes.csv rows), None: the diagnostics
    schedule."""
    return t.number("probes_every", None, min_open=0.0)
