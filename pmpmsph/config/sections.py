"""Parsers of single sections of a case: one table (`[grid]`, a `[[bodies]]` entry, `[sph]`,
`[domain]`, ...) into its spec, with the checks that need only that table and the bodies.
`config.load` assembles them into a `Case` and checks what spans sections.

Every error is a `ConfigError` naming the dotted TOML key.
"""
import contextvars
import math

from ..errors import ConfigError
from ..kernels.sph.hourglass_quadratic import HOURGLASS_FITS
from ..physics.sph.integrators import SPH_INTEGRATORS as SPH_INTEGRATOR_CLASSES
from ..scene.geometry import Box, Disc, Polygon
from ..scene.mesh import MeshGeometry, mesh_geometry
from .case import (METHODS, SPH_FORMULATIONS, SPH_INTEGRATORS, SPH_KERNELS, BodySpec,
                   GridSpec, MethodRegion, SPHSpec)
from .conditions import _voigt_len
from .initial_fields import InitialField, read_field
from .table import is_finite

#: folder that relative paths in a case (mesh files) are taken from: the case file's folder
CASE_DIR = contextvars.ContextVar("pmpmsph_case_dir", default=None)


def _grid(t, dim):
    origin = t.vector("origin", dim, (0.0,) * dim)
    cells = t.vector("cells", dim, integer=True, positive=True, scalar_ok=True)
    if t.has("cell_size"):
        h = t.vector("cell_size", dim, positive=True, scalar_ok=True)
        if t.has("length"):
            raise ConfigError(t.key("length"), "give either cell_size or length, not both")
    else:
        length = t.vector("length", dim, positive=True, scalar_ok=True)
        h = tuple(length[a] / cells[a] for a in range(dim))
    if any(abs(h[a] - h[0]) > 1e-12 * h[0] for a in range(dim)):  # (physics/mpm/grid.py)
        sizes = ", ".join(f"{v:.6g}" for v in h)
        raise ConfigError(t.key("cells"), f"the cells are {sizes} wide along the axes: they "
                          "must be square (one cell size), so length / cells must agree")
    periodic = _axes_list(t, "periodic", dim)
    for a in periodic:  # the folded ends must not overlap (`Grid.fold_periodic`)
        if cells[a] < 8:
            raise ConfigError(t.key("periodic"), f"a periodic axis needs at least 8 cells; "
                              f"{'xyz'[a]} has {cells[a]}")
    if math.prod(cells) > 2e8:
        raise ConfigError(t.key("cells"), f"{math.prod(cells)} cells is more than this solver "
                          "allocates (2e8)")
    t.finish()
    return GridSpec(origin, h, cells, periodic=periodic)


def _geometry(t, dim):
    shape = t.string("shape", choices=("box", "disc", "circle", "sphere", "polygon", "mesh"))
    if shape == "mesh":  # elements of a mesh file read with meshio (scene/mesh.py)
        return mesh_geometry(t, dim, CASE_DIR.get())
    if shape == "box":
        lo = t.vector("min", dim)
        hi = t.vector("max", dim)
        for a in range(dim):
            if hi[a] <= lo[a]:
                raise ConfigError(t.key("max") + f"[{a}]", "max must exceed min")
        return Box(lo, hi)
    if shape in ("disc", "circle", "sphere"):
        return Disc(t.vector("centre", dim), t.number("radius", min_open=0.0))
    if dim != 2:
        raise ConfigError(t.key("shape"), "polygons are 2D only")
    verts = t.raw("vertices")
    if not isinstance(verts, list) or len(verts) < 3:
        raise ConfigError(t.key("vertices"), "expected a list of at least 3 [x, y] points")
    pts = []
    for i, v in enumerate(verts):
        if (not isinstance(v, list) or len(v) != 2
                or not all(isinstance(c, (int, float)) and not isinstance(c, bool)
                           and is_finite(c) for c in v)):
            raise ConfigError(f"{t.key('vertices')}[{i}]", "expected [x, y] with finite numbers")
        pts.append(tuple(float(c) for c in v))
    poly = Polygon(tuple(pts))
    if poly.measure() <= 0:
        raise ConfigError(t.key("vertices"), "polygon has zero area")
    return poly


