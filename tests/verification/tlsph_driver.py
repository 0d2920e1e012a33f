"""Compact serial driver for the corrected-kernel SPH plate of seed 004, section 6.

Scenes 12 and 13 of BENCHMARKS.md: a 1 x 1 mm plate in plane strain, free surface, initial
velocity v1 = 0.8 x2, v2 = 0 (eq. 19), Hartmann-Neff neo-Hookean (mu = 1.25 MPa,
k = 5.833 MPa, rho = 3) or the Maxwell body with the same elasticity. Consistent units mm, s,
MPa, so c_p = sqrt((k + 4/3 mu)/rho) = sqrt(7.5/3) mm/s.

Particles: ``n x n`` on the nodes of a uniform grid with spacing s = 1/(n - 1), so a particle
sits exactly on the top-right corner, with trapezoidal volumes (s^2, s^2/2 on edges, s^2/4 at
corners: total volume and mass exact); ``layout="cells"`` puts them at cell centres of
spacing 1/n instead. h = k_h s (seed 004 section 2, k_h in [1, 1.4]; default 1.4, the
value at which the seed's combination stays stable longest, see below), support 2h.

Per stage: neighbour lists in the current configuration, F by eq. 8 (``f_mode="ref"``,
reference-configuration corrected gradients computed once) or the stage value of eq. 9
(``f_mode="exp"``), V = J V0, corrected kernel of the current configuration (eqs. 1-3),
stress from the material, force eq. 5, acceleration f / m (eq. 18). Time integration:
the Shu-Osher TVD-RK3 of seed 004 section 5 on (x, v) and, for eq. 9, on F with the
exponential update F <- exp(dt L) F as the Euler sub-step. The Maxwell state (eq. 16) is
committed once per step with the final F over the full dt; the stages use trial copies
advanced over their own time offsets (0, dt, dt/2). dt = CFL h / max(c_p, max |v|).

``force="current"`` (default) is the seed's eq. 5 with the kernel corrected in the current
configuration; ``force="reference"`` is its total-Lagrangian form (reference kernel, first
Piola-Kirchhoff stress), the exact adjoint of eq. 8. With eq. 8 the former is not
energy-consistent and develops an edge instability that sets in earlier the finer the
particles (pmpmsph/kernels/sph/tlsph.py, module docstring); the latter is stable.
"""
import time

import numpy as np

from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.smoothing.registry import kernel_code
from pmpmsph.kernels.sph.tlsph import (current_volume, deformation_gradient, energies,
                                   first_piola, internal_force, kernel_correction,
                                   material_stress, update_F_exp, velocity_gradient)
from pmpmsph.materials import material_from_table
from pmpmsph.materials.dispatch import material_tag

CUBIC = kernel_code("cubic")

MU, K_BULK, RHO = 1.25, 5.833, 3.0


def plate_material(eta=None):
    """Hartmann-Neff (eta None) or Maxwell material of seed 004, section 6."""
    if eta is None:
        table = {"model": "hartmann_neff", "mu": MU, "k": K_BULK, "rho": RHO}
    else:
        table = {"model": "maxwell", "mu": MU, "k": K_BULK, "eta": eta, "rho": RHO}
    return material_from_table(table, "material", 2)


def plate_particles(n, layout="nodes"):
    """(X0, V0, s, corner row) of an n x n plate on [0, 1]^2."""
    if layout == "nodes":
        s = 1.0 / (n - 1)
        c = np.linspace(0.0, 1.0, n)
        w = np.full(n, s)
        w[0] = w[-1] = 0.5 * s
    elif layout == "cells":
        s = 1.0 / n
        c = (np.arange(n) + 0.5) * s
        w = np.full(n, s)
    else:
        raise ValueError(layout)
    X, Y = np.meshgrid(c, c, indexing="ij")
    X0 = np.stack([X.ravel(), Y.ravel()], axis=1)
    V0 = np.outer(w, w).ravel()
    corner = int(np.argmax(X0[:, 0] + X0[:, 1]))
    return X0, V0, s, corner


