"""The initial particle state of a scene from its `Case`: every body seeded, its material, method
and load fields set, the bad set-ups (overlaps, too many points, empty bodies) refused."""
import numpy as np

from .codes import METHOD_CODES
from .config.initial_fields import field_values, voigt_tensors
from .errors import ConfigError
from .io.derived_fields import offered
from .kernels.mpm.shape_functions.registry import shape_named
from .particles import F_FIELD, J_FIELD, FieldSpec, ParticleSet
from .physics.coupling import coupling_fields
from .physics.loads import PrescribedVelocity, TractionLoads, _in_region
from .physics.mpm.stage import MPMStage
from .physics.sph.stage import SPHStage
from .physics.sph.total_lagrangian import TLSPHStage
from .scene.regions import region_methods
from .scene.seeding import seed_body


def sph_stage_class(case):
    """The SPH stage of a scene: updated-Lagrangian (seed 000) or total (seed 004)."""
    return TLSPHStage if case.sph.formulation == "total" else SPHStage


#: most lattice points a scene may seed: every rank seeds every body before keeping its own
#: particles, so this bounds the memory of one rank at set-up (about 1 kB per point)
MAX_SEEDED = 1e8


def lattice_points(body, grid):
    """How many lattice points `seed_body` lays over the body's bounding box (before it keeps
    those inside the geometry), from the geometry and ppc/spacing/count alone, in floating
    point: a scene can be rejected before anything is allocated. Mesh bodies: their particles.
    Returns (count, the TOML key of the seeding parameter)."""
    geom = body.geometry
    if hasattr(geom, "seed"):  # a mesh body, already read: one point per particle
        return float(len(geom.x)), "file"
    lo, hi = geom.bbox()
    if body.count is not None:
        return float(np.prod(np.array(body.count, float))), "count"
    if body.spacing is not None:
        per_axis = np.maximum(np.floor((hi - lo) / np.array(body.spacing, float) + 1e-9), 1.0)
        return float(np.prod(per_axis)), "spacing"
    h = np.array(grid.cell_size, float)
    org = np.array(grid.origin, float)
    cells = np.ceil((hi - org) / h) - np.floor((lo - org) / h)
    return float(np.prod(np.maximum(cells, 0.0) * body.ppc)), "ppc"


def _overlapped(x, earlier):
    """The first earlier body whose (closed) region holds some of the particles `x`:
    (index, how many) or None. Two bodies whose particles share space put material there
    twice (in MPM both load the same grid nodes), which is almost always a mistake in the
    case: bodies may touch but not overlap. Mesh bodies are checked only as the later body
    (a mesh has no point-in-body test)."""
    xlo, xhi = x.min(axis=0), x.max(axis=0)
    for bj, (geom, glo, ghi) in enumerate(earlier):
        if geom is None or np.any(xhi < glo) or np.any(xlo > ghi):
            continue
        near = np.all((x >= glo) & (x <= ghi), axis=1)
        inside = int(np.count_nonzero(geom.contains(x[near])))
        if inside:
            return bj, inside
    return None


def material_arrays(case):
    """(mtypes, mparams): type code and parameter vector of each material, in case order."""
    mats = list(case.materials.values())
    mtypes = np.array([m.type_code for m in mats], dtype=np.int64)
    mparams = np.array([m.params(case.dim) for m in mats], dtype=np.float64)
    return mtypes, mparams


