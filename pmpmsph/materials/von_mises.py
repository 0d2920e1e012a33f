"""J2 (von Mises) plasticity with linear isotropic hardening at finite strain: the
multiplicative split F = Fe Fp, the logarithmic (Hencky) elastic strain and the exponential
return map of Simo (1992, "Algorithms for static and dynamic multiplicative plasticity that
preserve the classical return mapping schemes of the infinitesimal theory", CMAME 99) and
Simo & Hughes (Computational Inelasticity, 1998, Box 9.1).

State (``STATE_SIZE = 7``): the inverse plastic right Cauchy-Green tensor Cp^-1 = Fp^-1
Fp^-T as ``[xx, yy, zz, xy, yz, xz]`` (initially the identity) and the equivalent plastic
strain alpha. Parameters ``[G, K, rho0, yield stress, H, 0, 0, 0]``: shear and bulk moduli
(from E and nu), the initial yield stress sigma_y and the hardening modulus H.

One call of `stress_von_mises` with the updated F (the trial state is that of the last
step, so every call starts again from it: the caller stores the state once per step):
1. trial elastic left Cauchy-Green tensor be = F Cp^-1 F^T, its eigen-pairs (lambda_i, n_i)
   and logarithmic strains e_i = ln(lambda_i)/2 (Simo 1992, eq. 4.7);
2. Hencky energy psi = K/2 (tr e)^2 + G |dev e|^2 + H alpha^2/2, Kirchhoff stress
   tau = K tr e 1 + 2 G dev e, coaxial with be;
3. yield function f = q - (sigma_y + H alpha), q = sqrt(3/2) |dev tau| (the Mises stress of
   tau); if f > 0 the radial return of the small-strain theory, exact in these
   variables: dgamma = f / (3 G + H), dev e scaled by 1 - 3 G dgamma / q, alpha += dgamma
   (Simo & Hughes, Box 9.1, steps 3-4);
4. sigma = tau / J; be = sum exp(2 e_i) n_i n_i^T and Cp^-1 = F^-1 be F^-T stored.
The plastic flow keeps det Cp = 1 (tr of the return's increment is 0), so tr e = ln J.

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
from .tensor import cofactor3, det3, store_sym

STATE_SIZE = 7
VON_MISES = 7
#: Jacobi sweeps at most (cyclic Jacobi converges quadratically: 3-5 in practice)
_SWEEPS = 12


@njit(inline="always")
def _rotation(app, aqq, apq):
    """(c, s, a_pp', a_qq') of the Jacobi rotation that zeroes a_pq (Numerical Recipes,
    section 11.1, eqs. 11.1.8-11.1.14)."""
    if apq == 0.0:
        return 1.0, 0.0, app, aqq
    theta = (aqq - app) / (2.0 * apq)
    t = 1.0 / (abs(theta) + math.sqrt(theta * theta + 1.0))
    if theta < 0.0:
        t = -t
    c = 1.0 / math.sqrt(t * t + 1.0)
    return c, t * c, app - t * apq, aqq + t * apq


@njit(inline="always")
def sym_eigen(xx, yy, zz, xy, yz, xz):
    """Eigenvalues (w0, w1, w2) and eigenvectors (the columns of V, row-major 9-tuple) of a
    symmetric 3x3 matrix by cyclic Jacobi rotations, to round-off."""
    a00, a11, a22, a01, a12, a02 = xx, yy, zz, xy, yz, xz
    v00, v01, v02, v10, v11, v12, v20, v21, v22 = 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0
    for _ in range(_SWEEPS):
        off = a01 * a01 + a02 * a02 + a12 * a12
        if not off > 1e-36 * (a00 * a00 + a11 * a11 + a22 * a22):
            break
        # (p, q) = (0, 1), r = 2
        c, s, a00, a11 = _rotation(a00, a11, a01)
        a01 = 0.0
        a02, a12 = c * a02 - s * a12, s * a02 + c * a12
        v00, v01 = c * v00 - s * v01, s * v00 + c * v01
        v10, v11 = c * v10 - s * v11, s * v10 + c * v11
        v20, v21 = c * v20 - s * v21, s * v20 + c * v21
        # (0, 2), r = 1
        c, s, a00, a22 = _rotation(a00, a22, a02)
        a02 = 0.0
        a01, a12 = c * a01 - s * a12, s * a01 + c * a12
        v00, v02 = c * v00 - s * v02, s * v00 + c * v02
        v10, v12 = c * v10 - s * v12, s * v10 + c * v12
        v20, v22 = c * v20 - s * v22, s * v20 + c * v22
        # (1, 2), r = 0
        c, s, a11, a22 = _rotation(a11, a22, a12)
        a12 = 0.0
        a01, a02 = c * a01 - s * a02, s * a01 + c * a02
        v01, v02 = c * v01 - s * v02, s * v01 + c * v02
        v11, v12 = c * v11 - s * v12, s * v11 + c * v12
        v21, v22 = c * v21 - s * v22, s * v21 + c * v22
    return (a00, a11, a22), (v00, v01, v02, v10, v11, v12, v20, v21, v22)


@njit(inline="always")
def congruence(a, s):
    """A S A^T as (xx, yy, zz, xy, yz, xz) for A a row-major 9-tuple and S symmetric
    (xx, yy, zz, xy, yz, xz)."""
    sxx, syy, szz, sxy, syz, sxz = s
    m00 = a[0] * sxx + a[1] * sxy + a[2] * sxz
    m01 = a[0] * sxy + a[1] * syy + a[2] * syz
    m02 = a[0] * sxz + a[1] * syz + a[2] * szz
    m10 = a[3] * sxx + a[4] * sxy + a[5] * sxz
    m11 = a[3] * sxy + a[4] * syy + a[5] * syz
    m12 = a[3] * sxz + a[4] * syz + a[5] * szz
    m20 = a[6] * sxx + a[7] * sxy + a[8] * sxz
    m21 = a[6] * sxy + a[7] * syy + a[8] * syz
    m22 = a[6] * sxz + a[7] * syz + a[8] * szz
    return (m00 * a[0] + m01 * a[1] + m02 * a[2],
            m10 * a[3] + m11 * a[4] + m12 * a[5],
            m20 * a[6] + m21 * a[7] + m22 * a[8],
            m00 * a[3] + m01 * a[4] + m02 * a[5],
            m10 * a[6] + m11 * a[7] + m12 * a[8],
            m00 * a[6] + m01 * a[7] + m02 * a[8])


@njit(inline="always")
def _trial_strains(F, state):
    """Principal logarithmic elastic strains of the trial state (step 1) and their
    directions V."""
    f = (F[0, 0], F[0, 1], F[0, 2], F[1, 0], F[1, 1], F[1, 2], F[2, 0], F[2, 1], F[2, 2])
    be = congruence(f, (state[0], state[1], state[2], state[3], state[4], state[5]))
    w, V = sym_eigen(be[0], be[1], be[2], be[3], be[4], be[5])
    return (0.5 * math.log(w[0]), 0.5 * math.log(w[1]), 0.5 * math.log(w[2])), V, f


@njit(inline="always")
def stress_von_mises(F, L, dt, state, par, sigma):
    """Return map and Cauchy stress of the module docstring (steps 1-4); updates `state`."""
    G = par[0]
    K = par[1]
    yield0 = par[3]
    H = par[4]
    e, V, f = _trial_strains(F, state)
    ev = e[0] + e[1] + e[2]
    m = ev * (1.0 / 3.0)
    d0, d1, d2 = e[0] - m, e[1] - m, e[2] - m
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
    J = det3(F)
    p = K * ev
    t = congruence(V, (p + 2.0 * G * d0, p + 2.0 * G * d1, p + 2.0 * G * d2, 0.0, 0.0, 0.0))
    r = 1.0 / J
    store_sym(sigma, r * t[0], r * t[1], r * t[2], r * t[3], r * t[4], r * t[5])
    if excess > 0.0:  # the new plastic state: Cp^-1 = F^-1 be F^-T
        be = congruence(V, (math.exp(2.0 * (m + d0)), math.exp(2.0 * (m + d1)),
                            math.exp(2.0 * (m + d2)), 0.0, 0.0, 0.0))
        c = cofactor3(F)  # F^-T = cof(F) / J, so F^-1 = cof(F)^T / J
        finv = (c[0] * r, c[3] * r, c[6] * r, c[1] * r, c[4] * r, c[7] * r,
                c[2] * r, c[5] * r, c[8] * r)
        cp = congruence(finv, be)
        for i in range(6):
            state[i] = cp[i]


@njit(fastmath=False)
def energy_von_mises(F, state, par):
    """psi = K/2 (tr e)^2 + G |dev e|^2 + H alpha^2 / 2 at the stored plastic state (no
    return), per unit reference volume."""
    G = par[0]
    K = par[1]
    H = par[4]
    e, _, _ = _trial_strains(F, state)
    ev = e[0] + e[1] + e[2]
    m = ev / 3.0
    dev2 = (e[0] - m) ** 2 + (e[1] - m) ** 2 + (e[2] - m) ** 2
    return 0.5 * K * ev * ev + G * dev2 + 0.5 * H * state[6] * state[6]


@njit(inline="always")
def wave_speed_von_mises(par, J):
    """The elastic longitudinal speed at rest (module docstring)."""
    return np.sqrt((par[1] + 4.0 / 3.0 * par[0]) / par[2])


@dataclass(frozen=True)
class VonMises(IsotropicElastic):
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
    state_size: ClassVar[int] = STATE_SIZE

    def __post_init__(self):
        super().__post_init__()
        if not self.yield_stress > 0:
            raise ConfigError("yield_stress", f"must be > 0, got {self.yield_stress!r}")
        if not self.hardening >= 0:
            raise ConfigError("hardening", f"must be >= 0, got {self.hardening!r}")

    @property
    def bulk(self):
        return self.E / (3.0 * (1.0 - 2.0 * self.nu))

    def params(self, dim):
        check_dim(dim)
        return self._vector(self.mu, self.bulk, self.rho, self.yield_stress, self.hardening)

    def sound_speed(self, dim=3):
        """sqrt((K + 4/3 G)/rho) in every dimension (1D is uniaxial strain here)."""
        return math.sqrt((self.bulk + 4.0 / 3.0 * self.mu) / self.rho)

    def initial_state(self):
        return np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0], dtype=np.float64)


register(Model(VonMises, stress_von_mises, energy_von_mises, wave_speed_von_mises))
