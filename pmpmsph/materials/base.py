"""What every material's configuration class shares: the checks of its table values, its
parameter vector, and the parsing of a `[materials.NAME]` table (`material_from_table`).

A law's configuration class (a frozen dataclass in its own module, registered there) sets
the class attributes

    model        canonical name in a case file;     aliases   other accepted names
    type_code    the integer the kernels switch on (stable: restart files keep it)
    required     table keys that must be given;     optional  keys that may be
    stiffness    the key an out-of-range error names (the modulus that sets the wave speed)
    accepts_E_nu (mu, k) may be given as (E, nu) instead
    fluid        a fluid: SPH integrates its continuity density, not F (a trait)
    state_size   length of its per-particle internal state
    plastic      a plasticity model: state[6] is the equivalent plastic strain and state[7]
                 the flag of plastic flow in the last update (a trait; io/derived_fields.py)

and defines `params(dim)`, a float64 vector of length NPAR with rho0 at PAR_RHO0, and
`sound_speed(dim)` at rest. Plain Python (no numba).
"""
import math
import numbers
from dataclasses import dataclass, fields
from typing import ClassVar

import numpy as np

from ..errors import ConfigError, did_you_mean, is_finite
from ..errors import short_repr as _short
from .codes import NPAR


def check_dim(dim):
    if dim not in (1, 2, 3):
        raise ValueError(f"dim must be 1, 2 or 3, got {dim!r}")


def positive(name, value, what):
    if not value > 0:
        raise ConfigError(name, f"{what} must be > 0, got {value!r}")


def poisson(name, value):
    if not value < 0.5:
        raise ConfigError(name, f"Poisson ratio must be < 0.5, got {value!r}")
    if not value > -1.0:
        raise ConfigError(name, f"Poisson ratio must be > -1, got {value!r}")


def finite_numbers(obj):
    for f in fields(obj):
        v = getattr(obj, f.name)
        if v is None and f.default is None:  # an optional value not given
            continue
        if not isinstance(v, numbers.Real) or isinstance(v, bool):
            raise ConfigError(f.name, f"expected a number, got {v!r}")
        if not is_finite(v):
            raise ConfigError(f.name, f"must be a finite number, got {_short(v)}")


class Material:
    """Methods shared by all materials (the dataclasses of the law modules add fields,
    `params` and `sound_speed`)."""

    aliases: ClassVar[tuple] = ()
    optional: ClassVar[tuple] = ()
    accepts_E_nu: ClassVar[bool] = False
    fluid: ClassVar[bool] = False
    state_size: ClassVar[int] = 0
    plastic: ClassVar[bool] = False

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


@dataclass(frozen=True)
class IsotropicElastic(Material):
    """Common part of the (E, nu, rho) solids (their fields, checks and parameters).

    Parameter vector: ``[lambda, mu, rho0, E, nu, 0, 0, 0]`` with the Lame constants
    lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).  For ``dim == 1`` the body is
    a uniaxial-stress bar: lambda = 0, mu = E/2 (so sigma_xx = E eps for small strain; nu is
    ignored in 1D)."""

    E: float
    nu: float
    rho: float
    required: ClassVar[tuple] = ("E", "nu", "rho")
    stiffness: ClassVar[str] = "E"

    def __post_init__(self):
        finite_numbers(self)
        positive("E", self.E, "Young's modulus")
        poisson("nu", self.nu)
        positive("rho", self.rho, "density")

    @property
    def lam(self):
        return self.E * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu))

    @property
    def mu(self):
        return self.E / (2.0 * (1.0 + self.nu))

    def params(self, dim):
        check_dim(dim)
        if dim == 1:
            return self._vector(0.0, 0.5 * self.E, self.rho, self.E, self.nu)
        return self._vector(self.lam, self.mu, self.rho, self.E, self.nu)

    def sound_speed(self, dim=3):
        """Longitudinal wave speed at rest: sqrt((lambda + 2 mu)/rho), in 1D sqrt(E/rho)."""
        m = self.E if dim == 1 else self.lam + 2.0 * self.mu
        return math.sqrt(m / self.rho)


class ShearBulk(Material):
    """Common part of the (mu, k) solids; parameters ``[mu, k, rho0, eta, 0, 0, 0, 0]``
    (eta only for Maxwell).  In 1D (F = diag(F_xx, 1, 1)) these models describe uniaxial
    *strain*, with small-strain modulus k + 4/3 mu."""

    accepts_E_nu: ClassVar[bool] = True
    stiffness: ClassVar[str] = "mu"

    def _check_common(self):
        finite_numbers(self)
        positive("mu", self.mu, "shear modulus")
        positive("k", self.k, "bulk modulus")
        positive("rho", self.rho, "density")

    def sound_speed(self, dim=3):
        """sqrt((k + 4/3 mu)/rho) (seed 004, section 5)."""
        return math.sqrt((self.k + 4.0 / 3.0 * self.mu) / self.rho)

    @classmethod
    def from_E_nu(cls, E, nu, rho, **kw):
        """mu = E / (2 (1 + nu)), k = E / (3 (1 - 2 nu))."""
        return cls(mu=E / (2.0 * (1.0 + nu)), k=E / (3.0 * (1.0 - 2.0 * nu)), rho=rho, **kw)


def material_from_table(table, key, dim, models):
    """Build a material from the TOML table at dotted path `key` for a `dim`-D run;
    `models` maps every accepted name to its class (`pmpmsph.materials.MODELS`).

    Classes with `accepts_E_nu` take either (mu, k) or (E, nu).  Errors are
    ``ConfigError(f"{key}.<field>", reason)`` (``ConfigError(key, ...)`` if not a table)."""
    check_dim(dim)
    valid = ", ".join(models)
    if not isinstance(table, dict):
        raise ConfigError(key, f"expected a table, got {type(table).__name__}")
    if "model" not in table:
        raise ConfigError(f"{key}.model", f"required value is missing; valid models: {valid}")
    name = table["model"]
    if not isinstance(name, str) or name not in models:
        raise ConfigError(f"{key}.model", f"unknown model {name!r}{did_you_mean(name, models)}; "
                          f"valid models: {valid}")
    cls = models[name]
    required = list(cls.required)
    optional = list(cls.optional)
    use_E_nu = cls.accepts_E_nu and ("E" in table or "nu" in table)
    if use_E_nu:
        for f in ("mu", "k"):
            if f in table:
                raise ConfigError(f"{key}.{f}", "give either (mu, k) or (E, nu), not both")
        required = ["E", "nu"] + [f for f in required if f not in ("mu", "k")]
    allowed = set(required) | set(optional) | {"model"}
    for f in table:
        if f not in allowed:
            raise ConfigError(f"{key}.{f}", f"unknown key for model {name!r}"
                              f"{did_you_mean(f, allowed)}; allowed: "
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
        if not is_finite(v):
            raise ConfigError(f"{key}.{f}", f"must be a finite number, got {_short(v)}")
        values[f] = float(v)
    try:
        if use_E_nu:
            E = values.pop("E")
            nu = values.pop("nu")
            positive("E", E, "Young's modulus")
            poisson("nu", nu)
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
        stiff = "E" if use_E_nu else cls.stiffness
        raise ConfigError(f"{key}.{stiff}", f"out of range for this model: with "
                          f"{', '.join(f'{f} = {table[f]!r}' for f in required)} its moduli or "
                          f"wave speed are not finite numbers ({speed!r})")
    return mat
