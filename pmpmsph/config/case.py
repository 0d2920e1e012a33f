"""The validated, frozen description of a scene (DESIGN.md section 1, `config/`).

`Case` is what the rest of the code consumes; `load.py` builds it from TOML text or from the
Python `Scene` API. Nothing here knows about MPI; the choice lists of the extension points
come from their registries.
"""
from dataclasses import dataclass, field
from typing import Optional

from ..kernels.mpm.grid_conditions.registry import grid_conditions
from ..kernels.mpm.shape_functions.registry import shape_functions
from ..kernels.sph.smoothing.registry import kernel_code, smoothing_kernels
from ..materials.base import Material
from ..physics.sph.integrators import SPH_INTEGRATORS as SPH_INTEGRATOR_CLASSES
from ..physics.mpm.transfer_schemes import TRANSFER_SCHEMES

#: `[mpm] shape` choices: the registered shape functions, in code order
SHAPES = tuple(s.name for s in shape_functions())
#: `[mpm] transfer` choices: the transfer schemes (physics/mpm/transfer_schemes.py)
TRANSFERS = tuple(TRANSFER_SCHEMES)
#: how G2P hands the grid velocity back to the particles (kernels/mpm/transfers.py, affine.py)
VELOCITY_UPDATES = ("flip", "apic", "mls")
CONTACTS = ("single", "multi")
METHODS = ("mpm", "sph")
#: `[[boundaries]] type` choices: the registered grid conditions, in code order
BC_KINDS = tuple(c.name for c in grid_conditions())
#: `[sph] kernel` choices: the registered smoothing kernels, in code order
SPH_KERNELS = tuple(k.name for k in smoothing_kernels())
#: `[sph] integrator` choices (physics/sph/integrators.py; "leapfrog" is Verlet)
SPH_INTEGRATORS = tuple(SPH_INTEGRATOR_CLASSES)
SPH_FORMULATIONS = ("updated", "total")


@dataclass(frozen=True)
class GridSpec:
    origin: tuple
    cell_size: tuple
    cells: tuple
    #: node layers stored outside the domain, and ghost node layers on each side of a slab:
    #: 2 and 3 cover every fixed stencil (kernels/mpm/shapes.py, parallel/decomposition.py);
    #: CPDI domains reaching R cells need R + 1 and R + 2 (set from `mpm.cpdi_reach`)
    pad: int = 2
    ghost: int = 3
    #: axes (0, 1, 2) along which the grid is periodic: node i and node i + cells are one
    #: node (MPM scenes; `Grid.fold_periodic`)
    periodic: tuple = ()

    @property
    def dim(self):
        return len(self.cells)

    @property
    def upper(self):
        return tuple(o + h * n for o, h, n in zip(self.origin, self.cell_size, self.cells))


@dataclass(frozen=True)
class MPMSpec:
    shape: str = "linear"
    transfer: str = "usl"
    flip: float = 1.0          # 1 = FLIP (thesis eq. 80), 0 = PIC
    velocity_update: str = "flip"  # the PIC/FLIP blend above, APIC (Jiang et al. 2015) or
    # MLS-MPM (Hu et al. 2018; USL with a B-spline shape)
    damping: float = 0.0       # alpha_d of thesis eq. 76
    mass_cutoff: float = 1e-10  # nodes lighter than this get no velocity (thesis listing 2)
    contact: str = "single"    # single velocity field, or one per body (Bardenhagen)
    friction: float = 0.0      # Coulomb coefficient of multi-field contact
    cpdi_reach: int = 2        # CPDI: the largest domain half-extent (cells) the grid covers
    hydrostatic: bool = False  # MPM fluid bodies start at rest in the hydrostatic state
    fbar: bool = False         # F-bar: the plastic materials' J averaged over the nodes
    deformation: str = "auto"  # what an MPM particle stores of its motion: "F" (the full
    # deformation gradient) or "J" (its determinant only; enough for fluids, whose stress
    # depends on J and the velocity gradient); "auto": J when every MPM material is a fluid


