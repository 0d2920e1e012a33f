"""The material registry: the one place that knows which constitutive models exist.

A law's module ends with one line,

    register(Model(NeoHookean, stress_neo_hookean, energy_neo_hookean, wave_speed_neo_hookean))

which carries everything the rest of the program needs about it (after CB-Geo MPM's
`Factory::register_product`, include/factory.h): the configuration class (its `model` name
and aliases, its `type_code`, the table keys it reads, its checks, its parameter vector,
its traits `fluid` and `state_size`) and the three compiled functions (Cauchy stress,
stored energy, wave speed). From the registry are generated: the case file's choice list
(`pmpmsph.materials.MODELS`), the kernels' dispatch on the type code and its compile-time
specialisations (`pmpmsph.materials.dispatch`), the energy of the diagnostics
(`kernels.diagnostics`).

`models()` imports every module of this package that is not part of its machinery, so a
new material is one new file (and its test): nothing else lists the models.

Plain Python: importing this module does not import numba.
"""
from dataclasses import dataclass

from ..plugins import Registry

#: modules of the package that hold no law
_MACHINERY = {"registry", "base", "codes", "dispatch", "tensor"}


@dataclass(frozen=True)
class Model:
    """One constitutive model (module docstring).

    config: the configuration dataclass (`materials.base.Material` subclass);
    stress(F, L, dt, state, par, sigma): Cauchy stress into sigma (may update state);
    energy(F, state, par): stored energy per unit reference volume;
    wave_speed(par, J): longitudinal (sound) speed at the current J, for the time step."""

    config: type
    stress: object
    energy: object
    wave_speed: object

    @property
    def name(self):
        return self.config.model

    @property
    def code(self):
        return self.config.type_code


def names_of(model):
    """The canonical name and the aliases a case file may use for `model`."""
    return (model.name,) + tuple(model.config.aliases)


_MODELS = Registry("material type", __package__, __file__, _MACHINERY, names_of)
#: add a model (its type code and names must be new); the registered models in code order;
#: the model of a type code
register, models, model_of_code = _MODELS.register, _MODELS.entries, _MODELS.of_code
