"""Elastic solids: linear elastic, St Venant-Kirchhoff, neo-Hookean, Hartmann-Neff neo-Hookean.

All four are stateless (`STATE_SIZE = 0`); `L`, `dt` and `state` are accepted for the common
interface and ignored.  Stress functions write the Cauchy stress into `sigma`; energy
functions return psi per unit *reference* volume.  The models assume J = det F > 0; the caller
checks for inverted particles.

Parameter vectors (length NPAR = 8, built by `pmpmsph.materials`):

* linear_elastic, stvk, neo_hookean: ``[lambda, mu, rho0, E, nu, 0, 0, 0]``
  (in 1D the registry stores lambda = 0, mu = E/2: a uniaxial-stress bar).
* hartmann_neff: ``[mu, k, rho0, 0, 0, 0, 0, 0]`` (shear and bulk modulus).

The wave speed of each (for the CFL condition) is the speed of a plane longitudinal wave
in uniaxial strain F = diag(J, 1, 1) of the model, ``c^2 = J^2 (d sigma_xx / dJ) / rho0``,
but never below the at-rest value ``c0^2 = (lambda + 2 mu)/rho0`` (``(k + 4/3 mu)/rho0``
for Hartmann-Neff; ``E/rho0`` for the 1D bar since lambda = 0, mu = E/2 there).
"""
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..jit import njit
from .base import IsotropicElastic, ShearBulk, check_dim
from .registry import Model, register
from .tensor import (det3, det_minus_one, hartmann_neff_cauchy,
                     hartmann_neff_volumetric_energy, inv_cbrt_sq, left_cauchy_green,
                     max_keep_nan, push_forward_sym, right_cauchy_green, store_sym,
                     trace_C_minus_three)

LINEAR_ELASTIC = 0
STVK = 1
NEO_HOOKEAN = 2
HARTMANN_NEFF = 3

STATE_SIZE = 0


# ---------------------------------------------------------------- linear elastic
@njit(inline="always")
def stress_linear_elastic(F, L, dt, state, par, sigma):
    """sigma = lambda tr(eps) I + 2 G eps with eps = sym(F) - I (Raymond, seed 000, eq. 3.11).

    Small-strain model: it is *not* objective under finite rotations."""
    lam = par[0]
    mu2 = 2.0 * par[1]
    exx = F[0, 0] - 1.0
    eyy = F[1, 1] - 1.0
    ezz = F[2, 2] - 1.0
    exy = 0.5 * (F[0, 1] + F[1, 0])
    eyz = 0.5 * (F[1, 2] + F[2, 1])
    exz = 0.5 * (F[0, 2] + F[2, 0])
    ltr = lam * (exx + eyy + ezz)
    store_sym(sigma, ltr + mu2 * exx, ltr + mu2 * eyy, ltr + mu2 * ezz,
              mu2 * exy, mu2 * eyz, mu2 * exz)


@njit(fastmath=False)
def energy_linear_elastic(F, state, par):
    """psi = 1/2 sigma:eps = lambda/2 tr(eps)^2 + mu eps:eps (eps = sym(F) - I)."""
    lam = par[0]
    mu = par[1]
    exx = F[0, 0] - 1.0
    eyy = F[1, 1] - 1.0
    ezz = F[2, 2] - 1.0
    exy = 0.5 * (F[0, 1] + F[1, 0])
    eyz = 0.5 * (F[1, 2] + F[2, 1])
    exz = 0.5 * (F[0, 2] + F[2, 0])
    tr = exx + eyy + ezz
    ee = exx * exx + eyy * eyy + ezz * ezz + 2.0 * (exy * exy + eyz * eyz + exz * exz)
    return 0.5 * lam * tr * tr + mu * ee


# ---------------------------------------------------------------- St Venant-Kirchhoff
@njit(inline="always")
def stress_stvk(F, L, dt, state, par, sigma):
    """S = lambda tr(E) I + 2 mu E, E = (C - I)/2 (seed 003, eq. 46); sigma = F S F^T / J."""
    lam = par[0]
    mu2 = 2.0 * par[1]
    cxx, cyy, czz, cxy, cyz, cxz = right_cauchy_green(F)
    exx = 0.5 * (cxx - 1.0)
    eyy = 0.5 * (cyy - 1.0)
    ezz = 0.5 * (czz - 1.0)
    ltr = lam * (exx + eyy + ezz)
    sxx, syy, szz, sxy, syz, sxz = push_forward_sym(
        F, ltr + mu2 * exx, ltr + mu2 * eyy, ltr + mu2 * ezz,
        mu2 * 0.5 * cxy, mu2 * 0.5 * cyz, mu2 * 0.5 * cxz)
    rJ = 1.0 / det3(F)
    store_sym(sigma, sxx * rJ, syy * rJ, szz * rJ, sxy * rJ, syz * rJ, sxz * rJ)


