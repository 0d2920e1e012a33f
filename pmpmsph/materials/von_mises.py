"""J2 (von Mises) plasticity with linear isotropic hardening at finite strain: the
multiplicative split F = Fe Fp, the logarithmic (Hencky) elastic strain and the exponential
return map of Simo (1992, "Algorithms for static and dynamic multiplicative plasticity that
preserve the classical return mapping schemes of the infinitesimal theory", CMAME 99) and
Simo & Hughes (Computational Inelasticity, 1998, Box 9.1).

State (``STATE_SIZE = 17``): the elastic left Cauchy-Green tensor be = Fe Fe^T as
``[xx, yy, zz, xy, yz, xz]`` (initially the identity), the equivalent plastic strain alpha,
a flag, 1 where the last stress update flowed plastically (the output fields
`plastic_strain` and `yielding`, io/derived_fields.py), and the F at which be was stored
(row-major, state[8:17]). Parameters ``[G, K, rho0, yield stress, H, 0, 0, 0]``: shear and
bulk moduli (from E and nu), the initial yield stress sigma_y and the hardening modulus H.

One call of `stress_von_mises` with the updated F (the trial state is that of the last
step, so every call starts again from it: the caller stores the state once per step):
1. trial elastic left Cauchy-Green tensor be_t = f be f^T with the relative deformation
   f = F Fn^-1 since the state was stored (Simo 1992, eq. 4.4; `tensor.hencky_trial` says
   why not F Cp^-1 F^T), its eigen-pairs (lambda_i, n_i) and logarithmic strains
   e_i = ln(lambda_i)/2 (Simo 1992, eq. 4.7);
2. Hencky energy psi = K/2 (tr e)^2 + G |dev e|^2 + H alpha^2/2, Kirchhoff stress
   tau = K tr e 1 + 2 G dev e, coaxial with be_t;
3. yield function f = q - (sigma_y + H alpha), q = sqrt(3/2) |dev tau| (the Mises stress of
   tau); if f > 0 the radial return of the small-strain theory, exact in these
   variables: dgamma = f / (3 G + H), dev e scaled by 1 - 3 G dgamma / q, alpha += dgamma
   (Simo & Hughes, Box 9.1, steps 3-4);
4. sigma = tau / J; be = sum exp(2 e_i) n_i n_i^T and Fn = F stored.
The plastic flow keeps det be = J^2 (tr of the return's increment is 0), so tr e = ln J.

In plane strain (2D) and uniaxial strain (1D) F has unit out-of-plane entries and the same
formulas apply (the out-of-plane plastic strain evolves). The wave speed for the time step
is the elastic one at rest, sqrt((K + 4/3 G)/rho0): plastic flow only softens.

This module is the whole of the model: the kernels below, its configuration class and its
registration (`pmpmsph.materials.registry`).
"""
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..errors import ConfigError
from ..jit import njit
from .base import IsotropicElastic, check_dim
from .registry import Model, register
from .tensor import hencky_split, hencky_trial, store_return

STATE_SIZE = 17
VON_MISES = 7


@njit(inline="always")
def stress_von_mises(F, L, dt, state, par, sigma):
    """Return map and Cauchy stress of the module docstring (steps 1-4); updates `state`."""
    G = par[0]
    K = par[1]
    yield0 = par[3]
    H = par[4]
    e, V, be, plane = hencky_trial(F, state)
    ev, m, d0, d1, d2 = hencky_split(e)
    q = math.sqrt(6.0) * G * math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)  # sqrt(3/2) |2 G dev e|
    alpha = state[6]
    excess = q - (yield0 + H * alpha)
    if excess > 0.0:
        dgamma = excess / (3.0 * G + H)
        scale = 1.0 - 3.0 * G * dgamma / q
        d0 *= scale
        d1 *= scale
        d2 *= scale
        state[6] = alpha + dgamma
    store_return(F, V, be, plane, K * ev, G, m, d0, d1, d2, excess > 0.0, state, sigma)


@njit(fastmath=False)
def energy_von_mises(F, state, par):
    """psi = K/2 (tr e)^2 + G |dev e|^2 + H alpha^2 / 2 at the stored plastic state (no
    return), per unit reference volume."""
    G = par[0]
    K = par[1]
    H = par[4]
    e, _, _, _ = hencky_trial(F, state)
    ev, _, d0, d1, d2 = hencky_split(e)
    dev2 = d0 * d0 + d1 * d1 + d2 * d2
    return 0.5 * K * ev * ev + G * dev2 + 0.5 * H * state[6] * state[6]


@njit(inline="always")
def wave_speed_hencky_plastic(par, J):
    """The elastic longitudinal speed at rest, sqrt((K + 4/3 G)/rho0) with G = par[0] and
    K = par[1] (module docstring; also drucker_prager's)."""
    return np.sqrt((par[1] + 4.0 / 3.0 * par[0]) / par[2])


@dataclass(frozen=True)
class HenckyPlastic(IsotropicElastic):
    """What the plasticity models in this frame share (E, nu, rho; parameters begin
    [G, K, rho0]): the state be = 1, alpha = 0, Fn = 1 at the start, and the elastic wave
    speed."""

    state_size: ClassVar[int] = STATE_SIZE
    plastic: ClassVar[bool] = True

    @property
    def bulk(self):
        return self.E / (3.0 * (1.0 - 2.0 * self.nu))

    def sound_speed(self, dim=3):
        """sqrt((K + 4/3 G)/rho) in every dimension (1D is uniaxial strain here)."""
        return math.sqrt((self.bulk + 4.0 / 3.0 * self.mu) / self.rho)

    def initial_state(self):
        state = np.zeros(STATE_SIZE)
        state[:3] = 1.0  # be
        state[8:17:4] = 1.0  # Fn
        return state


@dataclass(frozen=True)
class VonMises(HenckyPlastic):
    """J2 plasticity with linear isotropic hardening (module docstring): E, nu, rho, the
    initial yield stress (`yield_stress`, uniaxial) and the hardening modulus
    (`hardening`, d yield stress / d equivalent plastic strain; 0: perfectly plastic)."""

    yield_stress: float
    hardening: float = 0.0
    type_code: ClassVar[int] = VON_MISES
    model: ClassVar[str] = "von_mises"
    aliases: ClassVar[tuple] = ("j2",)
    required: ClassVar[tuple] = ("E", "nu", "rho", "yield_stress")
    optional: ClassVar[tuple] = ("hardening",)

    def __post_init__(self):
        super().__post_init__()
        if not self.yield_stress > 0:
            raise ConfigError("yield_stress", f"must be > 0, got {self.yield_stress!r}")
        if not self.hardening >= 0:
            raise ConfigError("hardening", f"must be >= 0, got {self.hardening!r} (softening "
                              "is not modelled: its tangent modulus E H / (E + H) is not "
                              "positive)")

    def params(self, dim):
        check_dim(dim)
        return self._vector(self.mu, self.bulk, self.rho, self.yield_stress, self.hardening)


register(Model(VonMises, stress_von_mises, energy_von_mises, wave_speed_hencky_plastic))
