"""The Python scene API: the same scene as a TOML file, built from code for scripting.

    scene = Scene(dimension=2, grid=dict(origin=[0, 0], length=[1, 1], cells=[20, 20]),
                  time=dict(end=1.0, cfl=0.5), gravity=[0, -9.81])
    scene.material("rubber", model="neo_hookean", E=1e3, nu=0.3, rho=1000)
    scene.body(name="disc", material="rubber", shape="disc", centre=[.5, .5], radius=.2, ppc=2)
    sim = scene.simulation()          # validated exactly like a TOML case

A body's `velocity` and `stress` take, besides numbers, expression strings of the position
(`velocity=["-3*(y - 0.5)", "3*(x - 0.5)"]`) or a function f(x) of the (n, dim) seeded
positions returning (n, dim) (stress: (n, Voigt length)): docs/initial_fields.md.
"""
from __future__ import annotations

import copy
from typing import TYPE_CHECKING, Any

from .config import case_from_dict
from .config.load import apply_overrides

if TYPE_CHECKING:  # (annotations only: simulation imports the whole solver)
    from .config.case import Case
    from .simulation import Simulation


class Scene:
    """A case as nested dicts, with one method per repeated table (module docstring)."""

    def __init__(self, dimension: int, **sections: Any) -> None:
        self.data = {"dimension": dimension, "materials": {}, "bodies": []}
        self.data.update(copy.deepcopy(sections))

    def material(self, name: str, **params: Any) -> Scene:
        self.data["materials"][name] = params
        return self

    def body(self, **spec: Any) -> Scene:
        self.data["bodies"].append(spec)
        return self

    def boundary(self, **spec: Any) -> Scene:
        self.data.setdefault("boundaries", []).append(spec)
        return self

    def damping(self, **spec: Any) -> Scene:
        self.data.setdefault("damping", []).append(spec)
        return self

    def load(self, **spec: Any) -> Scene:
        self.data.setdefault("loads", []).append(spec)
        return self

    def set(self, key: str, value: Any) -> Scene:
        """Set a dotted key, e.g. ``scene.set("mpm.shape", "cubic")``."""
        apply_overrides(self.data, [(key, value)])
        return self

    def case(self, name: str = "scene") -> Case:
        return case_from_dict(self.data, name=name)

    def simulation(self, **kwargs: Any) -> Simulation:
        from .simulation import Simulation  # noqa: PLC0415 - keeps `import pmpmsph` free of the solver

        return Simulation(self.case(), **kwargs)