def build_particles(case, keep=None):
    """Seed every body; `keep(x) -> bool mask` selects this rank's particles (None: all).

    gids are global: they count every body's particles in body order on every rank, so they
    do not depend on the number of ranks.
    """
    dim = case.dim
    ps = ParticleSet(dim)
    ps.declare(J_FIELD if case.tracks_J_only else F_FIELD)
    if case.has_mpm:
        for spec in MPMStage.fields(case):
            ps.declare(spec)
    if case.has_sph:
        for spec in sph_stage_class(case).fields(case):
            ps.declare(spec)
        if case.sph.formulation == "total":
            ps.copy_to_halo("vol0")
    for spec in coupling_fields(case):
        ps.declare(spec)
    mats = list(case.materials.values())
    mat_names = list(case.materials)
    state_size = max(m.state_size for m in mats)
    if state_size:
        ps.declare(FieldSpec("mstate", (state_size,)))
    if case.loads:
        for spec in TractionLoads.FIELDS:
            ps.declare(spec)
    if case.prescribed:
        for spec in PrescribedVelocity.FIELDS:
            ps.declare(spec)
    gid0 = 0
    lo = np.array(case.domain[0]) if case.domain else None
    hi = np.array(case.domain[1]) if case.domain else None
    where = "grid" if case.grid else "domain"
    seeded = 0.0
    for bi, body in enumerate(case.bodies):
        key = f"bodies[{bi}]"
        points, param = lattice_points(body, case.grid)
        seeded += points
        if seeded > MAX_SEEDED:
            so_far = f" ({seeded:.3g} in the scene so far)" if seeded > points else ""
            raise ConfigError(f"{key}.{param}", f"body {body.name!r} would seed about "
                              f"{points:.3g} particles{so_far}, more than this solver seeds "
                              f"({MAX_SEEDED:.0e}): check the body's size against its {param}")
    earlier = []
    acting = case.loads + case.prescribed
    selected = [0] * len(acting)  # particles each load / prescribed velocity acts on
    for bi, body in enumerate(case.bodies):
        x, vol, spacing = seed_body(body, case.grid)
        key = f"bodies[{bi}]"
        if len(x) == 0:
            raise ConfigError(key, f"body {body.name!r} has no particles: its geometry holds no "
                              "lattice point (check size against ppc/spacing)")
        if lo is not None and (np.any(x < lo) or np.any(x > hi)):
            raise ConfigError(key, f"body {body.name!r} has particles outside the {where} "
                              f"[{lo.tolist()}, {hi.tolist()}]")
        hit = _overlapped(x, earlier)
        if hit is not None:
            bj, inside = hit
            raise ConfigError(key, f"body {body.name!r} overlaps body "
                              f"{case.bodies[bj].name!r} (bodies[{bj}]): {inside} of its "
                              f"{len(x)} particles lie inside it; bodies may touch but not "
                              "overlap (each would put its own material in the same space)")
        for j, spec in enumerate(acting):
            if spec.body == body.name:
                selected[j] += int(np.count_nonzero(_in_region(x, spec.region)))
        geom = body.geometry
        earlier.append((geom, *geom.bbox()) if hasattr(geom, "contains") else (None, None, None))
        mi = mat_names.index(body.material)
        mat = mats[mi]
        n = len(x)
        gid = gid0 + np.arange(n, dtype=np.int64)
        gid0 += n
        sel = np.ones(n, bool) if keep is None else keep(x)
        vals = {
            "gid": gid, "body": np.full(n, bi, np.int32), "mat": np.full(n, mi, np.int32),
            # evaluated over the whole body on every rank before `sel`: the same values
            # and the same verdict on non-finite ones whatever the rank count
            "x": x, "v": field_values(body.velocity, x, f"{key}.velocity"),
            "mass": mat.rho0 * vol, "vol0": vol, "vol": vol,
            "method": region_methods(case, x, np.full(
                n, METHOD_CODES["wall" if body.wall else body.method], np.int8)),
        }
        if "rho" in ps:
            vals["rho"] = mat.rho0 * np.ones(n)
        if "X0" in ps:
            vals["X0"] = x
        if body.stress:
            vals["sigma"] = voigt_tensors(field_values(body.stress, x, f"{key}.stress"), dim)
            vals["prestress"] = vals["sigma"]
        if "lp" in ps:
            vals["lp"] = np.tile(0.5 * spacing / np.array(case.grid.cell_size), (n, 1))
            # GIMP's 3-node stencil covers half-widths up to 1/2 cell; a CPDI domain grows
            # with the stretch up to `mpm.cpdi_reach` cells, so start it at no more than one
            bound = shape_named(case.mpm.shape).half_width
            if np.any(vals["lp"] > bound + 1e-12):
                raise ConfigError(f"{key}.spacing", f"{case.mpm.shape.upper()} needs particle "
                                  f"spacing <= {2 * bound:g} cell size(s)")
        if state_size:
            st = np.zeros((n, state_size))
            st[:, : mat.state_size] = mat.initial_state()
            vals["mstate"] = st
            if "mstate0" in ps:
                vals["mstate0"] = st
        if case.loads:
            vals["fext0"] = TractionLoads.seed(case.loads, bi, x, vol, spacing, body.name, dim)
        if case.prescribed:
            vals["vpres_id"] = PrescribedVelocity.seed(case.prescribed, x, body.name)
        ps.append({k: np.asarray(v)[sel] for k, v in vals.items()})
    for spec, count in zip(acting, selected):
        if not count:
            raise ConfigError(f"{spec.key}.box", f"holds no particle of body {spec.body!r}, "
                              "so this would act on nothing")
    derived = offered(case, ps)  # io/derived_fields.py: computed when a snapshot is written
    for i, name in enumerate(case.output.fields):
        if name not in ps and name not in derived:
            raise ConfigError(f"output.fields[{i}]", f"no particle field {name!r} in this "
                              f"scene; fields: {', '.join(sorted(set(ps.arrays) | set(derived)))}")
    return ps