def _body(t, dim, materials, grid):
    name = t.string("name", t.path.replace("bodies", "body"))
    method = t.string("method", "mpm", choices=METHODS)
    mat = t.string("material")
    if mat not in materials:
        raise ConfigError(t.key("material"), f"unknown material {mat!r}; defined: "
                          f"{', '.join(materials) or 'none'}")
    geom = _geometry(t, dim)
    given = [k for k in ("ppc", "spacing", "count") if t.has(k)]
    if isinstance(geom, MeshGeometry):  # seeded per element (`ppe`, read with the mesh)
        given = MeshGeometry.check_body(t, method, given)
    if len(given) != 1:
        raise ConfigError(t.key("ppc"), "give exactly one of ppc, spacing or count")
    ppc = spacing = count = None
    if given[0] == "ppc":
        ppc = t.number("ppc", integer=True, min=1, max=16)
        if grid is None:
            raise ConfigError(t.key("ppc"), "ppc needs a [grid]")
    elif given[0] == "spacing":
        spacing = t.vector("spacing", dim, positive=True, scalar_ok=True)
    elif given[0] == "count":
        if not isinstance(geom, Box):
            raise ConfigError(t.key("count"), "count is for box bodies; use ppc or spacing")
        count = t.vector("count", dim, integer=True, positive=True, scalar_ok=True)
    # numbers, or expressions of the position (config/initial_fields.py)
    velocity = read_field(t, "velocity", dim, dim, (0.0,) * dim)
    stress = read_field(t, "stress", _voigt_len(dim), dim, ())
    wall = t.boolean("wall", False)
    if wall and method != "sph":
        raise ConfigError(t.key("wall"), "wall particles are SPH dummy particles: set "
                          "method = \"sph\" (MPM walls are grid boundaries)")
    moving = t.boolean("moving", False)
    if moving and not wall:
        raise ConfigError(t.key("moving"), "moving is for wall bodies (wall = true), whose "
                          "particles otherwise stay in place; other bodies move by their "
                          "own dynamics")
    if moving and isinstance(velocity, InitialField):  # (stage.py moves x by v each step)
        raise ConfigError(t.key("velocity"), "a moving wall moves rigidly: give its velocity "
                          "as numbers, not expressions")
    # a contact wall's Coulomb coefficient towards SPH solids (kernels/sph/contact.py)
    friction = t.number("friction", None, min=0.0)
    if friction is not None and not wall:
        raise ConfigError(t.key("friction"), "friction is a dummy wall's (wall = true) "
                          "Coulomb coefficient towards SPH solids; an MPM floor's friction "
                          "is a [[boundaries]] entry of type \"friction\"")
    if method == "sph" and ppc is not None and grid is None:
        raise ConfigError(t.key("ppc"), "SPH bodies without a [grid] are seeded by spacing "
                          "or count, not ppc")
    t.finish()
    return BodySpec(name, method, mat, geom, ppc, spacing, count, velocity, stress, wall,
                    moving, friction)


def _body_spacing(body, grid=None):
    """Smallest lattice spacing of a body (spacing, count, or ppc with a grid)."""
    if body.spacing is not None:
        return min(body.spacing)
    if body.ppc is not None:
        return min(grid.cell_size) / body.ppc
    g = body.geometry
    return min((hi - lo) / c for lo, hi, c in zip(g.lo, g.hi, body.count))


def _correction(t, formulation):
    """[sph] correction: false, true (the formulation's own: Liu's corrected kernel in the
    total one, Bonet & Lok's gradient correction in the updated one), or the kind by name,
    "liu" or "bonet_lok" (updated only). Liu's reads a bending strain rate across a few
    particle rows exactly where Bonet & Lok's reads a third of it at 2 rows (docs/plate.md).
    Returns (on, kind)."""
    raw = t.raw("correction", formulation == "total")
    default = "liu" if formulation == "total" else "bonet_lok"
    if isinstance(raw, bool):
        return raw, default
    if raw == "liu" or (raw == "bonet_lok" and formulation == "updated"):
        return True, raw
    kinds = '"liu"' if formulation == "total" else '"liu" or "bonet_lok"'
    raise ConfigError(t.key("correction"), f"expected true, false or {kinds} (the "
                      f"{formulation} formulation)")


def _hourglass_fit(t, kappa):
    """[sph] hourglass_fit: the field the hourglass control (factor `kappa`) fits
    (kernels/sph/hourglass_quadratic.py); refused without the control, where it would do
    nothing."""
    fit = t.string("hourglass_fit", "linear", choices=tuple(HOURGLASS_FITS))
    if fit != "linear" and kappa == 0.0:
        raise ConfigError(t.key("hourglass_fit"), "the fit is the hourglass control's, and "
                          "sph.hourglass is 0 (off)")
    return fit


