"""Material registry: validated Python-side material objects and their parameter vectors.

The compiled constitutive kernels live in `elastic`, `maxwell`, `fluid` and are selected per
particle by `dispatch.compute_stress` / `dispatch.strain_energy` / `dispatch.wave_speed`
through the integer `type_code`.  This module does not import numba.

Every material object has ``type_code``, ``state_size``, ``model`` (canonical name),
``params(dim)`` (float64 vector of length NPAR = 8, ``params[2]`` is always rho0),
``initial_state()``, ``rho0``, ``sound_speed(dim=3)`` (at rest, for the CFL condition) and
``max_stable_viscous_dt(h)`` (``inf`` unless an explicit viscous limit applies).

`material_from_table(table, key, dim)` builds one from a TOML table such as
``{model = "neo_hookean", E = 1e5, nu = 0.3, rho = 1500}`` and raises
``ConfigError(f"{key}.<field>", reason)`` on invalid input.
"""
import math
import numbers
from dataclasses import dataclass, fields
from typing import ClassVar

import numpy as np

from ..errors import ConfigError
from .codes import (HARTMANN_NEFF, LINEAR_ELASTIC, MAX_STATE_SIZE, MAXWELL, NEO_HOOKEAN, NPAR,
                    PAR_RHO0, STVK, TAIT_FLUID, TYPE_NAMES)

__all__ = ["LinearElastic", "StVenantKirchhoff", "NeoHookean", "HartmannNeff", "Maxwell",
           "TaitFluid", "MODELS", "MODEL_NAMES", "material_from_table", "NPAR", "PAR_RHO0",
           "MAX_STATE_SIZE", "LINEAR_ELASTIC", "STVK", "NEO_HOOKEAN", "HARTMANN_NEFF", "MAXWELL",
           "TAIT_FLUID", "TYPE_NAMES"]


def _check_dim(dim):
    if dim not in (1, 2, 3):
        raise ValueError(f"dim must be 1, 2 or 3, got {dim!r}")


def _positive(name, value, what):
    if not value > 0:
        raise ConfigError(name, f"{what} must be > 0, got {value!r}")


def _poisson(name, value):
    if not value < 0.5:
        raise ConfigError(name, f"Poisson ratio must be < 0.5, got {value!r}")
    if not value > -1.0:
        raise ConfigError(name, f"Poisson ratio must be > -1, got {value!r}")


def _isfinite(v):
    """math.isfinite that takes integers beyond the float range (TOML's) as not finite."""
    try:
        return math.isfinite(v)
    except OverflowError:
        return False


def _short(v):
    text = repr(v)
    return text if len(text) <= 40 else f"{text[:20]}...({len(text)} characters)"


def _finite_numbers(obj):
    for f in fields(obj):
        v = getattr(obj, f.name)
        if not isinstance(v, numbers.Real) or isinstance(v, bool):
            raise ConfigError(f.name, f"expected a number, got {v!r}")
        if not _isfinite(v):
            raise ConfigError(f.name, f"must be a finite number, got {_short(v)}")


class _Material:
    """Methods shared by all materials (the dataclasses below add fields and `params`)."""

    state_size: ClassVar[int] = 0

    @property
    def rho0(self):
        return float(self.rho)

    def initial_state(self):
        return np.zeros(self.state_size, dtype=np.float64)

    def max_stable_viscous_dt(self, h):
        """Explicit viscous time-step limit for spacing `h` (inf: no such limit)."""
        return math.inf

    def _vector(self, *values):
        par = np.zeros(NPAR, dtype=np.float64)
        par[:len(values)] = values
        return par


class _IsotropicElastic(_Material):
    """Common part of the (E, nu, rho) solids.

    Parameter vector: ``[lambda, mu, rho0, E, nu, 0, 0, 0]`` with the Lame constants
    lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).  For ``dim == 1`` the body is
    a uniaxial-stress bar: lambda = 0, mu = E/2 (so sigma_xx = E eps for small strain; nu is
    ignored in 1D)."""

    def __post_init__(self):
        _finite_numbers(self)
        _positive("E", self.E, "Young's modulus")
        _poisson("nu", self.nu)
        _positive("rho", self.rho, "density")

    @property
    def lam(self):
        return self.E * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu))

    @property
    def mu(self):
        return self.E / (2.0 * (1.0 + self.nu))

    def params(self, dim):
        _check_dim(dim)
        if dim == 1:
            return self._vector(0.0, 0.5 * self.E, self.rho, self.E, self.nu)
        return self._vector(self.lam, self.mu, self.rho, self.E, self.nu)

    def sound_speed(self, dim=3):
        """Longitudinal wave speed at rest: sqrt((lambda + 2 mu)/rho), in 1D sqrt(E/rho)."""
        m = self.E if dim == 1 else self.lam + 2.0 * self.mu
        return math.sqrt(m / self.rho)