@dataclass(frozen=True)
class SPHSpec:
    """SPH options (seed 000 §2 for the updated-Lagrangian form, seed 004 for the total one)."""
    kernel: str = "cubic"
    h: float = 0.0                     # smoothing length (support 2h)
    spacing: float = 0.0               # initial particle spacing (artificial stress W(dp))
    formulation: str = "updated"       # updated (Gray-Monaghan) | total (seed 004)
    correction: bool = True            # kernel correction: total, Liu's full correction
                                       # (eqs. 1-3; default on); updated, the gradient
                                       # correction of Bonet & Lok (kernels/sph/rates.py
                                       # `correction_matrices`; default off, load.py)
    correction_kind: str = "liu"       # "liu" (kernels/sph/liu.py) | "bonet_lok" (updated)
    deformation: str = "reference"     # total: F by eq. 8 (reference) or eq. 9 (rate)
    force: str = "reference"           # total: eq. 5 in the reference configuration with
                                       # P = J sigma F^-T (stable in bending), or in the
                                       # current one as seed 004 writes it ("current")
    integrator: str = "predictor_corrector"
    av_alpha: float = 1.0              # artificial viscosity (seed 000, eq. 2.7)
    av_beta: float = 1.0
    laminar: str = "morris"            # fluids' physical viscosity mu: pairwise (Morris et
                                       # al. 1997) or from the stress sigma = 2 mu dev(d)
    artificial_stress: float = 0.0     # epsilon of Gray, Monaghan & Swift (0: off)
    artificial_stress_exponent: float = 4.0
    hourglass: float = 0.0             # solids: hourglass control factor kappa
                                       # (kernels/sph/hourglass.py; 0: off)
    hourglass_fit: str = "linear"      # its fit: "linear" or "quadratic"
                                       # (kernels/sph/hourglass_quadratic.py)
    damping: float = 0.0               # alpha_d: a -= alpha_d v (as thesis eq. 76)
    density_diffusion: float = 0.1     # fluids: delta of delta-SPH (Antuono 2010; 0: off)
    density_diffusion_model: str = "fourtakas"  # the hydrostatic splitting of Fourtakas
                                       # et al. (2019; no gradient pass), or the
                                       # renormalised gradient of Antuono et al. (2010)
    shifting: float = 0.0              # fluids: A of particle shifting D = A h |v| dt
                                       # (Lind et al. 2012; 0: off; kernels/sph/shifting.py)
    wall_no_slip: bool = True          # dummy walls: no-slip or free slip
    pressure_min: float = float("-inf")  # fluids: floor of the pressure (0: no tension)
    hydrostatic: bool = False          # fluids start at the hydrostatic density

    @property
    def kernel_code(self):
        return kernel_code(self.kernel)


@dataclass(frozen=True)
class BodySpec:
    name: str
    method: str
    material: str
    geometry: object
    ppc: Optional[int] = None
    spacing: Optional[tuple] = None
    count: Optional[tuple] = None
    velocity: tuple = ()
    stress: tuple = ()          # initial (pre-)stress, Voigt order for the dimension
    wall: bool = False          # SPH dummy wall particles (pressure extrapolated); their
                                # `velocity` is the wall's (a lid: no-slip drags the fluid)
    moving: bool = False        # a wall that also moves with its velocity (else it stays)
    friction: float | None = None  # a contact wall's Coulomb coefficient towards SPH
                                # solids (0: smooth; None: a plain dummy wall;
                                # kernels/sph/contact.py)


@dataclass(frozen=True)
class Region:
    """Either a domain face ("x-", "y+", ...) or an axis-aligned box."""
    face: Optional[str] = None
    lo: Optional[tuple] = None
    hi: Optional[tuple] = None


@dataclass(frozen=True)
class BoundarySpec:
    region: Region
    kind: str                   # fixed | slip | friction
    normal: tuple = ()          # outward normal for slip/friction on a box region
    friction: float = 0.0
    until: float = float("inf")  # gates: removed at this time
    key: str = ""
    velocity: tuple = ()        # fixed: the wall's velocity (a lid; () for a wall at rest)


@dataclass(frozen=True)
class LoadSpec:
    """Traction on the particles of `body` inside `region`, ramped linearly over `ramp`
    (a surface `stress` in the case file is turned into the traction sigma . n)."""
    body: str
    region: Region
    traction: tuple
    normal: str = "x+"          # the loaded face's outward normal, for the area per particle
    ramp: float = 0.0
    key: str = ""


@dataclass(frozen=True)
class PrescribedSpec:
    """Prescribed velocity components (None = free) of particles in `region` of `body`."""
    body: str
    region: Region
    velocity: tuple
    start: float = 0.0
    until: float = float("inf")
    key: str = ""
    #: a clamp face of the box ("x+", ...) across which the held particles of a
    #: total-Lagrangian SPH body mirror the free ones (physics/sph/mirror_clamp.py), or None
    mirror: Optional[str] = None


@dataclass(frozen=True)
class DampingSpec:
    """A wave absorber: the fluids' particle velocities inside `region` are damped at a rate
    growing from 0 on the box's face opposite `direction` to `rate` (1/s) on its face
    `direction` (physics/damping.py)."""
    region: Region
    direction: str = "x+"
    rate: float = 10.0
    key: str = ""


@dataclass(frozen=True)
class MethodRegion:
    """Particles of non-wall bodies inside `geometry` are seeded (and, with handover,
    relabelled) as `method` (seed 000 §4: MPM and SPH regions)."""
    method: str
    geometry: object
    key: str = ""


