"""Output fields computed from the particle state when a snapshot is written (not stored,
not migrated): what a user looks at but no kernel needs.

    rho             mass / vol (when the scene has no density field of its own)
    pressure        -tr(sigma) / 3 (compression positive)
    mises           the von Mises stress sqrt(3/2) |dev sigma|
    plastic_strain  the equivalent plastic strain alpha of a plasticity model (0 elsewhere)
    yielding        1 where the last stress update flowed plastically, else 0 (uint8)

The last two read the state of the materials with the `plastic` trait (materials/base.py:
state[6] and state[7]); a scene without such a material does not offer them.
"""
import numpy as np


def _rho(p, n, case):
    return p["mass"][:n] / p["vol"][:n]


def _pressure(p, n, case):
    s = p["sigma"][:n]
    return -(s[:, 0, 0] + s[:, 1, 1] + s[:, 2, 2]) / 3.0


def _mises(p, n, case):
    s = p["sigma"][:n]
    mean = (s[:, 0, 0] + s[:, 1, 1] + s[:, 2, 2]) / 3.0
    dev = s.copy()
    for a in range(3):
        dev[:, a, a] -= mean
    return np.sqrt(1.5 * np.einsum("nij,nij->n", dev, dev))


def _plastic_rows(p, n, case):
    """Rows whose material has the `plastic` trait."""
    plastic = np.array([m.plastic for m in case.materials.values()], dtype=bool)
    return plastic[p["mat"][:n]]


def _state_entry(entry, dtype):
    def read(p, n, case):
        out = np.zeros(n, dtype)
        rows = _plastic_rows(p, n, case)
        out[rows] = p["mstate"][:n][rows, entry]
        return out
    return read


#: name -> (the particle fields it needs, whether it needs a plastic material, function)
DERIVED = {
    "rho": (("mass", "vol"), False, _rho),
    "pressure": (("sigma",), False, _pressure),
    "mises": (("sigma",), False, _mises),
    "plastic_strain": (("mstate",), True, _state_entry(6, np.float64)),
    "yielding": (("mstate",), True, _state_entry(7, np.uint8)),
}


def offered(case, particles):
    """The derived field names this scene can write."""
    plastic = any(m.plastic for m in case.materials.values())
    return [name for name, (needs, wants_plastic, _) in DERIVED.items()
            if all(k in particles for k in needs) and (plastic or not wants_plastic)]


def derived_field(name, particles, n, case):
    """The derived field `name` of the first `n` rows (module docstring)."""
    return DERIVED[name][2](particles, n, case)