@njit(fastmath=False)
def energy_stvk(F, state, par):
    """psi = lambda/2 (tr E)^2 + mu E:E (potential of seed 003, eq. 46)."""
    lam = par[0]
    mu = par[1]
    cxx, cyy, czz, cxy, cyz, cxz = right_cauchy_green(F)
    exx = 0.5 * (cxx - 1.0)
    eyy = 0.5 * (cyy - 1.0)
    ezz = 0.5 * (czz - 1.0)
    tr = exx + eyy + ezz
    ee = (exx * exx + eyy * eyy + ezz * ezz
          + 0.5 * (cxy * cxy + cyz * cyz + cxz * cxz))  # 2 * (C_ij/2)^2 off-diagonal
    return 0.5 * lam * tr * tr + mu * ee


# ---------------------------------------------------------------- neo-Hookean (seed 003)
@njit(inline="always")
def stress_neo_hookean(F, L, dt, state, par, sigma):
    """sigma = mu/J (F F^T - I) + lambda/J ln(J) I (seed 003, eq. 47)."""
    lam = par[0]
    mu = par[1]
    J = det3(F)
    rJ = 1.0 / J
    bxx, byy, bzz, bxy, byz, bxz = left_cauchy_green(F)
    vol = lam * np.log(J)
    store_sym(sigma,
              (mu * (bxx - 1.0) + vol) * rJ,
              (mu * (byy - 1.0) + vol) * rJ,
              (mu * (bzz - 1.0) + vol) * rJ,
              mu * bxy * rJ, mu * byz * rJ, mu * bxz * rJ)


@njit(fastmath=False)
def energy_neo_hookean(F, state, par):
    """psi = mu/2 (tr C - 3 - 2 ln J) + lambda/2 (ln J)^2, whose Kirchhoff stress is eq. 47."""
    lam = par[0]
    mu = par[1]
    jm1 = det_minus_one(F)
    lnJ = np.log1p(jm1)
    # tr C - 3 - 2 ln J = |F - I|^2 + 2 (tr(F - I) - ln J), each part free of cancellation
    return 0.5 * mu * (trace_C_minus_three(F) - 2.0 * lnJ) + 0.5 * lam * lnJ * lnJ


# ---------------------------------------------------------------- Hartmann-Neff neo-Hookean
@njit(inline="always")
def stress_hartmann_neff(F, L, dt, state, par, sigma):
    """tau = mu dev(B-bar) + k/10 (J^5 - J^-5) 1, sigma = tau / J, B-bar = J^(-2/3) F F^T
    (Shutov & Klyuchantsev, seed 004, eqs. 10-11)."""
    mu = par[0]
    k = par[1]
    J = det3(F)
    s = inv_cbrt_sq(J)
    bxx, byy, bzz, bxy, byz, bxz = left_cauchy_green(F)
    hartmann_neff_cauchy(s * bxx, s * byy, s * bzz, s * bxy, s * byz, s * bxz, J, mu, k, sigma)


@njit(fastmath=False)
def energy_hartmann_neff(F, state, par):
    """psi = mu/2 (tr B-bar - 3) + k/50 (J^5 + J^-5 - 2) (seed 004, eq. 12)."""
    mu = par[0]
    k = par[1]
    lnJ = np.log1p(det_minus_one(F))
    # J^(-2/3) tr C - 3 = (J^(-2/3) - 1) tr C + (tr C - 3), written without cancellation
    t3 = trace_C_minus_three(F)
    iso = np.expm1(-2.0 / 3.0 * lnJ) * (t3 + 3.0) + t3
    return 0.5 * mu * iso + hartmann_neff_volumetric_energy(lnJ, k)


# ---------------------------------------------------------------- wave speeds (module doc)
@njit(inline="always")
def wave_speed_linear_elastic(par, J):
    """c0, independent of J."""
    return np.sqrt((par[0] + 2.0 * par[1]) / par[2])