@dataclass(frozen=True)
class CouplingSpec:
    handover: bool = False      # relabel particles that cross a region boundary
    # "seed": seed 000 §4 as written (transition SPH stresses in P2G, MPM stresses in the
    # SPH sums); "conservative": each particle's stress acts through the discretisation
    # of its own strain rate (physics/coupling.py)
    interface: str = "seed"


@dataclass(frozen=True)
class TimeSpec:
    end: float
    dt: Optional[float] = None
    cfl: Optional[float] = None
    # the most steps a run of the case may take: a dt/end pair needing more (e.g. a dt typed
    # 1e-15 for 1e-5) is refused before step 1 unless this is raised or --max-steps bounds it
    max_steps: int = 100_000_000


#: default diagnostics schedule: every step up to this many particles, ...
DIAG_AUTO_PARTICLES = 100_000
#: ... and every this many steps above
DIAG_AUTO_EVERY = 100

#: added to the default output fields when a material is plastic (io/derived_fields.py)
PLASTIC_FIELDS = ("pressure", "mises", "plastic_strain", "yielding")


@dataclass(frozen=True)
class OutputSpec:
    every: Optional[float] = None       # snapshot interval in time
    every_steps: Optional[int] = None   # or in steps
    # steps between diagnostics rows; None: every step up to DIAG_AUTO_PARTICLES particles,
    # else every DIAG_AUTO_EVERY steps (a row costs a sixth to a fifth of a step at a
    # million particles; README "Output overhead")
    diagnostics_every: Optional[int] = None
    # what a viewer needs: ids, method/body, position, velocity, mass, density, stress
    # (vol = mass/rho and F are left out for size: add them by name)
    fields: tuple = ("gid", "method", "body", "x", "v", "mass", "rho", "sigma")  # + PLASTIC_FIELDS
    precision: str = "single"           # float fields of snapshots: "single" or "double"
    folder: str = "output"
    checkpoint_every: int = 0           # steps between checkpoints (0: only on signal/failure)
    probes_every: Optional[float] = None  # seconds between probes.csv rows (None: the
    # diagnostics schedule; config/probes.py)

    def diagnostics_interval(self, n_particles):
        """Steps between diagnostics rows for a run of n_particles (global)."""
        if self.diagnostics_every is not None:
            return self.diagnostics_every
        return 1 if n_particles <= DIAG_AUTO_PARTICLES else DIAG_AUTO_EVERY


@dataclass(frozen=True)
class ParallelSpec:
    axis: Optional[int] = None      # slab axis; None = the longest
    balance_every: int = 50         # steps between load-balance checks (0: never)
    balance_threshold: float = 0.1  # rebalance when max work / mean work - 1 exceeds this
    balance_by: str = "work"        # "work": particles + nodes; "time": measured compute time


@dataclass(frozen=True)
class Case:
    name: str
    dim: int
    grid: Optional[GridSpec]
    mpm: MPMSpec
    materials: dict[str, Material]
    bodies: tuple[BodySpec, ...]
    boundaries: tuple = ()
    loads: tuple = ()
    prescribed: tuple = ()
    damping: tuple = ()             # DampingSpec: wave absorbers on the fluids
    gravity: tuple[float, ...] = ()
    time: Optional[TimeSpec] = None
    output: OutputSpec = field(default_factory=OutputSpec)
    parallel: ParallelSpec = field(default_factory=ParallelSpec)
    sph: Optional[SPHSpec] = None
    domain: Optional[tuple] = None  # (min, max) box particles must stay in (grid box if any)
    periodic: tuple = ()            # axes (0, 1, 2) along which [domain] is periodic (SPH)
    regions: tuple = ()             # MethodRegion, applied in order over the body methods
    coupling: CouplingSpec = field(default_factory=CouplingSpec)
    probes: tuple = ()              # ProbeSpec (config/probes.py): RUN/probes.csv
    text: str = ""

    def _methods(self) -> set[str]:
        return {b.method for b in self.bodies} | {r.method for r in self.regions}

    @property
    def has_mpm(self) -> bool:
        return "mpm" in self._methods()

    @property
    def has_sph(self) -> bool:
        return "sph" in self._methods()

    @property
    def coupled(self) -> bool:
        return self.has_mpm and self.has_sph

    @property
    def tracks_J_only(self) -> bool:
        """True when particles carry J = det F instead of F (`mpm.deformation` "auto" or "J",
        which load.py refuses otherwise): a pure-MPM scene of fluids (Tait), any shape but
        CPDI, whose domains F shapes."""
        if self.mpm.deformation == "F" or self.has_sph or self.mpm.shape == "cpdi":
            return False
        return all(self.materials[b.material].fluid for b in self.bodies)

    def material_names(self) -> list[str]:
        return list(self.materials)

    def body_index(self, name: str) -> int:
        for i, b in enumerate(self.bodies):
            if b.name == name:
                return i
        raise KeyError(name)
