"""SPHStage: updated-Lagrangian SPH for solids and weakly compressible fluids
(DESIGN.md §3, steps 1, 3, 4 and 5).

One *evaluation* of the rates at the current state is:
    halo exchange (owned particles near slab faces copied to the neighbours)
    -> cell-list neighbours of owned particles over owned + halo rows
    -> dummy wall particles take the fluid's extrapolated pressure (then a halo refresh)
    -> sound speeds, artificial stress -> rates (acc, drho/dt, L) of owned SPH particles.
The integrators combine evaluations:
    verlet               kick v(dt/2) -> drift x(dt/2) -> drho, L there -> F, rho by the
                         implicit midpoint rule -> drift x(dt/2) -> stress -> evaluate -> kick
                         (time-reversible: reversing all velocities retraces the run)
    predictor_corrector  y* = y + dt/2 f(prev) -> stress -> evaluate f* -> y = y + dt f*
                         (Monaghan's midpoint predictor-corrector, one evaluation per step)
    rk3                  TVD Runge-Kutta of Shu & Osher (seed 004, §5), three evaluations
and the halo is refreshed at every evaluation.

With `[sph] correction = true` every evaluation (and the mid-step kinematics of verlet)
first computes the kernel gradient correction B of the owned rows (`correction_matrices`,
Bonet & Lok; seed 004 §2.1 for the first-order completeness it restores) and, for the
force, refreshes it in the halo: the rates then use corrected gradients (see `sph_rates`).
"""
import numpy as np

from ...kernels.neighbours import moved_beyond, neighbour_lists
from ...kernels.sph.rates import sph_rates
from ...kernels.sph.views import (pair_lists, pair_rows, rate_options,
                                  rate_terms, rates, shift_fields, smoothing_of, sph_state)
from ...kernels.sph.stress import pair_stress, sound_speeds, sph_stress, sync_ghost_velocity
from ...kernels.sph.artificial_stress import artificial_stress
from ...kernels.sph.density import density_gradient
from ...kernels.sph.shifting import shift_positions, shifting_state
from ...kernels.sph.integrate import (
    add_scaled,
    advance,
    cayley_update,
    first_outside,
    max_signal,
)
from ...kernels.sph.kernel_functions import SUPPORT, kernel_w
from ...materials.dispatch import material_tag
from ...parallel.decomposition import wrap_axis
from ...parallel.particle_halo import ParticleHalo
from ...particles import FieldSpec
from ..hydrostatic import fluid_columns
from ..scratch import rows_at_least
from .hourglass_control import HourglassControl
from .integrators import SPH_INTEGRATORS
from .kernel_correction import KernelCorrection
from .mirror_clamp import MirrorClamps
from .wall_terms import WallTerms
from ...timing import Timers

#: extra halo width beyond the kernel support and the skin, in units of h: owned particles
#: may stray this far past their slab face before they migrate (`MigrationSchedule`)
HALO_MARGIN = 0.5
#: Verlet skin of the neighbour lists, in units of h: lists (and the halo's membership) are
#: kept until some particle has moved half the skin since they were built
SKIN = 0.25


def shifting_fluids(case):
    """Whether the scene's SPH fluids are shifted (`[sph] shifting` > 0, kernels/
    sph/shifting.py): an updated-Lagrangian scene with a Tait fluid body."""
    return case.sph.shifting > 0.0 and diffusing_fluids(case, ignore_delta=True)


def diffusing_fluids(case, ignore_delta=False):
    """Whether the scene's SPH fluids take the delta-SPH density diffusion: an updated-
    Lagrangian scene with a Tait fluid body (not only walls) and a non-zero delta."""
    return (case.sph.formulation == "updated"
            and (ignore_delta or case.sph.density_diffusion > 0.0)
            and any(not b.wall and case.materials[b.material].fluid
                    for b in case.bodies))


