"""The hourglass control of SPH solids (`[sph] hourglass`, kernels/sph/hourglass.py and
kernels/sph/hourglass_quadratic.py), for both SPH stages.

A solid row's neighbours fit a deformation gradient Fh to their displacements u (linear or
quadratic, `[sph] hourglass_fit`); the control then penalises each pair's distance from the
place that fit puts it (after Ganzenmueller, "An hourglass control algorithm for Lagrangian
Smooth Particle Hydrodynamics", CMAME 2015; the energy and its pair force are derived in
kernels/sph/hourglass.py). One evaluation:

1. `fit`: Fh of the owned rows, refreshed in the halo (the force needs it at both ends);
2. `forces`: the pair penalty, added to the accelerations.

The updated-Lagrangian stage integrates u with x (`drift`, so u keeps its own rounding and
the control sees no cancellation in x - X0); the total-Lagrangian stage forms u = x - X0 at
each evaluation. The control's pairs depend on the reference positions and the lists alone,
so they are made once per list (`control_pairs`).
"""
import numpy as np

from ...kernels.sph.hourglass_quadratic import HOURGLASS_FITS
from ...kernels.sph.integrate import add_scaled
from ...particles import FieldSpec
from ..scratch import rows_at_least


class HourglassControl:
    """The control of one SPH stage (module doc); `fluid`: per material, whether it is a
    Tait fluid (fluid rows take no control)."""

    def __init__(self, case, fluid):
        spec = case.sph
        self.dim = case.dim
        self.kern = spec.kernel_code
        self.h = spec.h
        self.coef = spec.hourglass
        self.fluid = fluid
        fit = HOURGLASS_FITS[spec.hourglass_fit]
        self._make_pairs, self._fit, self._forces = fit.pairs, fit.fit, fit.forces
        self._A = np.zeros((0,) + fit.scratch)  # the fit's moment matrices (scratch)
        self._control, self._control_of = None, None

    @staticmethod
    def fields(case, displacement):
        """The fitted coefficients Fh and, with `displacement` (the updated-Lagrangian
        stage), the integrated displacement u (DESIGN.md §2). The reference positions X0
        are the stage's: the mirror clamps read them too."""
        out = [FieldSpec("u", ("dim",), halo=True)] if displacement else []
        return out + [FieldSpec("Fh", HOURGLASS_FITS[case.sph.hourglass_fit].coefficients,
                                migrate=False, halo=True)]

    def control_pairs(self, p, n, start, index):
        """The control's pairs and weights over these half lists (`HourglassFit.pairs`), made
        once per list (a rebuilt list is a new array): the fit and the forces each made them
        before, 40 % of the control's cost."""
        if self._control_of is None or self._control_of[0] is not start \
                or self._control_of[1] != n:
            self._control = self._make_pairs(self.dim, self.kern, self.h, n,
                                             p.with_halo("X0"), p.with_halo("method"),
                                             p.with_halo("mat"), self.fluid, start, index)
            self._control_of = (start, n)
        return self._control

    def fit(self, p, smoothing, pairs, control, u, halo, timers):
        """Step 1 of the module doc; `halo` None: no refresh (one rank, or the warm-up)."""
        n = p.n_owned
        self._A = rows_at_least(self._A, n)
        with timers.phase("sph"):
            self._fit(smoothing, pairs, control, u, p.with_halo("X0"), p.with_halo("mass"),
                      p.with_halo("rho"), p.with_halo("method"), p.with_halo("mat"),
                      self.fluid, self._A, p.with_halo("Fh"))
        if halo is not None:
            with timers.phase("halo"):
                halo.refresh(("Fh",))

    def forces(self, p, smoothing, pairs, control, u, cs, acc):
        """Step 2 of the module doc, added to `acc` (the caller's "sph" phase)."""
        self._forces(smoothing, pairs, control, u, p.with_halo("X0"), p.with_halo("Fh"),
                     p.with_halo("mass"), p.with_halo("rho"), cs, self.coef, acc)

    def drift(self, p, dim_tag, n, dt):
        """u += dt v over the owned SPH rows (the updated-Lagrangian stage's drift)."""
        add_scaled(dim_tag, n, p["method"], dt, p["u"], p["v"])