def _hourglass(t, formulation, integrator):
    """[sph] hourglass: the factor kappa of the hourglass control; in the updated formulation
    with the Verlet integrator, whose drifts carry the control's displacements (the total
    one forms them as x - X0 with any integrator)."""
    kappa = t.number("hourglass", 0.0, min=0.0)
    if kappa > 0.0 and formulation == "updated" and integrator != "verlet":
        raise ConfigError(t.key("hourglass"), f"the hourglass control needs sph.integrator = "
                          f"'verlet' (got '{integrator}')")
    return kappa


def _sph(t, dim, bodies, materials, grid=None, coupled=False):
    """The [sph] section; h defaults to h_factor x the particle spacing (seed 004 §2), also
    in a coupled scene. Seed 000 §4 sets h to the cell width; with its two particles per
    cell that is h = 2 spacings, where the cubic spline leaves the odd-even particle mode
    without stiffness and a loaded bar settles into a sawtooth (tests/verification/
    test_coupled.py: mean strain 1.20 x the exact one, against exact with 1.3 spacings).
    Give `h` = the cell size to follow the seed literally."""
    solids = [b for b in bodies if (b.method == "sph" or coupled) and not b.wall]
    spacing = min((_body_spacing(b, grid) for b in solids), default=0.0)
    if spacing == 0.0:
        raise ConfigError("bodies", "SPH scenes need at least one SPH body that is not a wall")
    kernel = t.string("kernel", "cubic", choices=SPH_KERNELS)
    if t.has("h") and t.has("h_factor"):
        raise ConfigError(t.key("h_factor"), "give either sph.h or sph.h_factor, not both")
    h = t.number("h", None, min_open=0.0)
    formulation = t.string("formulation", "updated", choices=SPH_FORMULATIONS)
    if h is None:
        # total-Lagrangian SPH: 1.4 spacings, the top of seed 004's range, delays the
        # free-edge mode of its force/F combination (kernels/sph/tlsph.py)
        default = 1.4 if formulation == "total" else 1.3
        h = t.number("h_factor", default, min_open=0.5, max=4.0) * spacing
    elif not 0.5 * spacing < h <= 4.0 * spacing:  # as h_factor: no neighbour / too many
        raise ConfigError(t.key("h"), f"{h:g} is not in (0.5, 4] x the particle spacing "
                          f"{spacing:g} (below, the kernel support 2h holds no neighbour; "
                          "above, every particle has hundreds)")
    integrator = t.string("integrator", "predictor_corrector", choices=SPH_INTEGRATORS)
    integrator = SPH_INTEGRATOR_CLASSES[integrator].name  # (an alias: its canonical name)
    visc = t.sub("viscosity", {})
    av_alpha = visc.number("alpha", 1.0, min=0.0)
    av_beta = visc.number("beta", 1.0, min=0.0)
    # the fluids' physical viscosity (their material's mu): pairwise velocity differences
    # (Morris, Fox & Zhu 1997), or the divergence of sigma = 2 mu dev(d) (kernels/sph/rates.py)
    laminar = visc.string("laminar", "morris", choices=("morris", "stress"))
    visc.finish()
    walls = t.string("walls", "no_slip", choices=("no_slip", "slip"))
    for i, b in enumerate(bodies):
        if b.wall and not materials[b.material].fluid:
            raise ConfigError(f"bodies[{i}].material", "wall particles take a fluid "
                              "material (their density follows the extrapolated pressure)")
        if b.friction is not None and formulation == "total":
            raise ConfigError(f"bodies[{i}].friction", "contact walls act on updated-"
                              "Lagrangian SPH solids; the total formulation's solids do not "
                              "meet walls: set [sph] formulation = \"updated\" or remove "
                              "friction")
    correction, correction_kind = _correction(t, formulation)
    kappa = _hourglass(t, formulation, integrator)
    spec = SPHSpec(
        kernel=kernel, h=h, spacing=spacing,
        formulation=formulation,
        # kernel correction: Liu's full correction in the total formulation (seed 004 eqs.
        # 1-3, on by default), the gradient correction of Bonet & Lok in the updated one
        # (kernels/sph/rates.py `correction_matrices`, off by default)
        correction=correction, correction_kind=correction_kind,
        deformation=t.string("deformation", "reference", choices=("reference", "rate")),
        # total: eq. 5 in the reference configuration (P = J sigma F^-T, the exact adjoint
        # of F by eq. 8: energy-consistent, stable in bending) by default; "current" is the
        # seed's form, kept to reproduce seed 004's figures (kernels/sph/tlsph.py)
        force=t.string("force", "reference", choices=("current", "reference")),
        integrator=integrator, av_alpha=av_alpha, av_beta=av_beta, laminar=laminar,
        artificial_stress=t.number("artificial_stress", 0.0, min=0.0, max=1.0),
        artificial_stress_exponent=t.number("artificial_stress_exponent", 4.0, min_open=0.0),
        # the odd-even mode of the corrected solid (kernels/sph/hourglass.py), off by default
        hourglass=kappa,
        # the field it fits: linear, or quadratic, which leaves bending alone
        hourglass_fit=_hourglass_fit(t, kappa),
        damping=t.number("damping", 0.0, min=0.0),
        # delta of the delta-SPH density diffusion of fluids (kernels/sph/density.py);
        # 0.1 is Antuono et al.'s (2010) value, 0 switches it off
        density_diffusion=t.number("density_diffusion", 0.1, min=0.0, max=1.0),
        # Fourtakas et al. (2019), DualSPHysics' default: as quiet at rest as Antuono's
        # (tests/verification/test_sph_density_diffusion.py) without the gradient pass
        density_diffusion_model=t.string("density_diffusion_model", "fourtakas",
                                         choices=("fourtakas", "antuono")),
        # A of particle shifting (kernels/sph/shifting.py), off by default; Skillen et al.
        # (2013) use 2: beyond 10 a particle would move about its spacing a step
        shifting=t.number("shifting", 0.0, min=0.0, max=10.0),
        wall_no_slip=walls == "no_slip",
        pressure_min=t.number("pressure_min", float("-inf")),
        hydrostatic=t.boolean("hydrostatic", False))
    t.finish()
    return spec


