"""Per-particle switch on the material type code, called from the MPM and SPH kernels.

Type codes (module constants, also in `pmpmsph.materials.codes`): LINEAR_ELASTIC = 0,
STVK = 1, NEO_HOOKEAN = 2, HARTMANN_NEFF = 3, MAXWELL = 4, TAIT_FLUID = 5.  An unknown code
gives a NaN stress / energy / wave speed, which the callers' NaN checks report.

The three entry points are inlined into the calling kernel at the Numba IR level
(``inline="always"``): as a plain call, the reference counting of the five array views
costs about as much as the stress update of the simple models (measured 20-40 ns per
particle saved by inlining).  Note that Numba's on-disk cache of a calling kernel is keyed
on the caller's source file only: after editing a material module, clear the
``__pycache__`` of the calling modules (this holds for any cross-module njit call).

`wave_speed(mtype, par, J)` is the spatial longitudinal wave speed for the CFL condition.
For the solids it is the speed of a plane longitudinal wave in uniaxial strain
F = diag(J, 1, 1) of the respective model, ``c^2 = J^2 (d sigma_xx / dJ) / rho0``,
but never below the at-rest value ``c0^2 = (lambda + 2 mu)/rho0`` (``(k + 4/3 mu)/rho0`` for
Hartmann-Neff/Maxwell; ``E/rho0`` for the 1D bar since lambda = 0, mu = E/2 there):

* linear_elastic: ``c0`` (independent of J);
* stvk: ``c0^2 max(1, J^2 (3 J^2 - 1)/2)``;
* neo_hookean (seed 003, eq. 47): ``max(c0^2, [mu (J^2 + 1) + lambda (1 - ln J)]/rho0)``;
* hartmann_neff, maxwell (seed 004, eq. 11; the Maxwell body's instantaneous response is
  bounded by the elastic one): ``max(c0^2, [2 mu/9 (J^(4/3) + 5 J^(-2/3))
  + k/10 (4 J^5 + 6 J^-5)]/rho0)``;
* tait_fluid: ``sqrt(dp/drho) = sqrt(kappa gamma/rho0 (rho/rho0)^(gamma-1))``, rho/rho0 = 1/J
  (seed 003, eq. 50).
"""
import numpy as np
from numba.extending import overload

from ..jit import njit
from .codes import HARTMANN_NEFF, LINEAR_ELASTIC, MAXWELL, NEO_HOOKEAN, STVK, TAIT_FLUID
from .elastic import (energy_hartmann_neff, energy_linear_elastic, energy_neo_hookean,
                      energy_stvk, stress_hartmann_neff, stress_linear_elastic,
                      stress_neo_hookean, stress_stvk)
from .fluid import energy_tait_fluid, stress_tait_fluid
from .maxwell import energy_maxwell, stress_maxwell

__all__ = ["LINEAR_ELASTIC", "STVK", "NEO_HOOKEAN", "HARTMANN_NEFF", "MAXWELL", "TAIT_FLUID",
           "compute_stress", "compute_stress_tagged", "material_tag", "strain_energy",
           "wave_speed"]


@njit
def _max_nan(a, b):
    """max(a, b) that returns NaN if b is NaN (so an invalid J is not masked)."""
    return a if a >= b else b


@njit(inline="always")
def compute_stress(mtype, F, L, dt, state, par, sigma):
    """Cauchy stress of material `mtype` into `sigma` (may update `state` in place)."""
    if mtype == NEO_HOOKEAN:
        stress_neo_hookean(F, L, dt, state, par, sigma)
    elif mtype == TAIT_FLUID:
        stress_tait_fluid(F, L, dt, state, par, sigma)
    elif mtype == LINEAR_ELASTIC:
        stress_linear_elastic(F, L, dt, state, par, sigma)
    elif mtype == STVK:
        stress_stvk(F, L, dt, state, par, sigma)
    elif mtype == HARTMANN_NEFF:
        stress_hartmann_neff(F, L, dt, state, par, sigma)
    elif mtype == MAXWELL:
        stress_maxwell(F, L, dt, state, par, sigma)
    else:
        for i in range(3):
            for j in range(3):
                sigma[i, j] = np.nan


_STRESS_BY_CODE = {NEO_HOOKEAN: stress_neo_hookean, TAIT_FLUID: stress_tait_fluid,
                   LINEAR_ELASTIC: stress_linear_elastic, STVK: stress_stvk,
                   HARTMANN_NEFF: stress_hartmann_neff, MAXWELL: stress_maxwell}


