"""TLSPHStage: corrected-kernel SPH for solids after seed 004 (Shutov & Klyuchantsev 2019).

State (x, v) and, with ``deformation = "rate"``, F; each *evaluation* at a state does
    halo exchange (width: two kernel supports times the largest stretch, so that every
        particle an owned one sums over has its own complete neighbour list here)
    -> reference lists on X0 + corrected reference gradients G0 (eqs. 1-3), once while the
       rows do not change
    -> F by eq. 8 (``reference``) for every row, or the integrated F (``rate``)
    -> stress of every row from F (material state restarted from its value at the step
       start: multi-stage integrators commit it once per step)
    -> the internal force eq. 5 — in the current configuration with the corrected kernel
       recomputed there (``force = "current"``, the seed's choice) or in the reference one
       with P = J sigma F^-T (``force = "reference"``, the exact adjoint of eq. 8)
    -> L by eq. 6 when eq. 9 or the current force needs the current configuration
and the integrators (TVD-RK3 as in seed 004 §5, predictor-corrector, Verlet) combine them.
The forces are scatters over all listed rows, so halo rows take part with their own lists.
See `pmpmsph.kernels.sph.tlsph` for the index conventions and the stability findings.
"""
import numpy as np

from ...errors import RunError
from ...kernels.neighbours import neighbour_lists
from ...kernels.sph.stress import sound_speeds, sph_stress_all
from ...kernels.sph.integrate import add_scaled, first_outside
from ...kernels.sph.kernel_functions import SUPPORT
from ...kernels.sph.views import pair_lists, smoothing_of
from ...kernels.sph.tlsph import (deformation_gradient, first_piola, internal_force,
                                   kernel_correction, velocity_gradient, volumes_from_F)
from ...parallel.particle_halo import ParticleHalo
from ...particles import FieldSpec
from .hourglass_control import HourglassControl
from .stage import HALO_MARGIN, SPHStage


