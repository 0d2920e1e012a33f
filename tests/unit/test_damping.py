"""Wave absorbers (`[[damping]]`, physics/damping.py): the case keys and their refusals, and
the damping law v <- v max(0, 1 - dt beta s^2) on the fluids' particles inside the zone
(Altomare et al. 2017, eq. 12), applied after the step."""
import numpy as np
import pytest

from pmpmsph import ConfigError, load_case_text
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.simulation import Simulation

WATER = """
dimension = 2
[grid]
origin = [0.0, 0.0]
length = [1.0, 0.5]
cells = [20, 10]
[materials.water]
model = "tait"
rho = 1000.0
kappa = 2.0e4
gamma = 7.0
[materials.rubber]
model = "neo_hookean"
E = 1.0e5
nu = 0.3
rho = 800.0
[[bodies]]
name = "water"
material = "water"
shape = "box"
min = [0.1, 0.1]
max = [0.9, 0.3]
ppc = 2
velocity = [0.5, 0.0]
[[bodies]]
name = "block"
material = "rubber"
shape = "box"
min = [0.6, 0.35]
max = [0.7, 0.45]
ppc = 2
velocity = [0.5, 0.0]
[[damping]]
box = { min = [0.5, 0.0], max = [1.0, 0.5] }
direction = "x+"
rate = 40.0
[time]
end = 0.1
dt = 1.0e-3
"""


def test_a_damping_zone_loads():
    case = load_case_text(WATER)
    (zone,) = case.damping
    assert zone.direction == "x+" and zone.rate == 40.0 and zone.region.lo == (0.5, 0.0)


@pytest.mark.parametrize("old,new,key,why", [
    ('direction = "x+"\n', "", "damping[0].direction", "required"),
    ('direction = "x+"', 'direction = "z+"', "damping[0].direction", "unknown value"),
    ("rate = 40.0", "rate = 0.0", "damping[0].rate", "> 0"),
    ("box = { min = [0.5, 0.0], max = [1.0, 0.5] }", 'face = "x+"', "damping[0].face",
     "inside a box"),
    ("max = [1.0, 0.5] }", "max = [0.5, 0.5] }", "damping[0].box.max", "no depth along x"),
    ("rate = 40.0", "rate = 40.0\nwidth = 1", "damping[0].width", "unknown key"),
    ('material = "water"', 'material = "rubber"', "damping[0]", "has none"),
])
def test_bad_damping_keys_name_themselves(old, new, key, why):
    assert old in WATER
    with pytest.raises(ConfigError) as err:
        load_case_text(WATER.replace(old, new, 1))
    assert err.value.key == key and why in str(err.value)


def test_the_fluid_in_the_zone_is_damped_by_the_law_and_nothing_else_is():
    """Water and a block moving uniformly at 0.5 m/s (no gravity: MPM carries a uniform motion
    unchanged, APIC's C stays 0), the zone over x >= 0.5 growing to 40/s at x = 1: after one
    step each water point inside it has v = 0.5 (1 - dt 40 s^2), s = (x - 0.5)/0.5 at its
    position after the step; the water outside and the block (not a fluid) keep 0.5."""
    sim = Simulation(load_case_text(WATER), dist=Distributor.serial(), write_output=False)
    sim.step()
    p = sim.particles
    n = p.n_owned
    x, v, body = p["x"][:n], p["v"][:n], p["body"][:n]
    s = np.clip((x[:, 0] - 0.5) / 0.5, 0.0, None)
    expected = np.where((body == 0) & (x[:, 0] >= 0.5), 0.5 * (1.0 - 1e-3 * 40.0 * s * s), 0.5)
    assert np.count_nonzero(expected < 0.5) > 50
    np.testing.assert_allclose(v[:, 0], expected, rtol=0, atol=1e-12)
    np.testing.assert_allclose(v[:, 1], 0.0, atol=1e-12)
