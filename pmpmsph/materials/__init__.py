"""Constitutive models: the configuration classes the case file builds, and their kernels.

Each law lives in one module of this package (`elastic`, `maxwell`, `fluid`,
`mooney_rivlin`, ...): its compiled stress, energy and wave speed, its configuration
dataclass (table keys, checks, parameter vector, traits), and one `register(Model(...))`
line (`registry`). The compiled dispatch on the type code (`dispatch`) and the choice list
below are generated from the registry, so a new material is one new module.

Every material object has ``type_code``, ``state_size``, ``fluid``, ``model`` (canonical
name), ``params(dim)`` (float64 vector of length NPAR = 8, ``params[2]`` is always rho0),
``initial_state()``, ``rho0``, ``sound_speed(dim=3)`` (at rest, for the CFL condition) and
``max_stable_viscous_dt(h)`` (``inf`` unless an explicit viscous limit applies).

`material_from_table(table, key, dim)` builds one from a TOML table such as
``{model = "neo_hookean", E = 1e5, nu = 0.3, rho = 1500}`` and raises
``ConfigError(f"{key}.<field>", reason)`` on invalid input.
"""
from . import base, registry
from .codes import NPAR, PAR_RHO0
from .elastic import HartmannNeff, LinearElastic, NeoHookean, StVenantKirchhoff
from .fluid import TaitFluid
from .maxwell import Maxwell

__all__ = ["LinearElastic", "StVenantKirchhoff", "NeoHookean", "HartmannNeff", "Maxwell",
           "TaitFluid", "MODELS", "MODEL_NAMES", "material_from_table", "NPAR", "PAR_RHO0"]

#: every accepted model name (canonical names and aliases) -> class, in type-code order
MODELS = {name: m.config for m in registry.models() for name in registry.names_of(m)}

#: canonical names, in type-code order
MODEL_NAMES = tuple(m.name for m in registry.models())


def material_from_table(table, key, dim):
    """Build a material from the TOML table at dotted path `key` for a `dim`-D run
    (`materials.base.material_from_table` over the registered models)."""
    return base.material_from_table(table, key, dim, MODELS)
