"""Drucker-Prager plasticity (soils, granular materials) at finite strain, in the frame of
materials/von_mises.py: the multiplicative split, Hencky elasticity and a return in the
principal logarithmic strains of the trial elastic be. The return is that of de Souza Neto,
Peric & Owen (Computational Methods for Plasticity, 2008, Box 8.9: smooth cone, then apex)
with constant cohesion.

Yield function and flow potential (tension positive, p = tr(tau)/3, J2 of dev tau):
    f = sqrt(J2) + eta p - xi c,        g = sqrt(J2) + eta_bar p,
matched to Mohr-Coulomb in plane strain (de Souza Neto et al., eq. 6.121: the cone that
gives the Mohr-Coulomb limit loads of plane-strain problems under associative flow):
    eta = 3 tan(phi) / sqrt(9 + 12 tan^2(phi)),   xi = 3 / sqrt(9 + 12 tan^2(phi)),
    eta_bar the same with the dilatancy angle psi (psi = phi: associative; 0: no plastic
volume change, the default). With trial state (s_t, p_t) and f_t > 0:
  cone:  dgamma = f_t / (G + K eta eta_bar),  sqrt(J2) = sqrt(J2_t) - G dgamma,
         p = p_t - K eta_bar dgamma   (valid while sqrt(J2_t) - G dgamma >= 0);
  apex:  s = 0, p = xi c / eta  (the tip of the cone: a cohesionless material carries no
         tension; no stress at all once pulled apart).
The equivalent plastic strain (state[6]) accumulates the deviatoric plastic strain
sqrt(2/3) |dev de_p| = dgamma / sqrt(3) on the cone, (sqrt(J2_t))/(sqrt(3) G) at the
apex. State as von_mises (be, alpha, the flag of plastic flow, Fn); parameters
``[G, K, rho0, c, eta, xi, eta_bar, sigma_t]`` (sigma_t = -1: no cut-off).

Tension cut-off (optional `tensile_strength` sigma_t, 0 <= sigma_t <= c cot(phi) = xi c / eta,
the apex; default: the apex itself, the cone alone): a second yield surface
    f_t = p - sigma_t <= 0        (p = tr(tau)/3, tension positive: pressure >= -sigma_t),
associative (flow potential p: a purely volumetric plastic strain dgamma_t 1/3), the
vertical cut of the cone in the (p, sqrt(J2)) plane. The return is a two-surface return
(multisurface plasticity with Koiter's flow rule, both consistency conditions enforced at a
corner, de Souza Neto et al. 2008, ch. 6 and the corner returns of ch. 8; the trial states
split by the flow directions through the corner as in Clausen, Damkilde & Andersen 2007,
"An efficient return algorithm for non-associated plasticity with linear yield criteria
in principal stress space", Computers & Structures 85, 1795), closed form because Hencky
elasticity moves (p, sqrt(J2)) linearly with the multipliers. With the corner C = (sigma_t, r_c),
r_c = xi c - eta sigma_t >= 0 (sqrt(J2) of the cone at p = sigma_t), and
dgamma_c = (sqrt(J2_t) - r_c) / G, dgamma_t = (p_t - sigma_t - K eta_bar dgamma_c) / K
(the two multipliers that bring the trial state to C):
  cut-off: p_t > sigma_t, sqrt(J2_t) <= r_c:  p = sigma_t, s = s_t, dgamma_t = (p_t - sigma_t)/K;
  corner:  dgamma_c >= 0 and dgamma_t >= 0:     p = sigma_t, sqrt(J2) = r_c;
  cone:    otherwise, if f_t > 0, the return above (it then lands at p <= sigma_t, so the
           apex is never reached: sigma_t <= xi c / eta).
These are exhaustive and exclusive: a trial state with sqrt(J2_t) > r_c reaches p <= sigma_t
by the cone's return exactly when dgamma_t <= 0 (G (p_t - sigma_t) <= K eta_bar
(sqrt(J2_t) - r_c)). In Kirchhoff stress, like the cone (Cauchy = Kirchhoff / J). With
sigma_t = xi c / eta (r_c = 0) the corner is the apex and the stress is the cone-and-apex
return's. The cut-off's flow is volumetric: alpha (deviatoric) grows only by dgamma_c /
sqrt(3) at the corner; the dissipation p dgamma_t = sigma_t dgamma_t >= 0.
"""
import math
from dataclasses import dataclass
from typing import ClassVar, Optional

from ..errors import ConfigError
from ..jit import njit
from .base import check_dim
from .registry import Model, register
from .tensor import hencky_split, hencky_trial, store_return
from .von_mises import HenckyPlastic, wave_speed_hencky_plastic

DRUCKER_PRAGER = 8


def plane_strain_match(angle_degrees):
    """(eta, xi) of the Drucker-Prager cone matched to Mohr-Coulomb in plane strain for a
    friction (or dilatancy) angle in degrees (module docstring)."""
    t = math.tan(math.radians(angle_degrees))
    r = math.sqrt(9.0 + 12.0 * t * t)
    return 3.0 * t / r, 3.0 / r