@njit(inline="always")
def wave_speed_stvk(par, J):
    """c^2 = c0^2 max(1, J^2 (3 J^2 - 1)/2)."""
    m0 = par[0] + 2.0 * par[1]
    return np.sqrt(max_keep_nan(m0, m0 * 0.5 * J * J * (3.0 * J * J - 1.0)) / par[2])


@njit(inline="always")
def wave_speed_neo_hookean(par, J):
    """c^2 = max(c0^2, [mu (J^2 + 1) + lambda (1 - ln J)]/rho0) (seed 003, eq. 47)."""
    lam = par[0]
    mu = par[1]
    m = mu * (J * J + 1.0) + lam * (1.0 - np.log(J))
    return np.sqrt(max_keep_nan(lam + 2.0 * mu, m) / par[2])


@njit(inline="always")
def wave_speed_hartmann_neff(par, J):
    """c^2 = max(c0^2, [2 mu/9 (J^(4/3) + 5 J^(-2/3)) + k/10 (4 J^5 + 6 J^-5)]/rho0)
    (seed 004, eq. 11; also the Maxwell body's, whose instantaneous response is bounded by
    the elastic one)."""
    mu = par[0]
    k = par[1]
    m0 = k + 4.0 / 3.0 * mu
    c = np.cbrt(J)
    J2 = J * J
    J5 = J2 * J2 * J
    m = 2.0 / 9.0 * mu * (c * J + 5.0 / (c * c)) + 0.1 * k * (4.0 * J5 + 6.0 / J5)
    return np.sqrt(max_keep_nan(m0, m) / par[2])


# ---------------------------------------------------------------- configuration, registration
@dataclass(frozen=True)
class LinearElastic(IsotropicElastic):
    """Small-strain linear elasticity, sigma = lambda tr(eps) I + 2 G eps (seed 000, eq. 3.11),
    eps = sym(F) - I.  Parameters: see `IsotropicElastic` (``[lambda, mu, rho0, E, nu, 0...]``)."""

    type_code: ClassVar[int] = LINEAR_ELASTIC
    model: ClassVar[str] = "linear_elastic"


@dataclass(frozen=True)
class StVenantKirchhoff(IsotropicElastic):
    """St Venant-Kirchhoff, S = lambda tr(E) I + 2 mu E (seed 003, eq. 46).
    Parameters ``[lambda, mu, rho0, E, nu, 0, 0, 0]`` (1D: lambda = 0, mu = E/2)."""

    type_code: ClassVar[int] = STVK
    model: ClassVar[str] = "stvk"
    aliases: ClassVar[tuple] = ("st_venant_kirchhoff",)


@dataclass(frozen=True)
class NeoHookean(IsotropicElastic):
    """Neo-Hookean, sigma = mu/J (F F^T - I) + lambda/J ln J I (seed 003, eq. 47).
    Parameters ``[lambda, mu, rho0, E, nu, 0, 0, 0]`` (1D: lambda = 0, mu = E/2)."""

    type_code: ClassVar[int] = NEO_HOOKEAN
    model: ClassVar[str] = "neo_hookean"


@dataclass(frozen=True)
class HartmannNeff(ShearBulk):
    """Neo-Hookean with the Hartmann-Neff volumetric part (seed 004, eqs. 10-12):
    tau = mu dev(B-bar) + k/10 (J^5 - J^-5) 1.  Parameters ``[mu, k, rho0, 0, 0, 0, 0, 0]``.
    Also constructible from (E, nu) via `from_E_nu` or the table keys E, nu."""

    mu: float
    k: float
    rho: float
    type_code: ClassVar[int] = HARTMANN_NEFF
    model: ClassVar[str] = "hartmann_neff"
    required: ClassVar[tuple] = ("mu", "k", "rho")

    def __post_init__(self):
        self._check_common()

    def params(self, dim):
        check_dim(dim)
        return self._vector(self.mu, self.k, self.rho)


register(Model(LinearElastic, stress_linear_elastic, energy_linear_elastic,
               wave_speed_linear_elastic))
register(Model(StVenantKirchhoff, stress_stvk, energy_stvk, wave_speed_stvk))
register(Model(NeoHookean, stress_neo_hookean, energy_neo_hookean, wave_speed_neo_hookean))
register(Model(HartmannNeff, stress_hartmann_neff, energy_hartmann_neff,
               wave_speed_hartmann_neff))
