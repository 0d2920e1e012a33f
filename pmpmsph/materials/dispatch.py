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

`compute_stress_tagged` / `strain_energy_tagged` / `wave_speed_tagged` take a compile-time
tag of the *set* of models a kernel call meets (`material_tag`): the Numba overloads below
read the set while typing the caller and inline the switch over those models only (one
model: its law, no switch). A runtime switch over every registered model, inlined in a
particle loop, costs ~4x the stress update itself and multiplies compile time: G2P with
all eleven models took 300-480 s to compile, 64 % of the test suite's compile time on a
cold cache (tests/conftest.py's compile log, 2026-11-28); over the two models of a float
it takes a few seconds. An empty tag still means the switch over every model.
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
    """Compile-time tag of the set of type codes `codes`: one tuple (0,)*(code+1) per code
    present, in code order (its type carries the codes: Numba types a tuple of tuples of
    different lengths as a tuple of their lengths)."""
    return tuple((0,) * (code + 1) for code in sorted(set(int(c) for c in codes)))


def _tag_codes(mtag):
    """The type codes a typed `material_tag` stands for (empty: every model)."""
    return tuple(t.count - 1 for t in mtag.types)


_TABLES = {"stress": (_STRESS_BY_CODE, "F, L, dt, state, par, sigma", compute_stress),
           "energy": (_ENERGY_BY_CODE, "F, state, par", strain_energy),
           "speed": (_SPEED_BY_CODE, "par, J", wave_speed)}
_SUBSET_SWITCHES = {}


def _switch_over(kind, mtag):
    """The compiled `f(code, args)` of `kind` ('stress', 'energy', 'speed') over the models
    of the typed tag `mtag`: the switch over every model for an empty tag, else over the
    tag's models only, with no test for the last (one model: its law, called directly).
    Generated once per set and process, inlined into its callers."""
    table, args, every = _TABLES[kind]
    codes = _tag_codes(mtag)
    if not codes:
        return every
    key = (kind, codes)
    if key not in _SUBSET_SWITCHES:
        name = f"{kind}_over_" + "_".join(str(c) for c in codes)
        _SUBSET_SWITCHES[key] = code_switch(name, args, {c: table[c] for c in codes}, None)
    return _SUBSET_SWITCHES[key]


def compute_stress_tagged(mtag, mtype, F, L, dt, state, par, sigma):
    """`compute_stress` over the models of `mtag` only, chosen at compile time (module doc).
    This Python body is what runs under NUMBA_DISABLE_JIT=1."""
    compute_stress(mtype, F, L, dt, state, par, sigma)


@overload(compute_stress_tagged, inline="always")
def _compute_stress_tagged_typed(mtag, mtype, F, L, dt, state, par, sigma):
    switch = _switch_over("stress", mtag)

    def impl(mtag, mtype, F, L, dt, state, par, sigma):
        switch(mtype, F, L, dt, state, par, sigma)
    return impl


def strain_energy_tagged(mtag, mtype, F, state, par):
    """`strain_energy` over the models of `mtag` only (as `compute_stress_tagged`). This
    body runs under NUMBA_DISABLE_JIT=1."""
    return strain_energy(mtype, F, state, par)


@overload(strain_energy_tagged, inline="always")
def _strain_energy_tagged_typed(mtag, mtype, F, state, par):
    switch = _switch_over("energy", mtag)

    def impl(mtag, mtype, F, state, par):
        return switch(mtype, F, state, par)
    return impl


def wave_speed_tagged(mtag, mtype, par, J):
    """`wave_speed` over the models of `mtag` only (as `compute_stress_tagged`). This body
    runs under NUMBA_DISABLE_JIT=1."""
    return wave_speed(mtype, par, J)


@overload(wave_speed_tagged, inline="always")
def _wave_speed_tagged_typed(mtag, mtype, par, J):
    switch = _switch_over("speed", mtag)

    def impl(mtag, mtype, par, J):
        return switch(mtype, par, J)
    return impl
