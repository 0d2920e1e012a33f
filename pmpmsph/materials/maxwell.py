"""Finite-strain Maxwell body of Simo & Miehe as used by Shutov & Klyuchantsev (seed 004,
eqs. 13-17), with the Hartmann-Neff neo-Hookean potential of eqs. 11-12.

State (``STATE_SIZE = 6``): the inelastic right Cauchy-Green tensor C_i = F_i^T F_i (eq. 13),
symmetric and unimodular, stored as ``[xx, yy, zz, xy, yz, xz]``; initially the identity.

Parameter vector (length NPAR = 8): ``[mu, k, rho0, eta, 0, 0, 0, 0]`` with shear modulus mu,
bulk modulus k and Newtonian viscosity eta.

One call of `stress_maxwell` with the updated F does:

1. the iteration-free update of eq. 16 (Shutov, Landgraf & Ihlemann):
   ``C_i^{n+1} = unimodular( C_i^n + (dt mu / eta) C-bar^{n+1} )``, where
   ``unimodular(X) = det(X)^(-1/3) X`` and ``C-bar = J^(-2/3) F^T F`` (eq. 14);
2. the stress of eqs. 14 and 17, ``sigma = F T F^T / J`` with
   ``T = mu C^-1 (C-bar C_i^-1)^D + k/10 (J^5 - J^-5) C^-1``.  Since
   ``F C^-1 (C-bar C_i^-1) F^T = J^(-2/3) F C_i^-1 F^T =: B-bar_e`` and
   ``tr(C-bar C_i^-1) = tr(B-bar_e)``, this equals exactly
   ``sigma = [mu dev(B-bar_e) + k/10 (J^5 - J^-5) 1] / J``, which is what is evaluated
   (no inverse of C needed, symmetric by construction).  With C_i = I it is the
   Hartmann-Neff model.

For dt = 0 (or eta -> infinity) a unimodular C_i is left unchanged.
"""
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..jit import njit
from .base import ShearBulk, check_dim, positive
from .elastic import wave_speed_hartmann_neff
from .registry import Model, register
from .tensor import (det3, hartmann_neff_cauchy, hartmann_neff_volumetric_energy,
                     inv_cbrt_sq, push_forward_sym, right_cauchy_green, sym_det, sym_inv)

STATE_SIZE = 6
MAXWELL = 4


@njit(inline="always")
def stress_maxwell(F, L, dt, state, par, sigma):
    """Update C_i in `state` by seed 004 eq. 16, then write sigma of eqs. 14 and 17."""
    mu = par[0]
    k = par[1]
    eta = par[3]
    J = det3(F)
    s = inv_cbrt_sq(J)
    cxx, cyy, czz, cxy, cyz, cxz = right_cauchy_green(F)
    # eq. 16: X = C_i^n + dt mu/eta C-bar^{n+1}; C_i^{n+1} = det(X)^(-1/3) X
    a = dt * mu / eta * s
    xx = state[0] + a * cxx
    yy = state[1] + a * cyy
    zz = state[2] + a * czz
    xy = state[3] + a * cxy
    yz = state[4] + a * cyz
    xz = state[5] + a * cxz
    u = 1.0 / np.cbrt(sym_det(xx, yy, zz, xy, yz, xz))
    xx *= u
    yy *= u
    zz *= u
    xy *= u
    yz *= u
    xz *= u
    state[0] = xx
    state[1] = yy
    state[2] = zz
    state[3] = xy
    state[4] = yz
    state[5] = xz
    # eq. 14/17 via B-bar_e = J^(-2/3) F C_i^-1 F^T
    ixx, iyy, izz, ixy, iyz, ixz = sym_inv(xx, yy, zz, xy, yz, xz)
    bxx, byy, bzz, bxy, byz, bxz = push_forward_sym(F, ixx, iyy, izz, ixy, iyz, ixz)
    hartmann_neff_cauchy(s * bxx, s * byy, s * bzz, s * bxy, s * byz, s * bxz, J, mu, k, sigma)


@njit(fastmath=False)
def energy_maxwell(F, state, par):
    """psi = mu/2 (tr(C-bar C_i^-1) - 3) + k/50 (J^5 + J^-5 - 2): the potential of eq. 12
    evaluated with the elastic part (the one whose derivative gives eq. 14) at the current,
    not updated, state."""
    mu = par[0]
    k = par[1]
    J = det3(F)
    cxx, cyy, czz, cxy, cyz, cxz = right_cauchy_green(F)
    ixx, iyy, izz, ixy, iyz, ixz = sym_inv(state[0], state[1], state[2],
                                           state[3], state[4], state[5])
    tr = (cxx * ixx + cyy * iyy + czz * izz
          + 2.0 * (cxy * ixy + cyz * iyz + cxz * ixz))
    return (0.5 * mu * (inv_cbrt_sq(J) * tr - 3.0)
            + hartmann_neff_volumetric_energy(np.log(J), k))


@dataclass(frozen=True)
class Maxwell(ShearBulk):
    """Finite-strain Maxwell body (Simo-Miehe; seed 004, eqs. 13-17) with the Hartmann-Neff
    potential.  Parameters ``[mu, k, rho0, eta, 0, 0, 0, 0]``; state: C_i as
    ``[xx, yy, zz, xy, yz, xz]``, initially the identity.  The update of eq. 16 is
    unconditionally stable, so there is no viscous time-step limit.  Its wave speed is the
    Hartmann-Neff one: the instantaneous response is bounded by the elastic one."""

    mu: float
    k: float
    eta: float
    rho: float
    type_code: ClassVar[int] = MAXWELL
    model: ClassVar[str] = "maxwell"
    required: ClassVar[tuple] = ("mu", "k", "eta", "rho")
    state_size: ClassVar[int] = STATE_SIZE

    def __post_init__(self):
        self._check_common()
        positive("eta", self.eta, "viscosity")

    def params(self, dim):
        check_dim(dim)
        return self._vector(self.mu, self.k, self.rho, self.eta)

    def initial_state(self):
        return np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0], dtype=np.float64)


register(Model(Maxwell, stress_maxwell, energy_maxwell, wave_speed_hartmann_neff))
