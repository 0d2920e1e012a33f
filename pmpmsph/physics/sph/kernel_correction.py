"""The kernel gradient correction of updated-Lagrangian SPH (`[sph] correction`), computed at
the start of each evaluation for the pair loop of `kernels.sph.rates.sph_rates`:

- `correction = true`: the matrices B_a = (M_a^T)^-1 of every owned row (Bonet & Lok 1999;
  seed 004 §2.1 for the first-order completeness they restore;
  `kernels.sph.correction.correction_matrices`);
- `correction = "liu"`: the coefficients of Liu's corrected kernel (seed 004, eqs. 1-3;
  `kernels.sph.liu.liu_coefficients`) of the SPH solid rows only.

The force needs them at both ends of a pair, so they are refreshed in the halo; the
kinematics alone (the Verlet step's mid-step drho and L) reads the owned rows' only.
The total-Lagrangian stage corrects its own kernel (`kernels.sph.tlsph.kernel_correction`).
"""
import numpy as np

from ...codes import SPH
from ...kernels.sph.correction import correction_matrices
from ...kernels.sph.liu import COEF, liu_coefficients
from ...particles import FieldSpec
from ..scratch import rows_at_least


class KernelCorrection:
    """The correction of one updated-Lagrangian SPH stage (module doc); `fluid`: per
    material, whether it is a Tait fluid."""

    #: `rate_options`' compile-time switch: corrected gradients in the pair loop
    TAG = (0,)

    def __init__(self, case, fluid):
        self.fluid = fluid
        self.liu = case.sph.correction_kind == "liu"
        self._M = np.zeros((0, 3, 3))   # Bonet & Lok's moment matrices (scratch)
        self._sums = np.zeros((0, 52))  # Liu's moment sums (scratch)
        self._rows, self._rows_key = None, None  # (`_liu_rows`)

    @staticmethod
    def fields(case):
        """Liu's coefficients or the matrices B (DESIGN.md §2): derived, so not migrated."""
        if case.sph.correction_kind == "liu":
            return [FieldSpec("liu", (COEF,), migrate=False)]
        return [FieldSpec("B", (3, 3), migrate=False, fill="identity")]

    def terms(self, p):
        """(B, liu) of `rate_terms`: the one this correction computes, None for the other."""
        if self.liu:
            return None, p.with_halo("liu")
        return p.with_halo("B"), None

    def _liu_rows(self, p, n):
        """The owned rows that take Liu's correction: SPH solids. Fluid pairs keep the plain
        gradient (with it, water under a plate broke up at the free surface's corners:
        det F < 0 after 35,000 steps at spacing 0.005, docs/plate.md). Kept while
        `particles.epoch` says no row changed."""
        if self._rows_key != (p.epoch, n):
            self._rows = (p["method"][:n] == SPH) & ~self.fluid[p["mat"][:n]]
            self._rows_key = (p.epoch, n)
        return self._rows

    def compute(self, p, smoothing, pairs, start, index, halo, timers):
        """B or Liu's coefficients of the owned rows; `halo` None: no refresh."""
        n = p.n_owned
        if self.liu:
            self._sums = rows_at_least(self._sums, n)
            with timers.phase("sph"):
                liu_coefficients(smoothing, pairs, p.with_halo("x"), p.with_halo("mass"),
                                 p.with_halo("rho"), p.with_halo("method"),
                                 p.with_halo("mat"), self._liu_rows(p, n), self._sums,
                                 p.with_halo("liu"))
            field = "liu"
        else:
            self._M = rows_at_least(self._M, n)
            dim_tag, kern_tag, h = smoothing
            with timers.phase("sph"):
                correction_matrices(dim_tag, kern_tag, h, n, p.with_halo("x"),
                                    p.with_halo("mass"), p.with_halo("rho"),
                                    p.with_halo("method"), start, index, self._M,
                                    p.with_halo("B"))
            field = "B"
        if halo is not None:
            with timers.phase("halo"):
                halo.refresh((field,))