@dataclass(frozen=True)
class LinearElastic(_IsotropicElastic):
    """Small-strain linear elasticity, sigma = lambda tr(eps) I + 2 G eps (seed 000, eq. 3.11),
    eps = sym(F) - I.  Parameters: see `_IsotropicElastic` (``[lambda, mu, rho0, E, nu, 0...]``)."""

    E: float
    nu: float
    rho: float
    type_code: ClassVar[int] = LINEAR_ELASTIC
    model: ClassVar[str] = "linear_elastic"


@dataclass(frozen=True)
class StVenantKirchhoff(_IsotropicElastic):
    """St Venant-Kirchhoff, S = lambda tr(E) I + 2 mu E (seed 003, eq. 46).
    Parameters ``[lambda, mu, rho0, E, nu, 0, 0, 0]`` (1D: lambda = 0, mu = E/2)."""

    E: float
    nu: float
    rho: float
    type_code: ClassVar[int] = STVK
    model: ClassVar[str] = "stvk"


@dataclass(frozen=True)
class NeoHookean(_IsotropicElastic):
    """Neo-Hookean, sigma = mu/J (F F^T - I) + lambda/J ln J I (seed 003, eq. 47).
    Parameters ``[lambda, mu, rho0, E, nu, 0, 0, 0]`` (1D: lambda = 0, mu = E/2)."""

    E: float
    nu: float
    rho: float
    type_code: ClassVar[int] = NEO_HOOKEAN
    model: ClassVar[str] = "neo_hookean"


class _ShearBulk(_Material):
    """Common part of the (mu, k) solids; parameters ``[mu, k, rho0, eta, 0, 0, 0, 0]``
    (eta only for Maxwell).  In 1D (F = diag(F_xx, 1, 1)) these models describe uniaxial
    *strain*, with small-strain modulus k + 4/3 mu."""

    def _check_common(self):
        _finite_numbers(self)
        _positive("mu", self.mu, "shear modulus")
        _positive("k", self.k, "bulk modulus")
        _positive("rho", self.rho, "density")

    def sound_speed(self, dim=3):
        """sqrt((k + 4/3 mu)/rho) (seed 004, section 5)."""
        return math.sqrt((self.k + 4.0 / 3.0 * self.mu) / self.rho)

    @classmethod
    def from_E_nu(cls, E, nu, rho, **kw):
        """mu = E / (2 (1 + nu)), k = E / (3 (1 - 2 nu))."""
        return cls(mu=E / (2.0 * (1.0 + nu)), k=E / (3.0 * (1.0 - 2.0 * nu)), rho=rho, **kw)


@dataclass(frozen=True)
class HartmannNeff(_ShearBulk):
    """Neo-Hookean with the Hartmann-Neff volumetric part (seed 004, eqs. 10-12):
    tau = mu dev(B-bar) + k/10 (J^5 - J^-5) 1.  Parameters ``[mu, k, rho0, 0, 0, 0, 0, 0]``.
    Also constructible from (E, nu) via `from_E_nu` or the table keys E, nu."""

    mu: float
    k: float
    rho: float
    type_code: ClassVar[int] = HARTMANN_NEFF
    model: ClassVar[str] = "hartmann_neff"

    def __post_init__(self):
        self._check_common()

    def params(self, dim):
        _check_dim(dim)
        return self._vector(self.mu, self.k, self.rho)


@dataclass(frozen=True)
class Maxwell(_ShearBulk):
    """Finite-strain Maxwell body (Simo-Miehe; seed 004, eqs. 13-17) with the Hartmann-Neff
    potential.  Parameters ``[mu, k, rho0, eta, 0, 0, 0, 0]``; state: C_i as
    ``[xx, yy, zz, xy, yz, xz]``, initially the identity.  The update of eq. 16 is
    unconditionally stable, so there is no viscous time-step limit."""

    mu: float
    k: float
    eta: float
    rho: float
    type_code: ClassVar[int] = MAXWELL
    model: ClassVar[str] = "maxwell"
    state_size: ClassVar[int] = 6

    def __post_init__(self):
        self._check_common()
        _positive("eta", self.eta, "viscosity")

    def params(self, dim):
        _check_dim(dim)
        return self._vector(self.mu, self.k, self.rho, self.eta)

    def initial_state(self):
        return np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0], dtype=np.float64)


@dataclass(frozen=True)
class TaitFluid(_Material):
    """Compressible Newtonian fluid with the Tait equation of state (seed 003, eqs. 48-50):
    sigma = 2 mu [d - tr(d)/3 I] - p I, p = kappa [(rho/rho0)^gamma - 1].
    Parameters ``[kappa, gamma, rho0, mu, 0, 0, 0, 0]`` (mu: dynamic shear viscosity)."""

    rho: float
    kappa: float
    gamma: float = 7.0
    mu: float = 0.0
    type_code: ClassVar[int] = TAIT_FLUID
    model: ClassVar[str] = "tait_fluid"

    def __post_init__(self):
        _finite_numbers(self)
        _positive("rho", self.rho, "density")
        _positive("kappa", self.kappa, "bulk modulus")
        _positive("gamma", self.gamma, "Tait exponent")
        if not self.mu >= 0:
            raise ConfigError("mu", f"viscosity must be >= 0, got {self.mu!r}")

    def params(self, dim):
        _check_dim(dim)
        return self._vector(self.kappa, self.gamma, self.rho, self.mu)

    def sound_speed(self, dim=3):
        """sqrt(dp/drho) at rho = rho0: sqrt(kappa gamma / rho0)."""
        return math.sqrt(self.kappa * self.gamma / self.rho)

    def max_stable_viscous_dt(self, h):
        """Explicit viscous diffusion limit dt <= 0.125 h^2 rho0 / mu (inf if mu = 0)."""
        if self.mu == 0:
            return math.inf
        return 0.125 * h * h * self.rho / self.mu


