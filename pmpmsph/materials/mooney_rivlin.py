"""Compressible Mooney-Rivlin solid (Mooney 1940, Rivlin 1948; the decoupled form of
Holzapfel, Nonlinear Solid Mechanics, 2000, eqs. 6.145 and 6.148-6.149):

    psi   = C10 (I1-bar - 3) + C01 (I2-bar - 3) + k/2 (J - 1)^2
    tau   = 2 dev[(C10 + C01 I1-bar) B-bar - C01 B-bar^2] + k J (J - 1) 1,  sigma = tau / J

with B-bar = J^(-2/3) F F^T, I1-bar = tr B-bar, I2-bar = (I1-bar^2 - tr B-bar^2)/2. The
small-strain shear modulus is mu = 2 (C10 + C01), the bulk modulus k; C01 = 0 is a
neo-Hookean solid. Stateless. Parameter vector ``[C10, C01, rho0, k, 0, 0, 0, 0]``. In 1D
(F = diag(F_xx, 1, 1)) it describes uniaxial strain, as the other (mu, k) solids do.

Wave speed (CFL): in uniaxial strain F = diag(J, 1, 1), sigma_xx = 4/3 g(J) + k (J - 1)
with g = (J^(1/3) - J^(-5/3)) (C10 + C01 J^(-2/3)), so c^2 = J^2 (4/3 g'(J) + k)/rho0,
never below the at-rest (k + 4/3 mu)/rho0.

This module is the whole of the model: the kernels below, its configuration class and its
registration (`pmpmsph.materials.registry`).
"""
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..errors import ConfigError
from ..jit import njit
from .base import Material, check_dim, finite_numbers, positive
from .registry import Model, register
from .tensor import det3, inv_cbrt_sq, left_cauchy_green, max_keep_nan, store_sym

MOONEY_RIVLIN = 6


@njit(inline="always")
def _isochoric_b(F):
    """J and B-bar = J^(-2/3) F F^T as a 6-tuple."""
    J = det3(F)
    s = inv_cbrt_sq(J)
    bxx, byy, bzz, bxy, byz, bxz = left_cauchy_green(F)
    return J, s * bxx, s * byy, s * bzz, s * bxy, s * byz, s * bxz


@njit(inline="always")
def stress_mooney_rivlin(F, L, dt, state, par, sigma):
    """Cauchy stress of the module docstring."""
    c10 = par[0]
    c01 = par[1]
    k = par[3]
    J, bxx, byy, bzz, bxy, byz, bxz = _isochoric_b(F)
    # B-bar^2
    qxx = bxx * bxx + bxy * bxy + bxz * bxz
    qyy = bxy * bxy + byy * byy + byz * byz
    qzz = bxz * bxz + byz * byz + bzz * bzz
    qxy = bxx * bxy + bxy * byy + bxz * byz
    qyz = bxy * bxz + byy * byz + byz * bzz
    qxz = bxx * bxz + bxy * byz + bxz * bzz
    a = c10 + c01 * (bxx + byy + bzz)
    xx = a * bxx - c01 * qxx
    yy = a * byy - c01 * qyy
    zz = a * bzz - c01 * qzz
    m = (xx + yy + zz) * (1.0 / 3.0)
    r = 2.0 / J
    p = k * (J - 1.0)
    store_sym(sigma, r * (xx - m) + p, r * (yy - m) + p, r * (zz - m) + p,
              r * (a * bxy - c01 * qxy), r * (a * byz - c01 * qyz), r * (a * bxz - c01 * qxz))


@njit(fastmath=False)
def energy_mooney_rivlin(F, state, par):
    """psi of the module docstring, per unit reference volume."""
    c10 = par[0]
    c01 = par[1]
    k = par[3]
    J, bxx, byy, bzz, bxy, byz, bxz = _isochoric_b(F)
    i1 = bxx + byy + bzz
    tr_b2 = bxx * bxx + byy * byy + bzz * bzz + 2.0 * (bxy * bxy + byz * byz + bxz * bxz)
    i2 = 0.5 * (i1 * i1 - tr_b2)
    return c10 * (i1 - 3.0) + c01 * (i2 - 3.0) + 0.5 * k * (J - 1.0) * (J - 1.0)


@njit(inline="always")
def wave_speed_mooney_rivlin(par, J):
    """Longitudinal speed in uniaxial strain (module docstring)."""
    c10 = par[0]
    c01 = par[1]
    k = par[3]
    m0 = k + 8.0 / 3.0 * (c10 + c01)
    c = np.cbrt(J)
    jm23 = 1.0 / (c * c)  # J^(-2/3)
    jm53 = jm23 / J       # J^(-5/3)
    # g'(J) = (J^(-2/3)/3 + 5/3 J^(-8/3)) (C10 + C01 J^(-2/3))
    #         - 2/3 C01 J^(-5/3) (J^(1/3) - J^(-5/3))
    dg = (((1.0 / 3.0) * jm23 + (5.0 / 3.0) * jm53 / J) * (c10 + c01 * jm23)
          - (2.0 / 3.0) * c01 * jm53 * (c - jm53))
    m = J * J * (4.0 / 3.0 * dg + k)
    return np.sqrt(max_keep_nan(m0, m) / par[2])


@dataclass(frozen=True)
class MooneyRivlin(Material):
    """Compressible Mooney-Rivlin solid (module docstring): C10, C01, bulk modulus k, rho."""

    C10: float
    C01: float
    k: float
    rho: float
    type_code: ClassVar[int] = MOONEY_RIVLIN
    model: ClassVar[str] = "mooney_rivlin"
    required: ClassVar[tuple] = ("C10", "C01", "k", "rho")
    stiffness: ClassVar[str] = "C10"

    def __post_init__(self):
        finite_numbers(self)
        if not self.C10 + self.C01 > 0:
            raise ConfigError("C10", "the shear modulus 2 (C10 + C01) must be > 0, got "
                              f"C10 = {self.C10!r}, C01 = {self.C01!r}")
        positive("k", self.k, "bulk modulus")
        positive("rho", self.rho, "density")

    @property
    def mu(self):
        return 2.0 * (self.C10 + self.C01)

    def params(self, dim):
        check_dim(dim)
        return self._vector(self.C10, self.C01, self.rho, self.k)

    def sound_speed(self, dim=3):
        """sqrt((k + 4/3 mu)/rho) at rest."""
        return math.sqrt((self.k + 4.0 / 3.0 * self.mu) / self.rho)


register(Model(MooneyRivlin, stress_mooney_rivlin, energy_mooney_rivlin,
               wave_speed_mooney_rivlin))
