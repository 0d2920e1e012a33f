"""A body's initial `velocity` and `stress` (docs/initial_fields.md): one vector, or per
component a number or an expression of the particle position (config/expressions.py), or
from the Python API a function f(x) -> (n, size) array.

A case that gives only numbers keeps its plain tuple of floats (`BodySpec.velocity` as it
always was); anything else is an `InitialField`, evaluated once where the body is seeded
(initial_particles.py). A restart reads the stored particles and never uses it.
"""
import numbers
from dataclasses import dataclass
from typing import Any, Callable, Optional

import numpy as np

from ..errors import ConfigError, is_finite
from ..errors import short_repr as _short
from .expressions import Expression, allowed_names, parse


@dataclass(frozen=True)
class InitialField:
    """Per-component numbers and `Expression`s, or one function of the positions."""
    size: int
    components: tuple = ()              # float | Expression, `size` of them
    function: Optional[Callable[[np.ndarray], Any]] = None

    def values(self, x, key):
        """(n, size) float64 values at the positions x (n, dim); a ConfigError at
        `key[c]` (`key` for a function) where a value is not finite."""
        n = len(x)
        if self.function is not None:
            out = np.asarray(self.function(np.array(x, np.float64)), np.float64)
            if out.shape != (n, self.size):
                raise ConfigError(key, f"the function returned an array of shape "
                                  f"{out.shape}, expected (n, {self.size}) = ({n}, {self.size})")
            out = out.copy()
        else:
            out = np.empty((n, self.size))
            for c, comp in enumerate(self.components):
                out[:, c] = comp.evaluate(x) if isinstance(comp, Expression) else comp
        bad = ~np.isfinite(out)
        if bad.any():
            c = int(np.argmax(bad.any(axis=0)))
            rows = np.flatnonzero(bad[:, c])
            at = ", ".join(f"{v:.6g}" for v in x[rows[0]])
            where = key if self.function is not None else f"{key}[{c}]"
            what = f"component {c} " if self.function is not None else ""
            raise ConfigError(where, f"{what}value is not finite at {len(rows)} of {n} "
                              f"particles (e.g. at ({at})): log or sqrt of a negative "
                              "number, log(0), a division by zero or an overflow")
        return out


def field_values(spec, x, key):
    """(n, size) values of a `BodySpec` velocity or stress (a tuple or an `InitialField`)."""
    if isinstance(spec, InitialField):
        return spec.values(x, key)
    return np.tile(np.asarray(spec, np.float64), (len(x), 1))


def _is_number(v):
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def read_field(t, name, size, dim, default):
    """`name` of the table `t`: a list of `size` numbers or expression strings (or, from
    Python, a function). Only numbers: a tuple of floats; else an `InitialField`."""
    if not t.has(name):
        t.raw(name, default)  # (marks it read)
        return default
    raw = t.raw(name)
    key = t.key(name)
    if callable(raw):
        return InitialField(size, function=raw)
    names = ", ".join(allowed_names(dim)[:dim])
    if not isinstance(raw, (list, tuple)) or len(raw) != size:
        raise ConfigError(key, f"expected a list of {size} numbers or expressions of "
                          f"{names}, got {_short(raw)}")
    comps = []
    for i, item in enumerate(raw):
        if isinstance(item, str):
            try:
                comps.append(parse(item, dim))
            except ValueError as exc:
                raise ConfigError(f"{key}[{i}]", str(exc)) from None
        elif _is_number(item) and is_finite(item):
            comps.append(float(item))
        else:
            raise ConfigError(f"{key}[{i}]", f"expected a finite number or an expression "
                              f"string (e.g. \"0.5 * {names[0]}\"), got {_short(item)}")
    if not any(isinstance(c, Expression) for c in comps):
        return tuple(comps)
    return InitialField(size, components=tuple(comps))


def voigt_tensors(values, dim):
    """(n, 3, 3) symmetric tensors from (n, k) Voigt rows (xx; xx yy xy; xx yy zz yz xz xy)."""
    pairs = {1: [(0, 0)], 2: [(0, 0), (1, 1), (0, 1)],
             3: [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]}[dim]
    out = np.zeros((len(values), 3, 3))
    for k, (i, j) in enumerate(pairs):
        out[:, i, j] = values[:, k]
        out[:, j, i] = values[:, k]
    return out