@njit(inline="always")
def stress_drucker_prager(F, L, dt, state, par, sigma):
    """Return map and Cauchy stress of the module docstring; updates `state`."""
    G = par[0]
    K = par[1]
    c = par[3]
    eta = par[4]
    xi = par[5]
    eta_bar = par[6]
    sigma_t = par[7]
    e, V, be, plane = hencky_trial(F, state)
    ev, m, d0, d1, d2 = hencky_split(e)
    p = K * ev
    root_j2 = math.sqrt(2.0) * G * math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)  # |2 G dev e|/sqrt 2
    f = root_j2 + eta * p - xi * c
    if sigma_t >= 0.0 and (p > sigma_t or f > 0.0):
        # with the tension cut-off (module docstring): cut-off, corner, or cone
        r_c = max(xi * c - eta * sigma_t, 0.0)  # (round-off below 0 at sigma_t = the apex)
        dg_c = (root_j2 - r_c) / G
        dg_t = (p - sigma_t - K * eta_bar * dg_c) / K
        scale = 1.0
        if p > sigma_t and root_j2 <= r_c:  # onto the cut-off: the deviator kept
            p = sigma_t
        elif dg_c >= 0.0 and dg_t >= 0.0:  # onto the corner
            scale = r_c / root_j2
            p = sigma_t
            state[6] += dg_c / math.sqrt(3.0)
        else:  # onto the cone (f > 0 here: the trial is outside and not beyond the cut)
            dgamma = f / (G + K * eta * eta_bar)
            scale = 1.0 - G * dgamma / root_j2
            p -= K * eta_bar * dgamma
            state[6] += dgamma / math.sqrt(3.0)
        d0 *= scale
        d1 *= scale
        d2 *= scale
        store_return(F, V, be, plane, p, G, p / (3.0 * K), d0, d1, d2, True, state, sigma)
        return
    if f > 0.0:
        dgamma = f / (G + K * eta * eta_bar)
        if root_j2 - G * dgamma >= 0.0:  # onto the smooth cone
            scale = 1.0 - G * dgamma / root_j2 if root_j2 > 0.0 else 0.0
            p -= K * eta_bar * dgamma
            state[6] += dgamma / math.sqrt(3.0)
        else:  # onto the apex
            scale = 0.0
            p = xi * c / eta if eta > 0.0 else p
            state[6] += root_j2 / (math.sqrt(3.0) * G)
        d0 *= scale
        d1 *= scale
        d2 *= scale
        m = p / (3.0 * K)
    store_return(F, V, be, plane, p, G, m, d0, d1, d2, f > 0.0, state, sigma)


@njit(fastmath=False)
def energy_drucker_prager(F, state, par):
    """psi = K/2 (tr e)^2 + G |dev e|^2 at the stored plastic state, per unit reference
    volume (no hardening: the plastic work is all dissipated)."""
    G = par[0]
    K = par[1]
    e, _, _, _ = hencky_trial(F, state)
    ev, _, d0, d1, d2 = hencky_split(e)
    return 0.5 * K * ev * ev + G * (d0 * d0 + d1 * d1 + d2 * d2)


@dataclass(frozen=True)
class DruckerPrager(HenckyPlastic):
    """Drucker-Prager plasticity (module docstring): E, nu, rho, `friction_angle` and
    `dilatancy_angle` in degrees (0 <= psi <= phi < 90; psi default 0), `cohesion` (>= 0,
    default 0), `tensile_strength` (the tension cut-off sigma_t in Pa, 0 <= sigma_t <=
    c cot(phi); default None: the cone's apex, no separate cut-off)."""

    friction_angle: float
    cohesion: float = 0.0
    dilatancy_angle: float = 0.0
    tensile_strength: Optional[float] = None
    type_code: ClassVar[int] = DRUCKER_PRAGER
    model: ClassVar[str] = "drucker_prager"
    required: ClassVar[tuple] = ("E", "nu", "rho", "friction_angle")
    optional: ClassVar[tuple] = ("cohesion", "dilatancy_angle", "tensile_strength")

    def __post_init__(self):
        super().__post_init__()
        if not 0.0 <= self.friction_angle < 90.0:
            raise ConfigError("friction_angle", "must be in [0, 90) degrees, got "
                              f"{self.friction_angle!r}")
        if not 0.0 <= self.dilatancy_angle <= self.friction_angle:
            raise ConfigError("dilatancy_angle", "must be in [0, friction_angle] degrees, "
                              f"got {self.dilatancy_angle!r}")
        if not self.cohesion >= 0.0:
            raise ConfigError("cohesion", f"must be >= 0, got {self.cohesion!r}")
        if self.friction_angle == 0.0 and self.cohesion == 0.0:
            raise ConfigError("cohesion", "a material without friction needs a cohesion > 0 "
                              "(it would carry no shear stress)")
        if self.tensile_strength is not None:
            st = self.tensile_strength
            apex = (self.cohesion / math.tan(math.radians(self.friction_angle))
                    if self.friction_angle > 0.0 else math.inf)
            if not 0.0 <= st <= apex * (1.0 + 1e-12):
                raise ConfigError("tensile_strength", "must be in [0, cohesion cot("
                                  f"friction_angle)] = [0, {apex:.6g}] (the cone's apex, "
                                  f"above which the cone itself cuts tension off), got {st!r}")

    def params(self, dim):
        check_dim(dim)
        eta, xi = plane_strain_match(self.friction_angle)
        eta_bar, _ = plane_strain_match(self.dilatancy_angle)
        sigma_t = -1.0 if self.tensile_strength is None else self.tensile_strength
        if eta > 0.0:  # not above the apex xi c / eta (the check allowed round-off)
            sigma_t = min(sigma_t, xi * self.cohesion / eta)
        return self._vector(self.mu, self.bulk, self.rho, self.cohesion, eta, xi, eta_bar,
                            sigma_t)


register(Model(DruckerPrager, stress_drucker_prager, energy_drucker_prager,
               wave_speed_hencky_plastic))
