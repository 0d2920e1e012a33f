"""Typed access to one TOML table that knows its dotted key path, for exact error messages.

Every getter validates and raises `ConfigError(key, reason)`; `finish()` rejects keys that no
getter asked for, so a misspelt key is an error rather than silently ignored.
"""
import difflib
import numbers

from ..errors import ConfigError, did_you_mean, is_finite
from ..errors import short_repr as _short

_MISSING = object()


def _is_number(v):
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


class Table:
    def __init__(self, data, path):
        if not isinstance(data, dict):
            raise ConfigError(path or "<root>", f"expected a table, got {type(data).__name__}")
        self.data = data
        self.path = path
        self.used = set()
        self.asked = set()  # every name a getter or `has` looked for: the section's keys

    def key(self, name):
        return f"{self.path}.{name}" if self.path else name

    def has(self, name):
        self.asked.add(name)
        return name in self.data

    def raw(self, name, default=_MISSING):
        self.used.add(name)
        self.asked.add(name)
        if name not in self.data:
            if default is _MISSING:
                unasked = [k for k in self.data if k not in self.asked]
                close = difflib.get_close_matches(name, unasked, n=1)
                hint = f" (is {close[0]!r} a misspelling of it?)" if close else ""
                raise ConfigError(self.key(name), "required value is missing" + hint)
            return default
        return self.data[name]

    def sub(self, name, default=_MISSING):
        v = self.raw(name, default)
        if v is None:
            return None
        return Table(v, self.key(name))

    def subs(self, name):
        """An array of tables (``[[name]]``), possibly absent (empty list)."""
        v = self.raw(name, [])
        if not isinstance(v, list):
            raise ConfigError(self.key(name), "expected an array of tables ([[...]])")
        return [Table(item, f"{self.key(name)}[{i}]") for i, item in enumerate(v)]

    def number(self, name, default=_MISSING, *, min=None, max=None, min_open=None,
               max_open=None, integer=False):
        if name not in self.data and default is not _MISSING:
            self.used.add(name)
            self.asked.add(name)
            return default
        v = self.raw(name)
        k = self.key(name)
        if not _is_number(v):
            raise ConfigError(k, f"expected a number, got {_short(v)}")
        if not is_finite(v):
            raise ConfigError(k, f"must be finite, got {_short(v)}")
        if integer:
            if int(v) != v:
                raise ConfigError(k, f"expected a whole number, got {_short(v)}")
            v = int(v)
        if min is not None and v < min:
            raise ConfigError(k, f"must be >= {min}, got {_short(v)}")
        if min_open is not None and v <= min_open:
            raise ConfigError(k, f"must be > {min_open}, got {_short(v)}")
        if max is not None and v > max:
            raise ConfigError(k, f"must be <= {max}, got {_short(v)}")
        if max_open is not None and v >= max_open:
            raise ConfigError(k, f"must be < {max_open}, got {_short(v)}")
        return v

    def vector(self, name, length, default=_MISSING, *, positive=False, integer=False,
               scalar_ok=False):
        """A list of `length` numbers (a single number too if `scalar_ok`)."""
        if name not in self.data and default is not _MISSING:
            self.used.add(name)
            self.asked.add(name)
            return default
        v = self.raw(name)
        k = self.key(name)
        if scalar_ok and _is_number(v):
            v = [v] * length
        if not isinstance(v, (list, tuple)) or len(v) != length:
            raise ConfigError(k, f"expected a list of {length} numbers, got {_short(v)}")
        out = []
        for i, item in enumerate(v):
            if not _is_number(item) or not is_finite(item):
                raise ConfigError(f"{k}[{i}]", f"expected a finite number, got {_short(item)}")
            if integer:
                if int(item) != item:
                    raise ConfigError(f"{k}[{i}]", f"expected a whole number, got {_short(item)}")
                item = int(item)
            if positive and item <= 0:
                raise ConfigError(f"{k}[{i}]", f"must be > 0, got {_short(item)}")
            out.append(item)
        return tuple(out)

    def string(self, name, default=_MISSING, *, choices=None):
        if name not in self.data and default is not _MISSING:
            self.used.add(name)
            self.asked.add(name)
            return default
        v = self.raw(name)
        k = self.key(name)
        if not isinstance(v, str):
            raise ConfigError(k, f"expected a string, got {_short(v)}")
        if choices is not None and v not in choices:
            raise ConfigError(k, f"unknown value {_short(v)}{did_you_mean(v, choices)}; "
                                 f"choose one of {', '.join(sorted(choices))}")
        return v

    def boolean(self, name, default=_MISSING):
        v = self.raw(name, default)
        if not isinstance(v, bool):
            raise ConfigError(self.key(name), f"expected true or false, got {_short(v)}")
        return v

    def finish(self):
        extra = [k for k in self.data if k not in self.used]
        if extra:
            known = self.asked
            raise ConfigError(self.key(extra[0]), "unknown key" + did_you_mean(extra[0], known))

