"""An SPH solid on a floor of contact walls (a dummy wall body with `friction`,
kernels/sph/contact.py): the contact holds it, a smooth wall (friction = 0) lets it slide
freely, a rough one brakes it by Coulomb's law (issue 21, item 2).

Set-up: a neo-Hookean block 0.10 x 0.05 (E = 2 MPa, nu = 0.3, rho = 2000; 20 x 10
particles at spacing 0.005, Wendland C2, h = 1.3 spacings, predictor-corrector) released at
rest on a floor of four rows of wall particles, under gravity tilted by theta (the floor is
an incline). Reference: a rigid block on an incline, acceleration along it
g (sin theta - mu cos theta) while tan theta > mu, at rest otherwise. The block's
centre-of-mass velocity along the floor is fitted linearly over 0.1 < t < 0.3 s.
Measured (this build): mu = 0 at 30 and 10 deg within 2e-15 g sin theta (the push is
normal to the floor, and the cells of its top row tile a flat face); mu = 0.3 and 0.5 at
30 deg within 2.0e-4 and 3.3e-4; at 10 deg with mu = 0.3 the block moves 20 um (its
elastic settling) and stays; its lowest particle within 0.002 spacings of where it
started in all.
A plain dummy floor (no `friction`) brakes the same block at 30 deg to 1.9 m/s^2 instead
of 4.9 (the artificial viscosity of the pairs it slides over), holds it at 10 deg, and
lets it sink 5.5 mm, more than a spacing (docs/sph.md, "Walls and solids").
In 3D (`incline(..., dim=3)`: a block 0.04 x 0.02 x 0.02, 8 x 4 x 4 particles, on two rows of wall
particles, the cells of the wall rows being cubes) the same holds: at 30 deg, mu = 0.3
within 1.7e-8 of g sin theta and mu = 0 within 5e-16, the lowest row within 0.0003
spacings of where it started.
"""
import numpy as np
import pytest

from pmpmsph import load_case_text
from pmpmsph.simulation import Simulation

G, DP = 9.81, 0.005


#: per dimension: the domain, the block's box, the floor's box (rows below y = 0), the end
GEOMETRY = {
    2: ([-0.1, -0.1], [0.8, 0.2], [0.05, 0.0], [0.15, 0.05], [-0.05, -4 * DP], [0.75, 0.0],
        0.3),
    3: ([-0.1, -0.1, -0.05], [0.4, 0.1, 0.09], [0.02, 0.0, 0.01], [0.06, 0.02, 0.03],
        [-0.02, -2 * DP, -0.01], [0.24, 0.0, 0.05], 0.2),
}


def incline(theta, mu, dim=2):
    """The scene's text: the floor's Coulomb coefficient `mu`, gravity tilted by `theta`
    degrees towards +x; in 3D a smaller block on a floor of two rows (module doc)."""
    th = np.radians(theta)
    lo, hi, block_lo, block_hi, floor_lo, floor_hi, end = GEOMETRY[dim]
    gravity = [float(G * np.sin(th)), float(-G * np.cos(th)), 0.0][:dim]
    return f"""
name = "incline"
dimension = {dim}
gravity = {gravity}
[domain]
min = {lo}
max = {hi}
[sph]
kernel = "wendland"
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
min = {block_lo}
max = {block_hi}
spacing = {DP}
[[bodies]]
name = "floor"
method = "sph"
material = "floor"
wall = true
friction = {mu}
shape = "box"
min = {floor_lo}
max = {floor_hi}
spacing = {DP}
[time]
end = {end}
cfl = 0.3
"""


def slide(theta, mu, dim=2):
    """(acceleration fitted along the floor, displacement along it, the lowest row's
    height change) of the block's centre of mass."""
    case = load_case_text(incline(theta, mu, dim))
    sim = Simulation(case)
    p = sim.particles
    block = p["body"][: p.n_owned] == 0
    m = p["mass"][: p.n_owned][block]
    x0 = np.sum(m * p["x"][: p.n_owned][block, 0]) / m.sum()
    low0 = p["x"][: p.n_owned][block, 1].min()
    times, speeds = [], []
    while sim.time < case.time.end - 1e-12:
        sim.step()
        if sim.time > case.time.end / 3 and sim.step_count % 20 == 0:
            n = p.n_owned
            block = p["body"][:n] == 0
            times.append(sim.time)
            speeds.append(np.sum(m * p["v"][:n][block, 0]) / m.sum())
    n = p.n_owned
    block = p["body"][:n] == 0
    x1 = np.sum(m * p["x"][:n][block, 0]) / m.sum()
    return np.polyfit(times, speeds, 1)[0], x1 - x0, p["x"][:n][block, 1].min() - low0


@pytest.mark.parametrize("theta, mu", [(30.0, 0.0), (10.0, 0.0), (30.0, 0.3), (30.0, 0.5)])
def test_block_slides_by_coulomb(theta, mu):
    th = np.radians(theta)
    acc, _, sink = slide(theta, mu)
    reference = G * (np.sin(th) - mu * np.cos(th))
    assert abs(acc - reference) < 1e-3 * G * np.sin(th), (acc, reference)
    assert abs(sink) < 0.01 * DP  # the contact holds the block on the floor


def test_block_sticks_below_friction_angle():
    acc, moved, sink = slide(10.0, 0.3)  # tan 10 deg = 0.18 < 0.3
    assert abs(acc) < 1e-4 * G
    assert abs(moved) < 0.01 * DP  # 20 um: the block's elastic settling
    assert abs(sink) < 0.01 * DP


def test_block_slides_by_coulomb_in_3d():
    th = np.radians(30.0)
    acc, _, sink = slide(30.0, 0.3, dim=3)
    reference = G * (np.sin(th) - 0.3 * np.cos(th))
    assert abs(acc - reference) < 1e-3 * G * np.sin(th), (acc, reference)
    assert abs(sink) < 0.01 * DP
