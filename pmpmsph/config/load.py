"""TOML text (or a plain dict from the Python `Scene` API) -> validated, frozen `Case`: the
entry points, and `case_from_dict`, which parses each section (config/sections.py,
config/conditions.py) and checks what spans sections.

Every error is a `ConfigError` naming the dotted TOML key; the CLI turns it into one line
and exit status 2 on every rank.
"""
import copy
import dataclasses
import os
import tomllib

from ..errors import ConfigError
from ..kernels.mpm.shape_functions.registry import shape_named
from ..materials import material_from_table
from ..physics.mpm.transfer_schemes import TRANSFER_SCHEMES
from .case import (CONTACTS, SHAPES, TRANSFERS, VELOCITY_UPDATES, Case, CouplingSpec, MPMSpec,
                   PLASTIC_FIELDS, OutputSpec, ParallelSpec, TimeSpec)
from .conditions import _boundary, _damping, _load, _prescribed
from .probes import probes_from, probes_interval
from .sections import (CASE_DIR, _body, _check_mpm_hydrostatic, _check_periodic, _domain,
                       _grid, _method_region, _sph)
from .table import Table


def parse_set(assignments):
    """`--set a.b=1.5` strings -> list of (dotted key, TOML value)."""
    out = []
    for item in assignments or ():
        if "=" not in item:
            raise ConfigError(item, "--set expects key=value")
        key, val = item.split("=", 1)
        try:
            parsed = tomllib.loads(f"v = {val}")["v"]
        except tomllib.TOMLDecodeError:
            parsed = val  # a bare word is a string
        except RecursionError:
            raise ConfigError(key.strip(), "--set value nested too deep") from None
        out.append((key.strip(), parsed))
    return out


def apply_overrides(data, overrides):
    """Set dotted keys (`a.b`, `bodies[0].ppc`) in the raw case dict."""
    for key, val in overrides:
        node = data
        parts = key.split(".")
        try:
            for part in parts[:-1]:
                if "[" in part:
                    name, idx = part[:-1].split("[")
                    node = node[name][int(idx)]
                else:
                    node = node.setdefault(part, {})
            if not isinstance(node, dict):
                raise TypeError
            node[parts[-1]] = val
        except (KeyError, IndexError, ValueError, TypeError, AttributeError):
            raise ConfigError(key, "--set names no value that can be set here") from None
    return data


