"""Weakly compressible Newtonian fluid with the Tait equation of state (seed 003, eqs. 48-50).

    sigma = 2 mu_f [d - tr(d)/3 I] - p I,   d = sym(L)            (eq. 49, Stokes: eq. 48)
    p     = kappa [(rho/rho0)^gamma - 1],   rho/rho0 = 1/J, J = det F   (eq. 50)

Stateless (``STATE_SIZE = 0``).  Parameter vector (length NPAR = 8):
``[kappa, gamma, rho0, mu_f, 0, 0, 0, 0]``.

The stored energy is the Tait potential per unit reference volume, psi(J) with
dpsi/dJ = -p and psi(1) = 0:

    psi(J) = kappa [ (J^(1-gamma) - 1)/(gamma - 1) + J - 1 ]   (gamma = 1: kappa [J - 1 - ln J]).

The viscous part stores no energy.  In 2D (plane strain) the deviator still uses tr(d)/3.
Its wave speed is the sound speed sqrt(dp/drho) = sqrt(kappa gamma/rho0 (rho/rho0)^(gamma-1)),
rho/rho0 = 1/J (seed 003, eq. 50).
"""
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..errors import ConfigError
from ..jit import njit
from .base import Material, check_dim, finite_numbers, positive
from .registry import Model, register
from .tensor import det_minus_one, store_sym

STATE_SIZE = 0
TAIT_FLUID = 5


@njit(inline="always")
def tait_pressure(jm1, kappa, gamma):
    """p = kappa [(1/J)^gamma - 1] (seed 003, eq. 50) from jm1 = J - 1.

    The usual exponents take a fast exact path (this runs per particle per step and a
    log/exp pair costs as much as the rest of the G2P loop): gamma = 1 as -kappa jm1/J
    (no cancellation), gamma = 7 by multiplication (absolute error ~1e-15 kappa); any other
    gamma as kappa expm1(-gamma log1p(jm1)), accurate near J = 1."""
    if gamma == 1.0:
        return -kappa * jm1 / (1.0 + jm1)
    if gamma == 7.0:
        r = 1.0 / (1.0 + jm1)
        r2 = r * r
        return kappa * (r2 * r2 * r2 * r - 1.0)
    return kappa * np.expm1(-gamma * np.log1p(jm1))


@njit(inline="always")
def stress_tait_fluid(F, L, dt, state, par, sigma):
    """Cauchy stress of seed 003, eq. 49 with the pressure of eq. 50."""
    stress_tait_of_jm1(det_minus_one(F), L, par, sigma)


@njit(inline="always")
def stress_tait_of_jm1(jm1, L, par, sigma):
    """`stress_tait_fluid` from J - 1 (all the model reads of F): the form G2P calls in a
    scene that stores J alone (`kernels.deformation`), where the 3x3 determinant of
    diag(J, 1, 1) would cost a sixth of the particle's update."""
    kappa = par[0]
    gamma = par[1]
    mu2 = 2.0 * par[3]
    p = tait_pressure(jm1, kappa, gamma)
    dxx = L[0, 0]
    dyy = L[1, 1]
    dzz = L[2, 2]
    tr3 = (dxx + dyy + dzz) * (1.0 / 3.0)
    store_sym(sigma,
              mu2 * (dxx - tr3) - p,
              mu2 * (dyy - tr3) - p,
              mu2 * (dzz - tr3) - p,
              par[3] * (L[0, 1] + L[1, 0]),
              par[3] * (L[1, 2] + L[2, 1]),
              par[3] * (L[0, 2] + L[2, 0]))


@njit(fastmath=False)
def energy_tait_fluid(F, state, par):
    """Tait potential psi(J), dpsi/dJ = -p(J), psi(1) = 0 (per unit reference volume)."""
    kappa = par[0]
    gamma = par[1]
    jm1 = det_minus_one(F)
    lnJ = np.log1p(jm1)
    g1 = gamma - 1.0
    if abs(g1) < 1e-12:
        term = -lnJ
    else:
        term = np.expm1(-g1 * lnJ) / g1
    return kappa * (term + jm1)


@njit(inline="always")
def wave_speed_tait_fluid(par, J):
    """c^2 = kappa gamma / rho0 J^(1 - gamma) (module doc); the usual exponents by
    multiplication (this runs per particle per step for the CFL time step; exp/log cost
    most of that pass)."""
    rho0 = par[2]
    gamma = par[1]
    if gamma == 7.0:
        r = 1.0 / J
        r2 = r * r
        return np.sqrt(par[0] * 7.0 / rho0 * (r2 * r2 * r2))
    if gamma == 1.0:
        return np.sqrt(par[0] / rho0)
    return np.sqrt(par[0] * gamma / rho0 * np.exp((1.0 - gamma) * np.log(J)))


@dataclass(frozen=True)
class TaitFluid(Material):
    """Compressible Newtonian fluid with the Tait equation of state (seed 003, eqs. 48-50):
    sigma = 2 mu [d - tr(d)/3 I] - p I, p = kappa [(rho/rho0)^gamma - 1].
    Parameters ``[kappa, gamma, rho0, mu, 0, 0, 0, 0]`` (mu: dynamic shear viscosity)."""

    rho: float
    kappa: float
    gamma: float = 7.0
    mu: float = 0.0
    type_code: ClassVar[int] = TAIT_FLUID
    model: ClassVar[str] = "tait_fluid"
    aliases: ClassVar[tuple] = ("tait", "newtonian_fluid")
    required: ClassVar[tuple] = ("rho", "kappa")
    optional: ClassVar[tuple] = ("gamma", "mu")
    stiffness: ClassVar[str] = "kappa"
    fluid: ClassVar[bool] = True

    def __post_init__(self):
        finite_numbers(self)
        positive("rho", self.rho, "density")
        positive("kappa", self.kappa, "bulk modulus")
        positive("gamma", self.gamma, "Tait exponent")
        if not self.mu >= 0:
            raise ConfigError("mu", f"viscosity must be >= 0, got {self.mu!r}")

    def params(self, dim):
        check_dim(dim)
        return self._vector(self.kappa, self.gamma, self.rho, self.mu)

    @property
    def viscosity(self):
        """The dynamic viscosity (the trait every fluid has)."""
        return self.mu

    def sound_speed(self, dim=3):
        """sqrt(dp/drho) at rho = rho0: sqrt(kappa gamma / rho0)."""
        return math.sqrt(self.kappa * self.gamma / self.rho)

    def max_stable_viscous_dt(self, h):
        """Explicit viscous diffusion limit dt <= 0.125 h^2 rho0 / mu (inf if mu = 0)."""
        if self.mu == 0:
            return math.inf
        return 0.125 * h * h * self.rho / self.mu


register(Model(TaitFluid, stress_tait_fluid, energy_tait_fluid, wave_speed_tait_fluid))
