"""The Python scene API: the same scene as a TOML file, built from code for scripting.

    scene = Scene(dimension=2, grid=dict(origin=[0, 0], length=[1, 1], cells=[20, 20]),
                  time=dict(end=1.0, cfl=0.5), gravity=[0, -9.81])
    scene.material("rubber", model="neo_hookean", E=1e3, nu=0.3, rho=1000)
    scene.body(name="disc", material="rubber", shape="disc", centre=[.5, .5], radius=.2, ppc=2)
    sim = scene.simulation()          # validated exactly like a TOML case
"""
import copy

from .config import case_from_dict


class Scene:
    def __init__(self, dimension, **sections):
        self.data = {"dimension": dimension, "materials": {}, "bodies": []}
        self.data.update(copy.deepcopy(sections))

    def material(self, name, **params):
        self.data["materials"][name] = params
        return self

    def body(self, **spec):
        self.data["bodies"].append(spec)
        return self

    def boundary(self, **spec):
        self.data.setdefault("boundaries", []).append(spec)
        return self

    def load(self, **spec):
        self.data.setdefault("loads", []).append(spec)
        return self

    def set(self, key, value):
        """Set a dotted key, e.g. ``scene.set("mpm.shape", "cubic")``."""
        from .config.load import apply_overrides

        apply_overrides(self.data, [(key, value)])
        return self

    def case(self, name="scene"):
        return case_from_dict(self.data, name=name)

    def simulation(self, **kwargs):
        from .simulation import Simulation

        return Simulation(self.case(), **kwargs)