def load_case_text(text, name="case", overrides=(), base_dir=None):
    """`base_dir`: folder of relative paths in the case (mesh files); default the cwd."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError("<toml>", f"not valid TOML: {exc}") from None
    except RecursionError:  # tomllib parses nested arrays and tables recursively
        raise ConfigError("<toml>", "not valid input: values nested too deep") from None
    data = apply_overrides(data, overrides)
    token = CASE_DIR.set(base_dir)
    try:
        return case_from_dict(data, name=name, text=text)
    finally:
        CASE_DIR.reset(token)


def load_case_file(path, overrides=()):
    try:
        with open(path, encoding="utf-8-sig") as fh:  # -sig: a byte-order mark is fine
            text = fh.read()
    except OSError as exc:
        raise ConfigError("<file>", f"cannot read {path}: {exc.strerror}") from None
    except UnicodeDecodeError as exc:
        raise ConfigError("<file>", f"{path} is not UTF-8 text (byte {exc.start}): a case "
                          "file is TOML text") from None
    name = os.path.splitext(os.path.basename(path))[0]
    return load_case_text(text, name=name, overrides=overrides,
                          base_dir=os.path.dirname(os.path.abspath(path)))


# -- pieces -----------------------------------------------------------------------------------
def _case_name(name):
    """The case name names the default output folder output/<name>: one plain path part."""
    if not name.strip() or name in (".", "..") or any(c in name for c in "/\\\0"):
        raise ConfigError("name", f"{name!r} is not a plain name (it names the output "
                          "folder output/<name>): no path separators, not empty, '.' or '..'")
    return name


def _folder(t, key, default):
    """A folder the case writes to: relative and inside the current directory tree. (The
    command line's --out is the user's explicit choice; a case file must not write
    elsewhere.)"""
    path = t.string(key, default)
    norm = os.path.normpath(path) if path else ""
    if (not path or os.path.isabs(path) or os.path.splitdrive(path)[0] or "\0" in path
            or norm == ".." or norm.startswith(".." + os.sep)):
        raise ConfigError(t.key(key), f"{path!r} is not a folder inside the current "
                          "directory: give a relative path without '..' that leaves it "
                          "(use --out for anywhere else)")
    return path


def case_from_dict(data, name="case", text=""):
    data = copy.deepcopy(data)
    root = Table(data, "")
    dim = root.number("dimension", integer=True, min=1, max=3)
    name = _case_name(root.string("name", name))
    grid_t = root.sub("grid", None)
    grid = _grid(grid_t, dim) if grid_t is not None else None

    mpm_t = root.sub("mpm", {})
    if mpm_t.has("contact_gap"):
        raise ConfigError(mpm_t.key("contact_gap"), "no longer a setting: multi-field contact "
                          "acts where the bodies' particle surfaces meet (no gap to choose)")
    mpm = MPMSpec(
        shape=mpm_t.string("shape", "linear", choices=SHAPES),
        transfer=mpm_t.string("transfer", "usl", choices=TRANSFERS),
        flip=mpm_t.number("flip", 1.0, min=0.0, max=1.0),
        velocity_update=mpm_t.string("velocity_update", "flip", choices=VELOCITY_UPDATES),
        damping=mpm_t.number("damping", 0.0, min=0.0),
        mass_cutoff=mpm_t.number("mass_cutoff", 1e-10, min=0.0),
        contact=mpm_t.string("contact", "single", choices=CONTACTS),
        friction=mpm_t.number("friction", 0.0, min=0.0),
        cpdi_reach=mpm_t.number("cpdi_reach", 2, integer=True, min=1, max=8),
        deformation=mpm_t.string("deformation", "auto", choices=("auto", "F", "J")),
        hydrostatic=mpm_t.boolean("hydrostatic", False),
        fbar=mpm_t.boolean("fbar", False),
    )
    if mpm.velocity_update != "flip" and mpm_t.has("flip"):
        raise ConfigError(mpm_t.key("flip"), "applies to velocity_update = \"flip\" only "
                          f"(the {mpm.velocity_update} transfer has no FLIP increment)")
    if mpm.velocity_update == "mls":
        if shape_named(mpm.shape).apic_d_inverse == 0.0:  # (the B-splines)
            raise ConfigError(mpm_t.key("velocity_update"), "\"mls\" needs shape = "
                              f"\"quadratic\" or \"cubic\" (its gradient is D^-1 N (x_I - x_p) "
                              f"of a B-spline), not {mpm.shape!r}; \"apic\" takes any shape")
        if not TRANSFER_SCHEMES[mpm.transfer].stress_last:
            raise ConfigError(mpm_t.key("velocity_update"), "\"mls\" is an update-stress-last "
                              f"scheme: it needs transfer = \"usl\", not {mpm.transfer!r}")
    if mpm_t.has("cpdi_reach") and mpm.shape != "cpdi":
        raise ConfigError(mpm_t.key("cpdi_reach"), "applies to shape = \"cpdi\" only")
    mpm_t.finish()
    if grid is not None and mpm.shape == "cpdi":
        # room for domain corners up to cpdi_reach cells from a particle that may sit one cell
        # outside the domain (pad) or have moved a cell since the last migration (ghosts)
        grid = dataclasses.replace(grid, pad=mpm.cpdi_reach + 1, ghost=mpm.cpdi_reach + 2)

    mats_t = root.sub("materials")
    materials = {}
    for mname in mats_t.data:
        materials[mname] = material_from_table(mats_t.raw(mname), mats_t.key(mname), dim)
    if not materials:
        raise ConfigError("materials", "define at least one material")

    bodies = tuple(_body(bt, dim, materials, grid) for bt in root.subs("bodies"))
    if not bodies:
        raise ConfigError("bodies", "define at least one [[bodies]] entry")
    names = [b.name for b in bodies]
    for i, n in enumerate(names):
        if names.index(n) != i:
            raise ConfigError(f"bodies[{i}].name", f"duplicate body name {n!r}")
    if any(b.method == "mpm" for b in bodies) and grid is None:
        raise ConfigError("grid", "MPM bodies need a [grid] section")
    regions = tuple(_method_region(rt, dim) for rt in root.subs("regions"))
    coup_t = root.sub("coupling", {})
    coupling = CouplingSpec(handover=coup_t.boolean("handover", False),
                            interface=coup_t.string("interface", "seed",
                                                    choices=("seed", "conservative")))
    coup_t.finish()
    if coupling.handover and not regions:
        raise ConfigError("coupling.handover", "handover needs [[regions]] to hand over at")
    methods = {b.method for b in bodies} | {r.method for r in regions}
    if mpm.fbar and not any(materials[b.material].plastic for b in bodies
                            if b.method == "mpm" or regions):
        raise ConfigError("mpm.fbar", "averages the volume change of plastic materials "
                          "(von_mises, drucker_prager) and no MPM body has one")
    has_sph = "sph" in methods
    coupled = has_sph and "mpm" in methods
    if coupled and grid is None:
        raise ConfigError("grid", "a coupled MPM-SPH scene needs a [grid]")
    sph_t = root.sub("sph", None)
    if sph_t is not None and not has_sph:
        raise ConfigError("sph", "an [sph] section but no body with method = \"sph\"")
    sph = _sph(sph_t if sph_t is not None else Table({}, "sph"), dim, bodies,
               materials, grid, coupled) if has_sph else None
    if coupled and coupling.interface == "conservative" and (
            sph.integrator != "verlet" or sph.formulation != "updated"):
        raise ConfigError("coupling.interface", "the conservative interface interleaves the "
                          "SPH kicks with the MPM step: it needs sph.integrator = \"verlet\" "
                          "and the updated formulation")
    dom_t = root.sub("domain", None)
    periodic = ()
    periodic_key = "domain.periodic"
    if dom_t is not None:
        domain, periodic = _domain(dom_t, dim)
        if periodic and grid is not None:
            raise ConfigError(periodic_key, "a scene with a [grid] is periodic along the "
                              "grid's periodic axes ([grid] periodic), over the grid's length")
    elif grid is not None:
        domain = (grid.origin, grid.upper)
        if has_sph:  # a coupled scene: the particles share the grid's period
            periodic, periodic_key = grid.periodic, "grid.periodic"
    elif has_sph:
        raise ConfigError("domain", "an SPH scene without a [grid] needs a [domain] box "
                          "(min, max) that the particles stay in")
    else:
        domain = None
    if periodic:
        _check_periodic(periodic, domain, bodies, periodic_key)
        if sph is not None and sph.formulation == "total":
            raise ConfigError(periodic_key, "total-Lagrangian SPH keeps its reference "
                              "neighbours: periodic axes are for updated-Lagrangian SPH")
        for axis in periodic:  # images of images would meet: 3 cells of the support 2h
            length = domain[1][axis] - domain[0][axis]
            if sph is not None and length < 6.0 * sph.h:
                raise ConfigError(periodic_key, f"the period {length:g} along "
                                  f"{'xyz'[axis]} is shorter than 6 h = {6.0 * sph.h:g} "
                                  "(three kernel supports): lengthen the domain")
    boundaries = tuple(_boundary(bt, dim) for bt in root.subs("boundaries"))
    for b in boundaries:
        if grid is None:
            raise ConfigError(b.key, "boundaries act on the MPM grid and this scene has no "
                              "[grid] (SPH walls are bodies with wall = true)")
        if b.region.lo is not None and any(
                b.region.hi[a] < grid.origin[a] or b.region.lo[a] > grid.upper[a]
                for a in range(dim)):
            raise ConfigError(f"{b.key}.box", "lies outside the grid: it holds no grid node")
        if b.region.face and "xyz".index(b.region.face[0]) in grid.periodic:
            raise ConfigError(f"{b.key}.face", f"{b.region.face} is an end of the periodic "
                              f"axis {b.region.face[0]}: a periodic axis has no ends")
    loads = tuple(_load(lt, dim, names) for lt in root.subs("loads"))
    if len({ld.ramp for ld in loads}) > 1:
        raise ConfigError("loads[1].ramp", "all loads share one ramp time in this version")
    prescribed = tuple(_prescribed(pt, dim, names) for pt in root.subs("prescribed"))
    for ps in prescribed:
        body = bodies[names.index(ps.body)]
        if ps.mirror and (body.method != "sph" or body.wall or sph is None
                          or materials[body.material].fluid):
            raise ConfigError(f"{ps.key}.mirror", "a mirror clamp is for SPH solids; an MPM "
                              "body is clamped by [[boundaries]] on the grid")
    damping = tuple(_damping(dt, dim) for dt in root.subs("damping"))
    if damping and not any(materials[b.material].fluid for b in bodies):
        raise ConfigError(damping[0].key, "a damping zone acts on fluids and this scene has "
                          "none")
    gravity = root.vector("gravity", dim, (0.0,) * dim)
    if mpm.hydrostatic:
        _check_mpm_hydrostatic(bodies, materials, gravity)

    tt = root.sub("time")
    end = tt.number("end", min_open=0.0)
    dt = tt.number("dt", None, min_open=0.0)
    cfl = tt.number("cfl", None, min_open=0.0, max=1.0)
    if (dt is None) == (cfl is None):
        raise ConfigError(tt.key("dt"), "give exactly one of time.dt or time.cfl")
    max_steps = tt.number("max_steps", TimeSpec.max_steps, integer=True, min=1)
    tt.finish()

    ot = root.sub("output", {})
    every = ot.number("every", None, min_open=0.0)
    every_steps = ot.number("every_steps", None, integer=True, min=1)
    if every is not None and every_steps is not None:
        raise ConfigError(ot.key("every_steps"), "give output.every or output.every_steps")
    fields = ot.raw("fields", list(OutputSpec().fields)
                    + (list(PLASTIC_FIELDS) if any(m.plastic for m in materials.values())
                       else []))
    if not isinstance(fields, list) or not all(isinstance(f, str) for f in fields):
        raise ConfigError(ot.key("fields"), "expected a list of field names")
    if not fields:
        raise ConfigError(ot.key("fields"), "a snapshot needs at least one field (e.g. "
                          "[\"gid\", \"x\"]); use --no-output for a run that writes nothing")
    output = OutputSpec(every=every, every_steps=every_steps,
                        diagnostics_every=ot.number("diagnostics_every", None, integer=True,
                                                    min=1),
                        fields=tuple(fields),
                        precision=ot.string("precision", "single",
                                            choices=("single", "double")),
                        folder=_folder(ot, "folder", "output"),
                        checkpoint_every=ot.number("checkpoint_every", 0, integer=True, min=0),
                        probes_every=probes_interval(ot))
    ot.finish()
    probes = probes_from(root.subs("probes"), dim, bodies, prescribed, damping, gravity,
                         domain, "mpm" in methods)
    if output.probes_every is not None and not probes:
        raise ConfigError(ot.key("probes_every"), "the scene has no [[probes]]")
    pt = root.sub("parallel", {})
    axis = pt.string("axis", "auto", choices=("auto",) + tuple("xyz"[:dim]))
    parallel = ParallelSpec(axis=None if axis == "auto" else "xyz".index(axis),
                            balance_every=pt.number("balance_every", 50, integer=True, min=0),
                            balance_threshold=pt.number("balance_threshold", 0.1, min_open=0.0),
                            balance_by=pt.string("balance_by", "work", choices=("work", "time")))
    pt.finish()
    root.finish()
    case = Case(name=name, dim=dim, grid=grid, mpm=mpm, materials=materials, bodies=bodies,
                boundaries=boundaries, loads=loads, prescribed=prescribed, damping=damping,
                gravity=gravity,
                time=TimeSpec(end, dt, cfl, max_steps), output=output, parallel=parallel, sph=sph,
                domain=domain, periodic=periodic, regions=regions, coupling=coupling,
                probes=probes, text=text)
    if mpm.deformation == "J" and not case.tracks_J_only:
        raise ConfigError("mpm.deformation", "J alone describes fluids only: it needs a pure-MPM "
                          "scene (no SPH), a shape other than cpdi and only fluid materials")
    return case
