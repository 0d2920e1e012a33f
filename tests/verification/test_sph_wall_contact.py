"""An SPH solid on dummy walls: the wall holds it and lets it slide without friction
(kernels/sph/rates.py, the contact of walls and SPH solids; issue 21, item 2).

Set-up: a neo-Hookean block (E = 2 MPa, nu = 0.3, rho = 2000) at spacing 0.005, Wendland
C2, predictor-corrector, released at rest on a floor of four rows of dummy wall particles,
under gravity tilted by theta (the floor is an incline). Reference: a block on a
frictionless incline accelerates at g sin theta along it and stays on it. The block's
centre-of-mass velocity along the floor is fitted linearly over 0.1 < t < 0.3 s.
Measured (this build): the acceleration within 5e-5 g sin theta at theta = 30 and 10 deg
(h = 1.3 spacings); the lowest particle within 0.01 spacings of its start. A block at rest
(theta = 0) 0.05 or 0.12 high, h = 1.3 or 2 spacings, stays within 0.004 spacings of its
start over 0.4 s. The block of tests/verification/test_sph_walls_solids.py left free (no
water, touching the right wall with its side, h = 2 spacings, E = 1e8) stays within 0.001
spacings of the floor over 0.2 s.
Before (the wall pushed with the solid's mean pressure, and the solid's kinematics did not
see the wall): the 30 deg block slid at 1.90 m/s^2 instead of 4.91 (the artificial
viscosity of the wall pairs it slid over held it like a friction of 0.35), the 10 deg block
did not slide at all and sank 5.5 mm (1.1 spacings) into the floor, and the free block of
the tank scene sank into the floor (docs/sph.md, "Walls and solids").
"""
import numpy as np
import pytest

from pmpmsph import load_case_text
from pmpmsph.simulation import Simulation

G, DP = 9.81, 0.005


def incline(theta, height=0.05, h_factor=1.3, end=0.3):
    """The scene's text: gravity tilted by `theta` degrees towards +x, a block 0.10 wide
    and `height` high on the floor."""
    th = np.radians(theta)
    return f"""
name = "incline"
dimension = 2
gravity = [{G * np.sin(th)}, {-G * np.cos(th)}]
[domain]
min = [-0.1, -0.1]
max = [0.8, 0.2]
[sph]
kernel = "wendland"
h_factor = {h_factor}
[materials.floor]
model = "tait"
rho = 1000.0
kappa = 1.0e5
[materials.block]
model = "neo_hookean"
E = 2.0e6
nu = 0.3
rho = 2000.0
[[bodies]]
name = "block"
method = "sph"
material = "block"
shape = "box"
min = [0.05, 0.0]
max = [0.15, {height}]
spacing = {DP}
[[bodies]]
name = "floor"
method = "sph"
material = "floor"
wall = true
shape = "box"
min = [-0.05, {-4 * DP}]
max = [0.75, 0.0]
spacing = {DP}
[time]
end = {end}
cfl = 0.3
"""


def run(text, watch_after=0.1):
    """(times, centre-of-mass velocities along x after `watch_after`, the largest drop of
    the lowest particle below its start over the run) of body 0."""
    case = load_case_text(text)
    sim = Simulation(case)
    p = sim.particles
    block = p["body"][: p.n_owned] == 0
    m = p["mass"][: p.n_owned][block]
    low0 = p["x"][: p.n_owned][block, 1].min()
    times, speeds, sink = [], [], 0.0
    while sim.time < case.time.end - 1e-12:
        sim.step()
        n = p.n_owned
        block = p["body"][:n] == 0
        sink = max(sink, low0 - p["x"][:n][block, 1].min())
        if sim.time > watch_after and sim.step_count % 20 == 0:
            times.append(sim.time)
            speeds.append(np.sum(m * p["v"][:n][block, 0]) / m.sum())
    return np.array(times), np.array(speeds), sink


@pytest.mark.parametrize("theta", [30.0, 10.0])
def test_block_slides_freely_on_a_smooth_incline(theta):
    times, speeds, sink = run(incline(theta))
    acc = np.polyfit(times, speeds, 1)[0]
    reference = G * np.sin(np.radians(theta))
    assert abs(acc - reference) < 1e-3 * reference, (acc, reference)
    assert sink < 0.05 * DP


@pytest.mark.parametrize("height, h_factor", [(0.05, 2.0), (0.12, 1.3)])
def test_block_rests_on_the_floor(height, h_factor):
    _, speeds, sink = run(incline(0.0, height, h_factor, end=0.4))
    assert sink < 0.05 * DP
    assert np.abs(speeds).max() < 1e-3  # m/s: no drift along the floor
