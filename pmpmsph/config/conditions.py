"""Case-file sections that select a region and act on it: `[[boundaries]]` (grid faces or
boxes), `[[loads]]` (traction or stress on a body's particles in a box), `[[prescribed]]`
(velocities of a body's particles in a box) and `[[damping]]` (wave absorbers on the fluids'
particles in a box); part of config/load.py, whose rules they keep:
every error is a `ConfigError` naming the dotted TOML key."""
import math

from ..errors import ConfigError
from ..kernels.mpm.grid_conditions.registry import condition_named, grid_conditions
from .case import BC_KINDS, BoundarySpec, DampingSpec, LoadSpec, PrescribedSpec, Region
from .table import is_finite

FACES = ("x-", "x+", "y-", "y+", "z-", "z+")


def _region(t, dim, required=True):
    if t.has("face"):
        face = t.string("face", choices=FACES[: 2 * dim])
        return Region(face=face)
    if t.has("box") or required:
        box = t.sub("box")
        lo = box.vector("min", dim)
        hi = box.vector("max", dim)
        for a in range(dim):
            if hi[a] < lo[a]:
                raise ConfigError(box.key("max") + f"[{a}]", "max is below min")
        box.finish()
        return Region(lo=lo, hi=hi)
    return None


def _voigt_len(dim):
    return {1: 1, 2: 3, 3: 6}[dim]


def _face_normal(face, dim):
    n = [0.0] * dim
    n["xyz".index(face[0])] = 1.0 if face[1] == "+" else -1.0
    return tuple(n)


def _boundary(t, dim):
    region = _region(t, dim)
    kind = t.string("type", choices=BC_KINDS)
    condition = condition_named(kind)
    if region.face:
        normal = _face_normal(region.face, dim)
        if t.has("normal"):
            raise ConfigError(t.key("normal"), "a face has its own normal; remove 'normal'")
    elif condition.normal == "none":
        normal = (0.0,) * dim
    else:
        normal = t.vector("normal", dim)
        norm = math.sqrt(sum(c * c for c in normal))
        if norm == 0:
            raise ConfigError(t.key("normal"), "normal must not be zero")
        normal = tuple(c / norm for c in normal)
    mu = t.number("friction", 0.0, min=0.0) if condition.friction else 0.0
    until = t.number("until", math.inf, min=0.0) if t.has("until") else math.inf
    velocity = ()
    if t.has("velocity"):
        if not condition.velocity:
            moving = " or ".join(f'"{c.name}"' for c in grid_conditions() if c.velocity)
            raise ConfigError(t.key("velocity"), f"a wall velocity applies to type = {moving} "
                              "(the nodes take it: a lid)")
        velocity = t.vector("velocity", dim)
        if region.face and velocity[FACES.index(region.face) // 2] != 0.0:
            raise ConfigError(t.key("velocity"), "a face may only move along itself (its "
                              "normal component must be 0)")
    t.finish()
    return BoundarySpec(region, kind, normal, mu, until, t.path, velocity)


def _no_face(t):
    """Loads and prescribed velocities select particles in a box; a grid face holds none."""
    if t.has("face"):
        raise ConfigError(t.key("face"), "this acts on the particles of a body inside a box: "
                          "give box = { min = [...], max = [...] } (faces are for [[boundaries]])")


def _load(t, dim, body_names):
    body = t.string("body")
    if body not in body_names:
        raise ConfigError(t.key("body"), f"unknown body {body!r}")
    _no_face(t)
    region = _region(t, dim)
    if t.has("stress") == t.has("traction"):
        raise ConfigError(t.key("traction"), "give either traction or stress (with normal)")
    ramp = t.number("ramp", 0.0, min=0.0)
    normal = t.string("normal", choices=FACES[: 2 * dim])
    if t.has("stress"):  # a stress on the surface acts as the traction sigma . n
        sigma = _voigt_matrix(t.vector("stress", _voigt_len(dim)), dim)
        n = _face_normal(normal, dim)
        traction = tuple(sum(sigma[i][j] * n[j] for j in range(dim)) for i in range(dim))
    else:
        traction = t.vector("traction", dim)
    t.finish()
    return LoadSpec(body, region, traction, normal, ramp, t.path)


def _voigt_matrix(v, dim):
    """Voigt order (xx; xx yy xy; xx yy zz yz xz xy) -> nested lists dim x dim."""
    if dim == 1:
        return [[v[0]]]
    if dim == 2:
        return [[v[0], v[2]], [v[2], v[1]]]
    return [[v[0], v[5], v[4]], [v[5], v[1], v[3]], [v[4], v[3], v[2]]]


def _prescribed(t, dim, body_names):
    body = t.string("body")
    if body not in body_names:
        raise ConfigError(t.key("body"), f"unknown body {body!r}")
    _no_face(t)
    region = _region(t, dim, required=False) or Region(lo=(-math.inf,) * dim,
                                                       hi=(math.inf,) * dim)
    raw = t.raw("velocity")
    if not isinstance(raw, list) or len(raw) != dim:
        raise ConfigError(t.key("velocity"), f"expected {dim} entries (numbers, or \"free\")")
    vel = []
    for i, c in enumerate(raw):
        if c == "free":
            vel.append(None)
        elif isinstance(c, (int, float)) and not isinstance(c, bool) and is_finite(c):
            vel.append(float(c))
        else:
            raise ConfigError(f"{t.key('velocity')}[{i}]", "expected a number or \"free\"")
    start = t.number("start", 0.0, min=0.0)
    until = t.number("until", math.inf, min=0.0) if t.has("until") else math.inf
    mirror = None
    if t.has("mirror"):
        mirror = t.string("mirror", choices=FACES[: 2 * dim])
        if any(c != 0.0 for c in vel) or start > 0.0 or until < math.inf:
            raise ConfigError(t.key("mirror"), "a mirror clamp holds its particles at rest "
                              "for the whole run: velocity all 0, no start or until")
        if not math.isfinite((region.hi if mirror[1] == "+" else region.lo)["xyz".index(
                mirror[0])]):
            raise ConfigError(t.key("mirror"), "the clamp face needs a box (it lies on the "
                              "box's face)")
    t.finish()
    return PrescribedSpec(body, region, tuple(vel), start, until, t.path, mirror)


def _damping(t, dim):
    """A wave absorber (DualSPHysics' damping zone): a box, the face towards which the damping
    grows (`direction`) and its full rate (1/s; 10 as DualSPHysics' default)."""
    _no_face(t)
    region = _region(t, dim)
    direction = t.string("direction", choices=FACES[: 2 * dim])
    a = "xyz".index(direction[0])
    if region.hi[a] <= region.lo[a]:
        raise ConfigError(t.key("box") + ".max", f"the box has no depth along {direction[0]}, "
                          "the direction the damping grows in")
    rate = t.number("rate", 10.0, min_open=0.0)
    t.finish()
    return DampingSpec(region, direction, rate, t.path)
