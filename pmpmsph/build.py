"""Build the particle state of a scene from its `Case` (seeding, materials, load fields)."""
import numpy as np

from .errors import ConfigError
from .particles import FieldSpec, ParticleSet
from .physics.loads import PrescribedVelocity, TractionLoads
from .physics.mpm import MPMStage
from .physics.sph import SPHStage
from .physics.tlsph import TLSPHStage


def sph_stage_class(case):
    """The SPH stage of a scene: updated-Lagrangian (seed 000) or total (seed 004)."""
    return TLSPHStage if case.sph.formulation == "total" else SPHStage
from .scene.seeding import seed_body

#: `method` field codes (kernels.sph uses the same numbers)
METHOD_CODES = {"mpm": 0, "sph": 1, "wall": 2}


def material_arrays(case):
    """(mtypes, mparams): type code and parameter vector of each material, in case order."""
    mats = list(case.materials.values())
    mtypes = np.array([m.type_code for m in mats], dtype=np.int64)
    mparams = np.array([m.params(case.dim) for m in mats], dtype=np.float64)
    return mtypes, mparams


def _voigt_to_tensor(stress, dim):
    s = np.zeros((3, 3))
    if dim == 1:
        s[0, 0] = stress[0]
    elif dim == 2:
        s[0, 0], s[1, 1], s[0, 1] = stress
        s[1, 0] = s[0, 1]
    else:
        s[0, 0], s[1, 1], s[2, 2], s[1, 2], s[0, 2], s[0, 1] = stress
        s[2, 1], s[2, 0], s[1, 0] = s[1, 2], s[0, 2], s[0, 1]
    return s


def build_particles(case, keep=None):
    """Seed every body; `keep(x) -> bool mask` selects this rank's particles (None: all).

    gids are global: they count every body's particles in body order on every rank, so they
    do not depend on the number of ranks.
    """
    dim = case.dim
    ps = ParticleSet(dim)
    if case.has_mpm:
        for spec in MPMStage.fields(case):
            ps.declare(spec)
    if case.has_sph:
        for spec in sph_stage_class(case).fields(case):
            ps.declare(spec)
        if case.sph.formulation == "total":
            ps.copy_to_halo("vol0")
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
    for bi, body in enumerate(case.bodies):
        x, vol, spacing = seed_body(body, case.grid)
        key = f"bodies[{bi}]"
        if len(x) == 0:
            raise ConfigError(key, f"body {body.name!r} has no particles: its geometry holds no "
                              "lattice point (check size against ppc/spacing)")
        if lo is not None and (np.any(x < lo) or np.any(x > hi)):
            raise ConfigError(key, f"body {body.name!r} has particles outside the {where} "
                              f"[{lo.tolist()}, {hi.tolist()}]")
        mi = mat_names.index(body.material)
        mat = mats[mi]
        n = len(x)
        gid = gid0 + np.arange(n, dtype=np.int64)
        gid0 += n
        sel = np.ones(n, bool) if keep is None else keep(x)
        vals = {
            "gid": gid, "body": np.full(n, bi, np.int32), "mat": np.full(n, mi, np.int32),
            "x": x, "v": np.tile(np.array(body.velocity, float), (n, 1)),
            "mass": mat.rho0 * vol, "vol0": vol, "vol": vol,
            "method": np.full(n, METHOD_CODES["wall" if body.wall else body.method], np.int8),
        }
        if "rho" in ps:
            vals["rho"] = np.full(n, mat.rho0)
        if "X0" in ps:
            vals["X0"] = x
        if body.wall:
            vals["v"] = np.zeros((n, dim))
        if body.stress:
            s = _voigt_to_tensor(body.stress, dim)
            vals["sigma"] = np.tile(s, (n, 1, 1))
            vals["prestress"] = vals["sigma"]
        if "lp" in ps:
            vals["lp"] = np.tile(0.5 * spacing / np.array(case.grid.cell_size), (n, 1))
            if np.any(vals["lp"] > 0.5 + 1e-12):
                raise ConfigError(f"{key}.spacing", "GIMP needs particle spacing <= cell size")
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
    return ps