def _check_mpm_hydrostatic(bodies, materials, gravity):
    """`[mpm] hydrostatic` needs gravity and an MPM body of a Tait fluid to act on."""
    if not any(gravity):
        raise ConfigError("mpm.hydrostatic", "a hydrostatic start needs gravity (the case "
                          "has none)")
    if not any(b.method == "mpm" and not b.wall
               and materials[b.material].fluid
               for b in bodies):
        raise ConfigError("mpm.hydrostatic", "no MPM body of a tait fluid to start "
                          "hydrostatic (it sets the MPM fluids' initial density and pressure)")


def _method_region(t, dim):
    method = t.string("method", choices=METHODS)
    geom = _geometry(t, dim)
    t.finish()
    return MethodRegion(method, geom, t.path)


def _domain(t, dim):
    """(min, max) and the periodic axes of the [domain] box of an SPH scene."""
    lo = t.vector("min", dim)
    hi = t.vector("max", dim)
    for a in range(dim):
        if hi[a] <= lo[a]:
            raise ConfigError(t.key("max") + f"[{a}]", "max must exceed min")
    periodic = _axes_list(t, "periodic", dim)
    t.finish()
    return (lo, hi), periodic


def _axes_list(t, key, dim):
    """A list of distinct axis names ("x", "y", "z") as sorted axis indices."""
    names = t.raw(key, [])
    axes = "xyz"[:dim]
    if (not isinstance(names, list) or not all(isinstance(n, str) and n in axes for n in names)
            or len(set(names)) != len(names)):
        raise ConfigError(t.key(key), f"expected a list of distinct axes among "
                          f"{', '.join(axes)}, got {names!r}")
    return tuple(sorted(axes.index(n) for n in names))


def _check_periodic(periodic, domain, bodies, key="domain.periodic"):
    """The periodic axes of the particles of an SPH or coupled scene: no wall closes one at
    an end, and every body that spans the period fills it with a whole number of spacings (a
    lattice that does not tile the period leaves a seam of wrong density)."""
    lo, hi = domain
    for axis in periodic:
        length = hi[axis] - lo[axis]
        for i, b in enumerate(bodies):
            blo, bhi = b.geometry.bbox()
            # a wall that closes the axis at either end (one that runs the whole period, as
            # the plates of a channel do, or an obstacle inside it are fine)
            near = 1e-9 * length + (max(b.spacing) if b.spacing is not None else 0.0)
            spans = bhi[axis] - blo[axis] >= length - 1e-9 * length
            if b.wall and not spans and (blo[axis] <= lo[axis] + near
                                         or bhi[axis] >= hi[axis] - near):
                raise ConfigError(key, f"bodies[{i}] ({b.name!r}) is a wall at an end of the "
                                  f"periodic axis {'xyz'[axis]}: a periodic axis has no ends; "
                                  "remove the wall or the axis from periodic")
            if b.spacing is None or bhi[axis] - blo[axis] < length - 1e-9 * length:
                continue
            cells = length / b.spacing[axis]
            if abs(cells - round(cells)) > 1e-6:
                raise ConfigError(key, f"the period {length:g} along {'xyz'[axis]} is "
                                  f"{cells:.4g} spacings of bodies[{i}] ({b.spacing[axis]:g}): "
                                  "make it a whole number")
