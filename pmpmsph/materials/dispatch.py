"""Per-particle switch on the material type code, generated from the material registry
(`pmpmsph.materials.registry`) and called from the MPM and SPH kernels.

  compute_stress(mtype, F, L, dt, state, par, sigma)   Cauchy stress (may update state)
  strain_energy(mtype, F, state, par)                   stored energy per reference volume
  wave_speed(mtype, par, J)                             longitudinal (sound) speed at J

Each is an `if mtype == code: return law(...)` chain over the registered models
(`jit.code_switch`). An unknown code gives a NaN stress / energy / wave speed,
which the callers' NaN checks report. The laws' own docstrings give their equations.

The switches are inlined into the calling kernel at the Numba IR level
(``inline="always"``): as a plain call, the reference counting of the five array views
costs about as much as the stress update of the simple models (measured 20-40 ns per
particle saved by inlining).

`compute_stress_tagged` / `strain_energy_tagged` take a compile-time tag instead when
every particle of a kernel call has one type (`material_tag`): the Numba overloads below
pick that model while *typing* the caller, so only its code is compiled and inlined (a
runtime switch over all the models, inlined in a particle loop, cost ~4x the stress
update itself and multiplied compile time).
"""
import numpy as np
from numba.extending import overload

from ..jit import code_switch, njit
from . import registry

__all__ = ["compute_stress", "compute_stress_tagged", "material_tag", "strain_energy",
           "strain_energy_tagged", "wave_speed", "wave_speed_tagged"]

_MODELS = registry.models()


@njit(inline="always")
def _nan_stress(sigma):
    for i in range(3):
        for j in range(3):
            sigma[i, j] = np.nan


_STRESS_BY_CODE = {m.code: m.stress for m in _MODELS}
_ENERGY_BY_CODE = {m.code: m.energy for m in _MODELS}

compute_stress = code_switch("compute_stress", "F, L, dt, state, par, sigma", _STRESS_BY_CODE,
                             "_nan_stress(sigma)", _nan_stress=_nan_stress)
strain_energy = code_switch("strain_energy", "F, state, par", _ENERGY_BY_CODE,
                            "return np.nan", np=np)
_SPEED_BY_CODE = {m.code: m.wave_speed for m in _MODELS}
wave_speed = code_switch("wave_speed", "par, J", _SPEED_BY_CODE, "return np.nan", np=np)


def material_tag(codes):
    """Compile-time tag for the `_tagged` entry points: one type code -> (0,)*(code+1),
    else ()."""
    codes = set(int(c) for c in codes)
    return (0,) * (codes.pop() + 1) if len(codes) == 1 else ()


def compute_stress_tagged(mtag, mtype, F, L, dt, state, par, sigma):
    """`compute_stress` with the type fixed at compile time when `mtag` is not empty
    (module doc). This Python body is what runs under NUMBA_DISABLE_JIT=1."""
    if len(mtag) == 0:
        compute_stress(mtype, F, L, dt, state, par, sigma)
    else:
        _STRESS_BY_CODE[len(mtag) - 1](F, L, dt, state, par, sigma)


@overload(compute_stress_tagged, inline="always")
def _compute_stress_tagged_typed(mtag, mtype, F, L, dt, state, par, sigma):
    count = len(mtag.types)
    if count == 0:
        def switch(mtag, mtype, F, L, dt, state, par, sigma):
            compute_stress(mtype, F, L, dt, state, par, sigma)
        return switch
    model = _STRESS_BY_CODE[count - 1]

    def fixed(mtag, mtype, F, L, dt, state, par, sigma):
        model(F, L, dt, state, par, sigma)
    return fixed


def strain_energy_tagged(mtag, mtype, F, state, par):
    """`strain_energy` with the type fixed at compile time when `mtag` is not empty (as
    `compute_stress_tagged`). This body runs under NUMBA_DISABLE_JIT=1."""
    if len(mtag) == 0:
        return strain_energy(mtype, F, state, par)
    return _ENERGY_BY_CODE[len(mtag) - 1](F, state, par)


@overload(strain_energy_tagged, inline="always")
def _strain_energy_tagged_typed(mtag, mtype, F, state, par):
    count = len(mtag.types)
    if count == 0:
        def switch(mtag, mtype, F, state, par):
            return strain_energy(mtype, F, state, par)
        return switch
    model = _ENERGY_BY_CODE[count - 1]

    def fixed(mtag, mtype, F, state, par):
        return model(F, state, par)
    return fixed


def wave_speed_tagged(mtag, mtype, par, J):
    """`wave_speed` with the type fixed at compile time when `mtag` is not empty (as
    `compute_stress_tagged`). This body runs under NUMBA_DISABLE_JIT=1."""
    if len(mtag) == 0:
        return wave_speed(mtype, par, J)
    return _SPEED_BY_CODE[len(mtag) - 1](par, J)


@overload(wave_speed_tagged, inline="always")
def _wave_speed_tagged_typed(mtag, mtype, par, J):
    count = len(mtag.types)
    if count == 0:
        def switch(mtag, mtype, par, J):
            return wave_speed(mtype, par, J)
        return switch
    model = _SPEED_BY_CODE[count - 1]

    def fixed(mtag, mtype, par, J):
        return model(par, J)
    return fixed