class Plate:
    """State and TVD-RK3 stepping of the seed-004 plate (see the module docstring)."""

    dim = 2

    def __init__(self, n=21, eta=None, k_h=1.4, cfl=0.3, corrected=True, f_mode="ref",
                 kind=CUBIC, layout="nodes", omega=0.8, force="current"):
        if f_mode not in ("ref", "exp"):
            raise ValueError(f_mode)
        if force not in ("current", "reference"):
            raise ValueError(force)
        self.force = force
        self.mat = plate_material(eta)
        self.mtype = self.mat.type_code
        self.mtag = material_tag((self.mtype,))
        self.par = self.mat.params(2)
        self.maxwell = eta is not None
        self.X0, self.vol0, self.s, self.corner = plate_particles(n, layout)
        self.N = len(self.X0)
        self.rows = np.arange(self.N)  # every particle is evaluated
        self.h = k_h * self.s
        self.cfl = cfl
        self.corrected = corrected
        self.f_mode = f_mode
        self.kind = kind
        self.mass = self.mat.rho0 * self.vol0
        self.cp = self.mat.sound_speed()
        self.x = self.X0.copy()
        self.v = np.zeros_like(self.X0)
        self.v[:, 0] = omega * self.X0[:, 1]
        self.F = np.tile(np.eye(3), (self.N, 1, 1))
        self.state = np.tile(self.mat.initial_state(), (self.N, 1))
        self.t = 0.0
        self.n_degenerate = 0
        # reference configuration: pairs and corrected gradients of eq. 8, once
        self.start0, self.index0 = neighbour_lists(self.X0, self.N, 2.0 * self.h)
        self.gw0 = np.empty((len(self.index0), 2))
        wt0 = np.empty(len(self.index0))
        self.n_degenerate += kernel_correction(self.X0, self.vol0, self.start0, self.index0,
                                               self.h, kind, 2, corrected, wt0, self.gw0)
        self.vol = self.vol0.copy()
        self.sigma = np.zeros((self.N, 3, 3))
        self.L = np.zeros((self.N, 3, 3))
        self.P = np.zeros((self.N, 3, 3))
        self.f = np.zeros((self.N, 2))

    def ref_F(self, x):
        F = np.empty((self.N, 3, 3))
        deformation_gradient(self.rows, self.start0, self.index0, self.gw0, self.vol0, x,
                             self.X0, 2, F)
        return F

    def rates(self, x, v, F, stage_dt):
        """(acceleration, L) at a stage; F is the stage deformation gradient. The current
        configuration's lists and corrected kernel are built when eq. 5 or eq. 9 needs them
        (L is not used by the stress of eq. 8 runs: the Maxwell update needs only F, dt)."""
        if self.force == "current" or self.f_mode == "exp":
            start, index = neighbour_lists(x, self.N, 2.0 * self.h)
            wt = np.empty(len(index))
            gw = np.empty((len(index), 2))
            current_volume(F, self.vol0, self.vol)
            self.n_degenerate += kernel_correction(x, self.vol, start, index, self.h,
                                                   self.kind, 2, self.corrected, wt, gw)
            velocity_gradient(self.rows, start, index, gw, self.vol, v, 2, self.L)
        trial = self.state.copy()
        material_stress(self.mtype, F, self.L, stage_dt, trial, self.par, self.sigma,
                        self.mtag)
        if self.force == "current":
            internal_force(start, index, gw, self.vol, self.sigma, 2, self.f)
        else:  # total-Lagrangian form: first Piola-Kirchhoff P = J sigma F^-T, reference pairs
            first_piola(self.rows, F, self.sigma, self.P)
            internal_force(self.start0, self.index0, self.gw0, self.vol0, self.P, 2, self.f)
        return self.f / self.mass[:, None], self.L.copy()

    def _F_of(self, x, F):
        return self.ref_F(x) if self.f_mode == "ref" else F

    def time_step(self):
        vmax = np.sqrt((self.v ** 2).sum(axis=1).max())
        return self.cfl * self.h / max(self.cp, vmax)

    def step(self, dt):
        """One Shu-Osher TVD-RK3 step of eq. 18 (and of eq. 9 when f_mode == "exp").

        In Butcher form the stages are u1 = u0 + dt k0, u2 = u0 + dt (k0 + k1)/4,
        u_new = u0 + dt (k0 + k1 + 4 k2)/6. For eq. 9 each F increment dt sum_j a_j L_j F0
        is replaced by its exponential, F = exp(dt sum_j a_j L_j) F0 (commuting L: exactly
        the RK3 of dF/dt = L F; otherwise second order). Applying exp(dt L) inside the
        convex Shu-Osher combinations instead would be only first order in dt."""
        x0, v0, F0 = self.x, self.v, self.F
        exp_mode = self.f_mode == "exp"

        def F_at(x, *terms):
            if not exp_mode:
                return self.ref_F(x)
            Ls = sum(c * L for c, L in terms)
            F = np.empty_like(F0)
            update_F_exp(Ls, F0, dt, F)
            return F

        a0, L0 = self.rates(x0, v0, F_at(x0) if not exp_mode else F0, 0.0)
        x1 = x0 + dt * v0
        v1 = v0 + dt * a0
        a1, L1 = self.rates(x1, v1, F_at(x1, (1.0, L0)), dt)
        x2 = x0 + 0.25 * dt * (v0 + v1)
        v2 = v0 + 0.25 * dt * (a0 + a1)
        a2, L2 = self.rates(x2, v2, F_at(x2, (0.25, L0), (0.25, L1)), 0.5 * dt)
        self.x = x0 + dt / 6.0 * (v0 + v1 + 4.0 * v2)
        self.v = v0 + dt / 6.0 * (a0 + a1 + 4.0 * a2)
        self.F = F_at(self.x, (1.0 / 6.0, L0), (1.0 / 6.0, L1), (2.0 / 3.0, L2))
        if self.maxwell:  # commit eq. 16 over the full step with the final F
            material_stress(self.mtype, self.F, np.zeros_like(self.F), dt, self.state,
                            self.par, self.sigma, self.mtag)
        self.t += dt

    def energy(self):
        """(K, U) of eq. 7 at the current state."""
        return energies(self.mass, self.v, self.vol0, self.F, self.mtype, self.state,
                        self.par, 2, self.mtag)

    def run(self, T):
        """Advance to T; returns a history dict (t, K, U, E, corner displacement u[:, 2])."""
        wall = time.perf_counter()
        ts, Ks, Us, us = [], [], [], []

        def record():
            K, U = self.energy()
            ts.append(self.t)
            Ks.append(K)
            Us.append(U)
            us.append(self.x[self.corner] - self.X0[self.corner])

        record()
        steps = 0
        while self.t < T * (1.0 - 1e-12):
            dt = min(self.time_step(), T - self.t)
            self.step(dt)
            steps += 1
            record()
            if not np.isfinite(self.x).all() or not np.isfinite(Ks[-1] + Us[-1]):
                break
        t = np.array(ts)
        K = np.array(Ks)
        U = np.array(Us)
        return {"t": t, "K": K, "U": U, "E": K + U, "u": np.array(us), "steps": steps,
                "wall": time.perf_counter() - wall, "n_degenerate": self.n_degenerate}


def run_plate(T, **kw):
    """Build a `Plate` with keyword arguments `kw` and run it to T."""
    return Plate(**kw).run(T)


def drift(hist):
    """max_t |E(t) - E(0)| / E(0) and the final (E(T) - E(0)) / E(0)."""
    E = hist["E"]
    return np.abs(E - E[0]).max() / E[0], (E[-1] - E[0]) / E[0]


def curve_at(hist, t):
    """Corner displacement (2,) at times t, linear interpolation in time."""
    return np.stack([np.interp(t, hist["t"], hist["u"][:, i]) for i in range(2)], axis=1)