def compute_stress_tagged(mtag, mtype, F, L, dt, state, par, sigma):
    """`compute_stress` with the type fixed at compile time when `mtag` is not empty.

    `mtag = (0,) * (code + 1)` (see `material_tag`) names one material type for every particle
    of a kernel call. The Numba overload below picks that model while *typing* the caller, so
    only its code is compiled and inlined: a runtime switch over all six models, inlined in a
    particle loop, costs ~4x the stress update itself and multiplies compile time. The switch
    is used only when a scene mixes material types (`mtag = ()`). This Python body is what
    runs under NUMBA_DISABLE_JIT=1.
    """
    if len(mtag) == 0:
        compute_stress(mtype, F, L, dt, state, par, sigma)
    else:
        _STRESS_BY_CODE[len(mtag) - 1](F, L, dt, state, par, sigma)


@overload(compute_stress_tagged, inline="always")
def _compute_stress_tagged_typed(mtag, mtype, F, L, dt, state, par, sigma):
    count = len(mtag.types)
    if count == 0:
        def switch(mtag, mtype, F, L, dt, state, par, sigma):
            compute_stress(mtype, F, L, dt, state, par, sigma)
        return switch
    model = _STRESS_BY_CODE[count - 1]

    def fixed(mtag, mtype, F, L, dt, state, par, sigma):
        model(F, L, dt, state, par, sigma)
    return fixed


def material_tag(codes):
    """Compile-time tag for `compute_stress_tagged`: one type code -> (0,)*(code+1), else ()."""
    codes = set(int(c) for c in codes)
    return (0,) * (codes.pop() + 1) if len(codes) == 1 else ()


@njit(inline="always")
def strain_energy(mtype, F, state, par):
    """Stored energy per unit reference volume psi of material `mtype`."""
    if mtype == NEO_HOOKEAN:
        return energy_neo_hookean(F, state, par)
    elif mtype == TAIT_FLUID:
        return energy_tait_fluid(F, state, par)
    elif mtype == LINEAR_ELASTIC:
        return energy_linear_elastic(F, state, par)
    elif mtype == STVK:
        return energy_stvk(F, state, par)
    elif mtype == HARTMANN_NEFF:
        return energy_hartmann_neff(F, state, par)
    elif mtype == MAXWELL:
        return energy_maxwell(F, state, par)
    return np.nan


@njit(inline="always")
def wave_speed(mtype, par, J):
    """Longitudinal (solids) or sound (fluid) speed at the current J, see the module doc."""
    rho0 = par[2]
    if mtype == TAIT_FLUID:
        # c^2 = kappa gamma / rho0 J^(1 - gamma); the usual exponents by multiplication (this
        # runs per particle per step for the CFL time step; exp/log cost most of that pass)
        gamma = par[1]
        if gamma == 7.0:
            r = 1.0 / J
            r2 = r * r
            return np.sqrt(par[0] * 7.0 / rho0 * (r2 * r2 * r2))
        if gamma == 1.0:
            return np.sqrt(par[0] / rho0)
        return np.sqrt(par[0] * gamma / rho0 * np.exp((1.0 - gamma) * np.log(J)))
    if mtype == LINEAR_ELASTIC or mtype == STVK or mtype == NEO_HOOKEAN:
        lam = par[0]
        mu = par[1]
        m0 = lam + 2.0 * mu
        if mtype == LINEAR_ELASTIC:
            m = m0
        elif mtype == STVK:
            m = m0 * 0.5 * J * J * (3.0 * J * J - 1.0)
        else:
            m = mu * (J * J + 1.0) + lam * (1.0 - np.log(J))
        return np.sqrt(_max_nan(m0, m) / rho0)
    if mtype == HARTMANN_NEFF or mtype == MAXWELL:
        mu = par[0]
        k = par[1]
        m0 = k + 4.0 / 3.0 * mu
        c = np.cbrt(J)
        J2 = J * J
        J5 = J2 * J2 * J
        m = 2.0 / 9.0 * mu * (c * J + 5.0 / (c * c)) + 0.1 * k * (4.0 * J5 + 6.0 / J5)
        return np.sqrt(_max_nan(m0, m) / rho0)
    return np.nan