class SPHStage:
    def __init__(self, case, particles, materials, decomposition, dist, timers=None):
        self.case = case
        self.p = particles
        self.dim = case.dim
        spec = case.sph
        self.spec = spec
        self.kern = spec.kernel_code
        self.h = spec.h
        self.radius = SUPPORT * self.h
        self.skin = SKIN * self.h
        #: how far an owned particle may stray past its slab face before it must migrate
        #: (`MigrationSchedule`): the halo's width holds this margin beyond the lists'
        #: radius, so a stray's neighbours across the face are still in the halo
        self.stray_reach = HALO_MARGIN * self.h
        self.dim_tag = (0,) * self.dim
        self.kern_tag = (0,) * (self.kern + 1)
        # inviscid fluids alone need no velocity gradient (F follows from the density)
        mats = list(case.materials.values())  # (in the order of `materials`' rows)
        # a fluid's viscosity acts pairwise (Morris et al. 1997, kernels/sph/rates.py) or through
        # its stress: mu per material where it is pairwise, else 0; None if no fluid is
        pairwise = [m.fluid and spec.laminar == "morris" for m in mats]
        self.morris_mu = (np.array([m.viscosity if pw else 0.0 for m, pw in zip(mats, pairwise)])
                          if any(pw and m.viscosity > 0.0 for m, pw in zip(mats, pairwise))
                          else None)
        self.want_L = not all(m.fluid and (m.viscosity == 0.0 or pw)
                              for m, pw in zip(mats, pairwise))
        self.integrator = SPH_INTEGRATORS[spec.integrator]  # (sph_integrators.py)
        self.mtypes, self.mparams = materials
        # the set of material models this stage's kernels meet, a compile-time tag: their
        # stress and wave-speed switches cover those only (materials/dispatch.py); from the
        # case's bodies (not this rank's rows, which migrate), every body's since SPH rows
        # pair with MPM points and region coupling turns one method into the other
        used = sorted({list(case.materials).index(b.material) for b in case.bodies})
        self.tagged_materials = (self.mtypes, self.mparams, material_tag(self.mtypes[used]))
        self.gravity = np.zeros(3)
        self.gravity[: self.dim] = case.gravity
        self.timers = timers if timers is not None else Timers()
        self.dist = dist
        self.halo_enabled = True
        self.halo = None
        # prescribed velocities (physics/loads.py PrescribedVelocity), held within a step
        self.constraint = None
        # mirror clamps (physics/sph/mirror_clamp.py); `_mirror` is the evaluation's (None
        # in the kernels' warm-up on zero rows, one rank at a time: the clamps are collective)
        self.mirror = (MirrorClamps(case, particles, dist, case.sph.h)
                       if any(s.mirror for s in case.prescribed) else None)
        self._mirror = None
        self.set_decomposition(decomposition)
        self.use_as = spec.artificial_stress > 0.0
        self.w_dp = kernel_w(self.kern, self.dim, spec.spacing, self.h) if self.use_as else 1.0
        # per material: a fluid (Tait) meets a solid of another material through the mirror
        # pair of kernels/sph/rates.py's sph_rates
        self.fluid = np.array([m.fluid for m in mats], np.bool_)
        updated = spec.formulation == "updated"
        # kernel gradient correction (physics/sph/kernel_correction.py; opt in, default
        # off; the total formulation corrects its own kernel: TLSPHStage)
        self.correction = (KernelCorrection(case, self.fluid)
                           if spec.correction and updated else None)
        # hourglass control of the solids (physics/sph/hourglass_control.py; needs X0)
        self.hourglass = (HourglassControl(case, self.fluid)
                          if spec.hourglass > 0.0 and updated else None)
        self._M = np.zeros((0, 3, 3))  # moment matrices (scratch: delta-SPH, shifting)
        # delta-SPH: delta h c0 per material (c0 = sqrt(kappa gamma / rho0) of a Tait
        # fluid), 0 for the others; None when no fluid diffuses
        self.dcoef = None
        if diffusing_fluids(case):
            self.dcoef = np.array([spec.density_diffusion * self.h * m.sound_speed(self.dim)
                                   if m.fluid else 0.0 for m in mats])
        # Fourtakas et al. (2019): the hydrostatic part of a pair's density difference is
        # taken out instead of the renormalised gradients (`kernels.sph.density`)
        self.split = self.dcoef is not None and spec.density_diffusion_model == "fourtakas"
        # particle shifting: A h of D = A h |v| dt (0: off)
        self.shift_coef = spec.shifting * self.h if shifting_fluids(case) else 0.0
        # walls, and solids a fluid meets (physics/sph/wall_terms.py)
        self.walls = WallTerms(case, (self.mtypes, self.mparams), self.fluid, self.gravity)
        self.lo = np.array(case.domain[0], float)
        self.hi = np.array(case.domain[1], float)
        self.start = np.zeros(1, np.int64)
        self.index = np.zeros(0, np.int64)
        self.x_build = None     # owned positions when the lists were built (None: rebuild)
        self.n_total_build = 0
        self.evaluated = False
        self.evaluations = 0
        self.rebuilds = 0

    @staticmethod
    def fields(case):
        """Fields the SPH stage needs beyond the core ones (DESIGN.md §2)."""
        multi = SPH_INTEGRATORS[case.sph.integrator].multi_stage
        out = [
            FieldSpec("rho", (), halo=True, output=True),
            FieldSpec("acc", ("dim",)),
            FieldSpec("drho", ()),
            FieldSpec("L", (3, 3)),
            FieldSpec("cs", ()),  # migrates: the CFL signal of a row that just moved rank
            FieldSpec("S", (6,), migrate=False),
        ]
        out += WallTerms.fields(case)
        if case.sph.artificial_stress > 0:
            out.append(FieldSpec("R", (6,), migrate=False))
        if case.sph.correction:
            out += KernelCorrection.fields(case)
        if diffusing_fluids(case) and case.sph.density_diffusion_model == "antuono":
            # delta-SPH: renormalised density gradients
            out.append(FieldSpec("gradrho", (3,), migrate=False))
        if shifting_fluids(case):  # particle shifting: grad C and the surface eigenvalue
            out += [FieldSpec("gradc", (3,), migrate=False), FieldSpec("lam", (), migrate=False),
                    FieldSpec("gradv", (3, 3), migrate=False)]
        if case.sph.hourglass > 0.0 or any(s.mirror for s in case.prescribed):
            # reference positions (set at seeding, initial_particles.py): the hourglass
            # control's and the mirror clamps' (physics/sph/mirror_clamp.py)
            out.append(FieldSpec("X0", ("dim",), halo=True, output=True))
        if case.sph.hourglass > 0.0:
            out += HourglassControl.fields(case, displacement=True)
        if multi:
            out += [FieldSpec("x_n", ("dim",), migrate=False),
                    FieldSpec("v_n", ("dim",), migrate=False),
                    FieldSpec("rho_n", (), migrate=False),
                    FieldSpec("F_n", (3, 3), migrate=False, fill="identity")]
        return out

    def set_decomposition(self, decomposition):
        self.dec = decomposition
        lo, hi = self.case.domain
        periodic = [(a, lo[a], hi[a] - lo[a]) for a in self.case.periodic]
        self.halo = ParticleHalo(decomposition, self.p,
                                 (SUPPORT + SKIN + HALO_MARGIN) * self.h, periodic=periodic)
        self.invalidate()

    def invalidate(self):
        """Owned rows changed (migration, balancing, sorting): rebuild lists and halo."""
        self.x_build = None

    # -- one evaluation ------------------------------------------------------------------------
    def _mstate(self, n):
        p = self.p
        return p["mstate"][:n] if "mstate" in p else np.zeros((n, 0))

    def kinematics(self):
        """drho and L only, at the current positions and velocities (the Verlet step needs
        them at mid-step)."""
        p, t = self.p, self.timers
        n = p.n_owned
        if "vg" in p:
            sync_ghost_velocity(n, p["method"], p["v"], p["vg"])
        self._place_ghosts()
        # rows may have moved since the last evaluation (migration): rebuild the lists and
        # the halo if so (collectively), else refresh the halo in place
        self._update_neighbours()
        self._correction(halo=False)
        self._density_gradient()
        with t.phase("sph"):
            if self.split:  # Fourtakas' splitting reads the current sound speeds
                sound_speeds(self.dim, p.n_total, p.with_halo("method"), p.with_halo("mat"),
                             p.with_halo("rho"), p.with_halo("F"), self.tagged_materials,
                             p.with_halo("cs"))
            # drho and L only, without the artificial stress
            sph_rates(self._smoothing(), self._pairs(n), self._pair_rows(),
                      self._options(want_force=False, want_L=True, want_fsi=False),
                      self._terms(R=None, pw=None, clamped=None),
                      rates(p.with_halo("acc"), p.with_halo("drho"), p.with_halo("L")))
        self._restore_ghosts()

    def _density_gradient(self):
        """delta-SPH: the renormalised density gradient of the owned fluid rows, refreshed in
        the halo (the diffusion needs it at both ends of a pair). No-op without it."""
        if self.dcoef is None or self.split:
            return
        p = self.p
        n = p.n_owned
        self._M = rows_at_least(self._M, n)
        with self.timers.phase("sph"):
            density_gradient(self._smoothing(), self._pairs(n), p.with_halo("x"),
                             p.with_halo("mass"), p.with_halo("rho"), p.with_halo("method"),
                             p.with_halo("mat"), self.dcoef, self._M, p.with_halo("gradrho"))
        if self.halo_enabled:
            with self.timers.phase("halo"):
                self.halo.refresh(("gradrho",))

    def _shifting_state(self):
        """Particle shifting: grad C and the surface eigenvalue of the owned fluid rows at
        this evaluation's state (applied at the end of the step, `step`). No-op without."""
        if self.shift_coef == 0.0:
            return
        p = self.p
        n = p.n_owned
        self._M = rows_at_least(self._M, n)
        with self.timers.phase("sph"):
            vg = p.with_halo("vg") if "vg" in p else p.with_halo("v")
            shifting_state(self._smoothing(), self._pairs(n), p.with_halo("x"), vg,
                           p.with_halo("mass"), p.with_halo("rho"), p.with_halo("method"),
                           p.with_halo("mat"), self.fluid, self._M, self._shifting())

    def _shifting(self):
        """Particle shifting's fields of the owned rows (`shift_fields`)."""
        p = self.p
        return shift_fields(p["gradc"], p["lam"], p["gradv"])

    def _gradrho_owned(self):
        """delta-SPH's density gradients of the owned rows (none without delta-SPH)."""
        return self.p["gradrho"] if "gradrho" in self.p else np.zeros((0, 3))

    def _diffusion(self):
        """The sph_rates arguments of delta-SPH (None, None: off)."""
        if self.dcoef is None:
            return None, None
        if self.split:
            return self.dcoef, None
        return self.dcoef, self.p.with_halo("gradrho")

    def _smoothing(self):
        return smoothing_of(self.dim_tag, self.kern_tag, self.h)

    def _pairs(self, n):
        """The owned rows' half neighbour lists (kernels/sph/views.py `pair_lists`)."""
        return pair_lists(n, self.start, self.index)

    def _pair_rows(self):
        """The rows `sph_rates` reads (kernels/sph/views.py `pair_rows`), owned and halo."""
        p = self.p
        vg = p.with_halo("vg") if "vg" in p else p.with_halo("v")
        return pair_rows(p.with_halo("x"), p.with_halo("v"), vg, p.with_halo("mass"),
                        p.with_halo("rho"), p.with_halo("S"), p.with_halo("cs"),
                        p.with_halo("method"), p.with_halo("mat"))

    def _options(self, want_force, want_L, want_fsi):
        spec = self.spec
        corr_tag = () if self.correction is None else KernelCorrection.TAG
        return rate_options(corr_tag, self.fluid, self.gravity, spec.damping,
                            spec.av_alpha, spec.av_beta, want_force, want_L, want_fsi,
                            self.split)

    def _terms(self, R, pw, clamped):
        """The optional terms of `sph_rates` this scene has (`rate_terms`)."""
        dcoef, gradrho = self._diffusion()
        pws, contact = self.walls.rate_terms(self.p)
        B, liu = (None, None) if self.correction is None else self.correction.terms(self.p)
        return rate_terms(R=R, as_n=self.spec.artificial_stress_exponent,
                          w_dp=self.w_dp, B=B, liu=liu, dcoef=dcoef,
                          gradrho=gradrho, morris_mu=self.morris_mu, pw=pw, clamped=clamped,
                          pws=pws, contact=contact)

    def _correction(self, halo):
        """The kernel gradient correction of the owned rows, with `halo` refreshed in the
        halo (physics/sph/kernel_correction.py). No-op without the option."""
        if self.correction is not None:
            self.correction.compute(self.p, self._smoothing(), self._pairs(self.p.n_owned),
                                    self.start, self.index,
                                    self.halo if halo and self.halo_enabled else None,
                                    self.timers)

    def set_constraint(self, prescribed):
        """Hold the prescribed velocities (physics/loads.py PrescribedVelocity) within each
        step too: every evaluation zeroes their components of the acceleration. The mirror
        clamps are matched to their partners here (collective: a clamp face off the particle
        layers is bad input, reported before step 1)."""
        self.constraint = prescribed
        if self.mirror is not None:
            self.mirror.setup()

    def _place_ghosts(self):
        """The clamps' ghosts at the image of the free body (before the halo refresh)."""
        self._mirror = self.mirror if self.halo_enabled else None
        if self._mirror is not None:
            self._mirror.place()

    def _restore_ghosts(self):
        if self._mirror is not None:
            self._mirror.restore()

    def _hourglass_fit(self):
        """The hourglass control's fit of the owned solid rows, refreshed in the halo
        (physics/sph/hourglass_control.py). No-op without the option."""
        if self.hourglass is None:
            return
        p = self.p
        n = p.n_owned
        self.hourglass.fit(p, self._smoothing(), self._pairs(n),
                           self.hourglass.control_pairs(p, n, self.start, self.index),
                           p.with_halo("u"), self.halo if self.halo_enabled else None,
                           self.timers)

    def _need_rebuild(self):
        """Collective: rebuild if the rows changed or a particle moved half the skin."""
        p = self.p
        need = self.x_build is None or len(self.x_build) != p.n_owned
        if not need and p.n_owned:
            need = moved_beyond(p["x"], self.x_build, 0.5 * self.skin)
        if self.halo_enabled and self.dist.size > 1:
            need = self.dist.any(need)
        return need

    def _update_neighbours(self, skip=()):
        """Rebuild the lists and the halo (collectively) if due, else refresh the halo's
        changing fields but `skip` (fields the caller derives and refreshes itself)."""
        p, t = self.p, self.timers
        if self._need_rebuild():
            if self.halo_enabled:
                with t.phase("halo"):
                    self.halo.exchange()
            with t.phase("neighbours"):
                # half lists: the rates loop takes every pair once, for both ends
                self.start, self.index = neighbour_lists(p.with_halo("x"), p.n_owned,
                                                         self.radius + self.skin, half=True)
            self.x_build = p["x"].copy()
            self.n_total_build = p.n_total
            self.rebuilds += 1
        else:
            # the halo rows are still in place behind the owned ones (the caller only hid
            # them for migration, which moved nothing here): refresh them in the same plan
            p.n_total = self.n_total_build
            if self.halo_enabled:
                with t.phase("halo"):
                    self.halo.refresh(tuple(n for n in self.halo.mutable if n not in skip))

    def evaluate(self):
        """Rates (acc, drho, L) of owned SPH particles at the current state."""
        p, t = self.p, self.timers
        self._place_ghosts()
        # the wall velocities and the solids' mirrored pressures are derived below from the
        # refreshed rows and then refreshed themselves: not sent twice
        self._update_neighbours(skip=WallTerms.DERIVED)
        n, nt = p.n_owned, p.n_total
        self.walls.derive(p, self._smoothing(), self._pairs(n),
                          self.halo if self.halo_enabled else None, t)
        self._correction(halo=True)
        self._density_gradient()
        self._shifting_state()
        self._hourglass_fit()
        with t.phase("sph"):
            rho, sigma = p.with_halo("rho"), p.with_halo("sigma")
            sound_speeds(self.dim, nt, p.with_halo("method"), p.with_halo("mat"), rho,
                         p.with_halo("F"), self.tagged_materials, p.with_halo("cs"))
            pair_stress(self.dim_tag, nt, sigma, rho, p.with_halo("S"))
            R = p.with_halo("R") if self.use_as else np.zeros((0, 6))
            if self.use_as:
                artificial_stress(self.dim, nt, sigma, rho, self.spec.artificial_stress, R)
            if self._mirror is not None:  # the clamps' stress is left out
                held = self._mirror.held_rows()
                p.with_halo("S")[held] = 0.0
                if self.use_as:
                    R[held] = 0.0
            sph_rates(self._smoothing(), self._pairs(n), self._pair_rows(),
                      self._options(want_force=True, want_L=self.want_L, want_fsi="fsi" in p),
                      self._terms(R=R if self.use_as else None,
                                  pw=p.with_halo("pw") if "pw" in p else None,
                                  clamped=None if self._mirror is None
                                  else self._mirror.held_rows()),
                      rates(p.with_halo("acc"), p.with_halo("drho"), p.with_halo("L"),
                            p.with_halo("fsi") if "fsi" in p else None,
                            p.with_halo("fcpl") if "fcpl" in p else None))
            if self.hourglass is not None:
                self.hourglass.forces(p, self._smoothing(), self._pairs(n),
                                      self.hourglass.control_pairs(p, n, self.start,
                                                                   self.index),
                                      p.with_halo("u"), p.with_halo("cs"), p.with_halo("acc"))
            # after every other force: the friction bounds their sum
            self.walls.contact(p, n, self.start, self.index,
                               None if self._mirror is None else self._mirror.held_rows())
        if self._mirror is not None:  # the ghosts' forces to their partners
            self._mirror.hand_back(p["acc"], self.gravity[: self.dim], self.spec.damping)
        if self.constraint is not None:
            self.constraint.hold(p["acc"])
        self._restore_ghosts()
        self.evaluated = True
        self.evaluations += 1

    def stress(self, dt, mstate_in):
        """Stress (and volume) of owned SPH particles; returns a failed row or -1."""
        p = self.p
        n = p.n_owned
        with self.timers.phase("sph"):
            return sph_stress(n, p["method"], p["mat"], p["rho"], p["F"], p["L"], dt,
                              (mstate_in, self._mstate(n)), self.tagged_materials,
                              p["sigma"], p["vol"], p["mass"], self.spec.pressure_min,
                              np.zeros(0) if self.morris_mu is None else self.morris_mu)

    def hydrostatic_start(self):
        """Fluid bodies start at rest in the hydrostatic state below their top, along g
        (physics/hydrostatic.py). An initial condition: `Simulation` applies it once, after
        seeding and the first balance (collective: the top is a global maximum), before the
        first time step is chosen; a restart restores rho instead."""
        n = self.p.n_owned
        half = 0.5 * self.spec.spacing
        for mine, rho, _ in fluid_columns(self.case, self.p, (self.mtypes, self.mparams),
                                          self.gravity[: self.dim], "sph",
                                          lambda body, up: half,
                                          self.dist if self.halo_enabled else None):
            self.p["rho"][:n][mine] = rho

    def initialise(self):
        """Stress from the initial state, then the first rates (before step 1)."""
        n = self.p.n_owned
        self.stress(0.0, self._mstate(n).copy())
        self.evaluate()

    def resume(self):
        """After a restart: rebuild what an evaluation derives (neighbour lists, halo, wall
        states, gradients) at the restored state, but keep the restored rates and stress.
        The rates a step starts from are those of the last evaluation before the
        checkpoint, which for the predictor-corrector was at mid-step: evaluating again at
        the restored state would give other ones (the velocities of a restarted run then
        drifted by 1e-5 relative). Collective."""
        p = self.p
        kept = {k: p[k].copy() for k in p.fields(migrate=True)}
        self.initialise()
        for k, values in kept.items():
            p[k][:] = values

    def warm_up(self):
        """Compile every kernel of this stage on empty arrays (the caller has set the
        particle counts to zero); no halo exchange."""
        p = self.p
        neighbour_lists(np.zeros((2, self.dim)), 2, 1.0)
        self.halo_enabled = False
        self.x_build = None
        try:
            self.evaluate()
            self.kinematics()
            self.stress(0.0, self._mstate(0).copy())
            n = 0
            if "x_n" in p:
                self._advance(0.0, 1.0, 0.0, save=True)
            add_scaled(self.dim_tag, n, p["method"], 0.0, p["v"], p["acc"])
            cayley_update(self.dim_tag, n, p["method"], 0.0, p["rho"], p["F"], p["drho"],
                          p["L"])
            first_outside(self.dim, n, p["x"], self.lo, self.hi)
            if self.shift_coef > 0.0:
                shift_positions(self.dim_tag, n, p["method"], p["mat"], self.fluid, p["x"],
                                p["v"], p["rho"], self._gradrho_owned(), self._shifting(),
                                self.shift_coef, 0.0, 1.0)
        finally:
            self.halo_enabled = True
            self.evaluated = False
            self.evaluations = self.rebuilds = 0
            self.x_build = None

    # -- integrators ---------------------------------------------------------------------------
    def _advance(self, c0, c1, dtc, save=False):
        """One stage y <- c0 y_n + c1 y + dtc f (with `save`: y_n <- y first)."""
        p = self.p
        n = p.n_owned
        with self.timers.phase("integrate"):
            advance(self.dim_tag, n, p["method"],
                    sph_state(p["x_n"], p["v_n"], p["rho_n"], p["F_n"]),
                    sph_state(p["x"], p["v"], p["rho"], p["F"]),
                    rates(p["acc"], p["drho"], p["L"]), c0, c1, dtc, save, self.want_L)

    def _drift(self, n, dt):
        """x += dt v over the owned SPH rows, and the hourglass control's displacement
        u += dt v with them (kernels/sph/hourglass.py: u keeps its own rounding)."""
        p = self.p
        add_scaled(self.dim_tag, n, p["method"], dt, p["x"], p["v"])
        if self.hourglass is not None:
            self.hourglass.drift(p, self.dim_tag, n, dt)

    def kick(self, dt):
        """The first half kick of a Verlet step alone (v += dt/2 acc, with the first rates
        if none yet): the conservative coupling gives it before the MPM step, whose P2G
        then carries the SPH momentum at mid-step, and calls `step` with `kicked`."""
        if not self.evaluated:
            self.initialise()
        p = self.p
        with self.timers.phase("integrate"):
            add_scaled(self.dim_tag, p.n_owned, p["method"], 0.5 * dt, p["v"], p["acc"])

    def step(self, dt, time, kicked=False):
        """Advance owned SPH particles by dt; returns a failed row or -1. `kicked`: the
        first half kick of a Verlet step was given already (`kick`)."""
        p = self.p
        n = p.n_owned
        if not self.evaluated:
            self.initialise()
        self.walls.dt = dt
        m0 = self._mstate(n).copy()
        bad = self.integrator.updated(self, dt, m0, kicked)
        if self.shift_coef > 0.0 and bad < 0:
            with self.timers.phase("integrate"):
                shift_positions(self.dim_tag, n, p["method"], p["mat"], self.fluid, p["x"],
                                p["v"], p["rho"], self._gradrho_owned(), self._shifting(),
                                self.shift_coef, dt, self.spec.spacing)
        self.walls.move(p, n, dt)  # prescribed motion, after the fluid's
        for axis in self.case.periodic:  # back into the period (images do the rest)
            wrap_axis(p["x"][:n], axis, self.lo[axis], self.hi[axis] - self.lo[axis])
        if bad < 0:
            bad = first_outside(self.dim, n, p["x"], self.lo, self.hi)
        return bad

    def signal_speed(self):
        """Local max of c + |v| over owned particles, c from the last evaluation (None before
        the first one: the caller then uses the material wave speeds)."""
        if not self.evaluated or "cs" not in self.p:
            return None
        p = self.p
        return max_signal(self.dim_tag, p.n_owned, p["cs"], p["v"])

    def local_stable_dt(self):
        """This rank's part of `stable_dt` (no collective)."""
        limit = min((m.max_stable_viscous_dt(self.h) for m in self.case.materials.values()),
                    default=np.inf)
        p = self.p
        if self.evaluated and p.n_owned and "drho" in p:
            rate = float(np.max(np.abs(p["drho"]) / p["rho"]))
            if rate > 0:
                limit = min(limit, 1.0 / rate)
        return limit

    def stable_dt(self):
        """Viscous limit 0.125 h^2 / nu of the fluids, and 1 / max |drho/dt| / rho (times the
        caller's Courant number: the density changes by at most that fraction in a step, so
        a violent expansion cannot drive the continuity density through zero). Global
        (collective when parallel); the CFL limit is the caller's."""
        limit = self.local_stable_dt()
        if self.halo_enabled and self.dist.size > 1:
            limit = self.dist.min(limit)
        return limit