class TLSPHStage(SPHStage):
    """Total-Lagrangian SPH (seed 004) with the integrators of `SPHStage`."""

    @staticmethod
    def fields(case):
        state = max((m.state_size for m in case.materials.values()), default=0)
        out = [
            FieldSpec("X0", ("dim",), halo=True, output=True),
            FieldSpec("rho", (), halo=True, output=True),
            FieldSpec("acc", ("dim",)),
            FieldSpec("drho", ()),
            FieldSpec("L", (3, 3)),
            FieldSpec("force", ("dim",), migrate=False),
            FieldSpec("x_n", ("dim",), migrate=False),
            FieldSpec("v_n", ("dim",), migrate=False),
            FieldSpec("rho_n", (), migrate=False),
            FieldSpec("F_n", (3, 3), migrate=False, fill="identity"),
        ]
        if state:
            out.append(FieldSpec("mstate0", (state,), halo=True))
        if case.sph.hourglass > 0.0:  # the fitted gradient of the hourglass control
            out += HourglassControl.fields(case, displacement=False)
        return out

    def __init__(self, case, particles, materials, decomposition, dist, timers=None):
        self.stretch = 1.0
        super().__init__(case, particles, materials, decomposition, dist, timers)
        spec = case.sph
        self.corrected = spec.correction
        self.rate = spec.deformation == "rate"
        self.current_force = spec.force == "current"
        self.ref = None  # (start0, index0, gw0) of the reference configuration
        # hourglass control (kernels/sph/hourglass.py) over half lists of the reference
        # configuration; u = x - X0 is formed at each evaluation (no integrated field)
        self.hourglass = (HourglassControl(case, self.fluid) if spec.hourglass > 0.0
                          else None)
        # the materials of the SPH solids: their rows (and MPM points of the same material,
        # seed 000's region coupling) form the reference configuration; the rows of other
        # materials, e.g. an MPM fluid's points, are neither neighbours nor written here
        names = list(case.materials)
        self.tl_materials = np.array(sorted({names.index(b.material) for b in case.bodies
                                             if b.method == "sph" and not b.wall}), np.int64)
        self.others = None  # mask of the rows of other materials (None: there are none)
        self.want_L = True  # F is integrated (eq. 9) or recomputed: advance it in any case

    def set_decomposition(self, decomposition):
        self.dec = decomposition
        self.halo = ParticleHalo(decomposition, self.p, self._halo_width(), check=False)
        self.invalidate()

    def invalidate(self):
        self.x_build = None
        self.ref = None

    def _halo_width(self):
        """Two kernel supports (the neighbours' own lists) times the largest stretch."""
        return 2.0 * SUPPORT * self.h * self.stretch * 1.1 + HALO_MARGIN * self.h

    def _max_stretch(self):
        """Largest principal stretch of the owned F (global), for the halo width."""
        F = self.p["F"]
        if len(F) == 0:
            s = 1.0
        else:
            d = self.dim
            C = np.einsum("nki,nkj->nij", F[:, :d, :d], F[:, :d, :d])
            s = float(np.sqrt(np.max(np.linalg.eigvalsh(C)))) if d > 1 else float(
                np.max(np.abs(F[:, 0, 0])))
        return self.dist.max(s) if self.halo_enabled and self.dist.size > 1 else s

    # -- one evaluation ------------------------------------------------------------------------
    def _exchange(self):
        p, t = self.p, self.timers
        if self.dist.size == 1 or not self.halo_enabled:
            if self.ref is None:
                p.drop_halo()
            else:
                p.n_total = self.n_total_build
            return
        with t.phase("halo"):
            self.stretch = self._max_stretch()
            self.halo.width = self._halo_width()
            thinnest = np.diff(self.dec.faces).min() * self.dec.dx
            if self.halo.width > thinnest:
                raise RunError(-1, -1, f"total-Lagrangian SPH needs a halo of "
                               f"{self.halo.width:.3g} (two kernel supports x stretch "
                               f"{self.stretch:.3g}), thicker than the thinnest slab "
                               f"{thinnest:.3g}: use fewer ranks or a larger [domain]")
            self.halo.exchange()
        self.ref = None  # the halo rows changed

    def _reference(self):
        """Reference lists and corrected gradients G0 for every row (once per halo)."""
        p = self.p
        if self.ref is not None:
            return self.ref
        X0 = p.with_halo("X0")
        nt = p.n_total
        others = ~np.isin(p.with_halo("mat"), self.tl_materials)
        self.others = others if others.any() else None
        # the rows this stage evaluates (F, stress, volume, ...): its own materials'
        self.rows = np.nonzero(~others)[0] if self.others is not None else np.arange(nt)
        with self.timers.phase("neighbours"):
            start, index = self._own_pairs(*neighbour_lists(X0, nt, SUPPORT * self.h))
        with self.timers.phase("sph"):
            gw0 = np.empty((len(index), self.dim))
            wt0 = np.empty(len(index))
            kernel_correction(X0, p.with_halo("vol0"), start, index, self.h, self.kern,
                              self.dim, self.corrected, wt0, gw0)
        self.ref = (start, index, gw0)
        if self.hourglass is not None:
            self.ref_half = neighbour_lists(X0, p.n_owned, SUPPORT * self.h, half=True)
        self.n_total_build = nt
        self.rebuilds += 1
        return self.ref

    def _own_pairs(self, start, index):
        """The CSR lists (start, index) without the pairs that touch a row of another
        material (the lists unchanged when every row is of an SPH solid's material; two such
        materials touching at the start stay joined, as before)."""
        if self.others is None:
            return start, index
        rows = np.repeat(np.arange(len(start) - 1), np.diff(start))
        keep = ~self.others[rows] & ~self.others[index]
        kept = np.zeros_like(start)
        np.cumsum(np.bincount(rows[keep], minlength=len(start) - 1), out=kept[1:])
        return kept, index[keep]

    def evaluate(self, dt_state=0.0):
        """Accelerations of the owned particles at the current state (and F, stress, L).
        The rows of other materials (the points of an MPM fluid in a coupled scene) keep
        their own F, L, stress, volume, density and material state: the kernels write
        `self.rows` alone, and no pair joins those rows to others (`_own_pairs`)."""
        self._place_ghosts()
        self._exchange()
        self._reference()
        self._evaluate(dt_state)
        self._restore_ghosts()

    def _evaluate(self, dt_state):
        p, t = self.p, self.timers
        start0, index0, gw0 = self.ref
        rows = self.rows
        nt, n = p.n_total, p.n_owned
        x, v, F = p.with_halo("x"), p.with_halo("v"), p.with_halo("F")
        vol0, vol = p.with_halo("vol0"), p.with_halo("vol")
        with t.phase("sph"):
            if not self.rate:
                deformation_gradient(rows, start0, index0, gw0, vol0, x, p.with_halo("X0"),
                                     self.dim, F)
            J = np.ones(nt)  # (1 for the rows of other materials)
            volumes_from_F(rows, F, vol0, p.with_halo("mass"), J, vol, p.with_halo("rho"))
            inverted = np.nonzero(~(J[:n] > 0))[0]  # owned rows only: halo rows are their
            if len(inverted) and self._bad < 0:     # owners' to report
                self._bad = int(inverted[0])
            need_current = self.current_force or self.rate
            if need_current:
                start, index = self._own_pairs(*neighbour_lists(x, nt, SUPPORT * self.h))
                gw = np.empty((len(index), self.dim))
                wt = np.empty(len(index))
                kernel_correction(x, vol, start, index, self.h, self.kern, self.dim,
                                  self.corrected, wt, gw)
                velocity_gradient(rows, start, index, gw, vol, v, self.dim, p.with_halo("L"))
            mstate = p.with_halo("mstate") if "mstate" in p else np.zeros((nt, 0))
            if "mstate0" in p:  # the own rows' state restarted from the step's start
                m0 = p.with_halo("mstate0")
                if self.others is None:
                    mstate[:] = m0
                else:
                    mstate[rows] = m0[rows]
            sph_stress_all(rows, p.with_halo("mat"), F, p.with_halo("L"), dt_state, mstate,
                           self.tagged_materials, p.with_halo("sigma"))
            f = p.with_halo("force")
            held = self._mirror.held_rows() if self._mirror is not None else None
            if self.current_force:
                sigma = p.with_halo("sigma")
                if held is not None:  # a mirror clamp's stress is left out
                    sigma = np.where(held[:, None, None], 0.0, sigma)
                internal_force(start, index, gw, vol, sigma, self.dim, f)
            else:
                P = np.empty((nt, 3, 3))
                first_piola(rows, F, p.with_halo("sigma"), P)
                if held is not None:
                    P[held] = 0.0
                internal_force(start0, index0, gw0, vol0, P, self.dim, f)
            acc = p["acc"]
            acc[:] = f[:n] / p["mass"][:, None] + self.gravity[: self.dim]
        if self.hourglass is not None:
            self._hourglass(acc)
        if self._mirror is not None:  # the ghosts' forces to their partners
            self._mirror.hand_back(acc, self.gravity[: self.dim])
        with t.phase("sph"):
            if self.spec.damping:
                acc -= self.spec.damping * p["v"]
            if self.constraint is not None:
                self.constraint.hold(acc)
        self.evaluated = True
        self.evaluations += 1

    def _hourglass(self, acc):
        """Adds the hourglass control of kernels/sph/hourglass.py to acc: the pair penalty on
        each particle's distance from where its neighbours' fitted deformation gradient puts
        it (Ganzenmueller 2015, written for this total-Lagrangian form), which resists the
        odd-even mode the corrected kernel does not see (docs/plate.md: at a clamp it let the
        first free columns slip and rotate, +19 % deflection at 4 particles through a
        plate's thickness)."""
        p, t = self.p, self.timers
        n, nt = p.n_owned, p.n_total
        smoothing = smoothing_of(self.dim_tag, self.kern_tag, self.h)
        pairs = pair_lists(n, *self.ref_half)
        u = p.with_halo("x") - p.with_halo("X0")
        cs = np.empty(nt)
        with t.phase("sph"):
            sound_speeds(self.dim, nt, p.with_halo("method"), p.with_halo("mat"),
                         p.with_halo("rho"), p.with_halo("F"), self.tagged_materials, cs)
            control = self.hourglass.control_pairs(p, n, *self.ref_half)
        self.hourglass.fit(p, smoothing, pairs, control, u,
                           self.halo if self.halo_enabled and self.dist.size > 1 else None, t)
        with t.phase("sph"):
            self.hourglass.forces(p, smoothing, pairs, control, u, cs, acc)

    def initialise(self):
        self._bad = -1
        self.evaluate(0.0)

    def stress(self, dt, mstate_in):  # the stress is part of every evaluation here
        return -1

    def warm_up(self):
        p = self.p
        neighbour_lists(np.zeros((2, self.dim)), 2, 1.0)
        self.halo_enabled = False
        try:
            self.evaluate(0.0)
            if "x_n" in p:
                self._advance(0.0, 1.0, 0.0, save=True)
            add_scaled(self.dim_tag, 0, p["method"], 0.0, p["v"], p["acc"])
            first_outside(self.dim, 0, p["x"], self.lo, self.hi)
        finally:
            self.halo_enabled = True
            self.evaluated = False
            self.evaluations = self.rebuilds = 0
            self.invalidate()

    # -- integrators ---------------------------------------------------------------------------
    def step(self, dt, time):
        p = self.p
        n = p.n_owned
        self._bad = -1
        if not self.evaluated:
            self.initialise()
        if "mstate0" in p:  # commit the material state of the last step
            p["mstate0"][...] = p["mstate"]
        self.integrator.total(self, dt)
        bad = self._bad
        if bad < 0:
            bad = first_outside(self.dim, n, p["x"], self.lo, self.hi)
        return bad