#: every accepted model name (canonical names and aliases) -> class
MODELS = {
    "linear_elastic": LinearElastic,
    "stvk": StVenantKirchhoff,
    "st_venant_kirchhoff": StVenantKirchhoff,
    "neo_hookean": NeoHookean,
    "hartmann_neff": HartmannNeff,
    "maxwell": Maxwell,
    "tait": TaitFluid,
    "tait_fluid": TaitFluid,
    "newtonian_fluid": TaitFluid,
}

#: canonical names, in type-code order
MODEL_NAMES = tuple(TYPE_NAMES[c] for c in sorted(TYPE_NAMES))

# required and optional table fields per class (besides "model")
_REQUIRED = {
    LinearElastic: ("E", "nu", "rho"),
    StVenantKirchhoff: ("E", "nu", "rho"),
    NeoHookean: ("E", "nu", "rho"),
    HartmannNeff: ("mu", "k", "rho"),
    Maxwell: ("mu", "k", "eta", "rho"),
    TaitFluid: ("rho", "kappa"),
}
_OPTIONAL = {TaitFluid: ("gamma", "mu")}


def _valid_models_text():
    return ", ".join(MODELS)


def material_from_table(table, key, dim):
    """Build a material from the TOML table at dotted path `key` for a `dim`-D run.

    Hartmann-Neff and Maxwell accept either (mu, k) or (E, nu).  Errors are
    ``ConfigError(f"{key}.<field>", reason)`` (``ConfigError(key, ...)`` if not a table)."""
    _check_dim(dim)
    if not isinstance(table, dict):
        raise ConfigError(key, f"expected a table, got {type(table).__name__}")
    if "model" not in table:
        raise ConfigError(f"{key}.model",
                          f"required value is missing; valid models: {_valid_models_text()}")
    name = table["model"]
    if not isinstance(name, str) or name not in MODELS:
        raise ConfigError(f"{key}.model",
                          f"unknown model {name!r}; valid models: {_valid_models_text()}")
    cls = MODELS[name]
    required = list(_REQUIRED[cls])
    optional = list(_OPTIONAL.get(cls, ()))
    use_E_nu = cls in (HartmannNeff, Maxwell) and ("E" in table or "nu" in table)
    if use_E_nu:
        for f in ("mu", "k"):
            if f in table:
                raise ConfigError(f"{key}.{f}", "give either (mu, k) or (E, nu), not both")
        required = ["E", "nu"] + [f for f in required if f not in ("mu", "k")]
    allowed = set(required) | set(optional) | {"model"}
    for f in table:
        if f not in allowed:
            raise ConfigError(f"{key}.{f}", f"unknown key for model {name!r}; allowed: "
                              f"{', '.join(required + optional)}")
    values = {}
    for f in required + optional:
        if f not in table:
            if f in optional:
                continue
            raise ConfigError(f"{key}.{f}", f"required value is missing for model {name!r}")
        v = table[f]
        if not isinstance(v, numbers.Real) or isinstance(v, bool):
            raise ConfigError(f"{key}.{f}", f"expected a number, got {v!r}")
        if not _isfinite(v):
            raise ConfigError(f"{key}.{f}", f"must be a finite number, got {_short(v)}")
        values[f] = float(v)
    try:
        if use_E_nu:
            E = values.pop("E")
            nu = values.pop("nu")
            _positive("E", E, "Young's modulus")
            _poisson("nu", nu)
            mat = cls.from_E_nu(E, nu, **values)
        else:
            mat = cls(**values)
    except ConfigError as e:
        raise ConfigError(f"{key}.{e.key}", e.reason) from None
    # finite inputs can still overflow (E = 1e308, nu near 0.5, rho = 1e-320): the time step
    # would be zero or NaN, so the run could never advance
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        try:
            speed = mat.sound_speed(dim)
        except (OverflowError, ZeroDivisionError):
            speed = math.inf
        par = mat.params(dim)
    if not (np.all(np.isfinite(par)) and math.isfinite(speed) and speed > 0):
        stiff = next(f for f in required if f in ("E", "mu", "kappa"))
        raise ConfigError(f"{key}.{stiff}", f"out of range for this model: with "
                          f"{', '.join(f'{f} = {table[f]!r}' for f in required)} its moduli or "
                          f"wave speed are not finite numbers ({speed!r})")
    return mat
