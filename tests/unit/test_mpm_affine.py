"""APIC (Jiang et al. 2015) and MLS-MPM (Hu et al. 2018) transfers (kernels/mpm/affine.py).

1. Both transfers are exact for an affine velocity field v(x) = A x + b, for every shape
   function in 1D, 2D and 3D: particles carrying v_p = A x_p + b and C_p = A scatter nodal
   velocities A x_I + b (Jiang 2015 eq. 12), and G2P of those returns v_p and C_p = A
   (eq. 10, with D_p summed, constant or, for the linear hat, replaced by grad N).
   PIC (C = 0) does not reproduce the nodal field: the check has teeth.
2. Angular momentum (Jiang 2015 §5.4; Hu 2018 §4.2): an elastic disc spinning freely keeps
   sum m_p x_p x v_p + sum m_p (C_p D_p) : eps (the affine part) to 1e-11 over 150 steps with
   APIC and MLS; PIC loses more than 1 % of it.
3. Bad input names the key: MLS with a shape other than a B-spline or a scheme other than USL,
   and `flip` beside an affine transfer (tests/hostile/*.toml cover the command line).
"""
import numpy as np
import pytest

from pmpmsph.errors import ConfigError
from pmpmsph.kernels.mpm.affine import g2p_affine, p2g_affine
from pmpmsph.kernels.mpm.shapes import CUBIC, GIMP, LINEAR, QUADRATIC, static_tags
from pmpmsph.kernels.mpm.views import grid_layout, scatter_points
from pmpmsph.scene_api import Scene

NODES = 12
DX = 0.1
SHAPES = {"linear": LINEAR, "gimp": GIMP, "quadratic": QUADRATIC, "cubic": CUBIC}


def _affine_field(dim, rng):
    return rng.uniform(-1, 1, (dim, dim)), rng.uniform(-1, 1, dim)


def _grid(dim):
    strides = np.array([NODES ** (dim - 1 - a) for a in range(dim)], np.int64)
    return strides, np.zeros(dim), np.zeros(dim, np.int64), NODES ** dim


def _node_positions(dim):
    idx = np.indices((NODES,) * dim).reshape(dim, -1).T
    return idx * DX


@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("shape, mls", [(s, False) for s in SHAPES]
                         + [("quadratic", True), ("cubic", True)])  # MLS: B-splines only
def test_p2g_of_an_affine_field_is_exact(dim, shape, mls):
    rng = np.random.default_rng(dim)
    A, b = _affine_field(dim, rng)
    n = 40
    x = 0.45 + rng.uniform(0.0, 0.3, (n, dim))
    v = x @ A.T + b
    C = np.zeros((n, 3, 3))
    C[:, :dim, :dim] = A
    strides, origin, offset, nn = _grid(dim)
    lp = np.full((n, dim), 0.25) if shape == "gimp" else None
    gmass = np.zeros((1, nn))
    gmom = np.zeros((1, nn, dim))
    layout = grid_layout(origin, offset, 1.0 / DX, strides, np.full(3, -1e9), np.full(3, 1e9))
    p2g_affine(static_tags(dim, SHAPES[shape]), mls,
               scatter_points(x, v, rng.uniform(1, 2, n), rng.uniform(0.5, 1, n),
                             np.zeros((n, 3, 3)), C), layout, gmass, gmom, lp=lp)
    hit = gmass[0] > 1e-12 * gmass.max()
    vel = gmom[0][hit] / gmass[0][hit, None]
    exact = _node_positions(dim)[hit] @ A.T + b
    assert np.abs(vel - exact).max() < 1e-12
    # PIC (C = 0) does not give the affine nodal field
    gmass[:] = 0.0
    gmom[:] = 0.0
    p2g_affine(static_tags(dim, SHAPES[shape]), mls,
               scatter_points(x, v, rng.uniform(1, 2, n), rng.uniform(0.5, 1, n),
                             np.zeros((n, 3, 3)), np.zeros_like(C)), layout, gmass, gmom,
               lp=lp)
    assert np.abs(gmom[0][hit] / gmass[0][hit, None] - exact).max() > 1e-3


@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("shape", list(SHAPES))
def test_g2p_of_an_affine_field_returns_it(dim, shape):
    rng = np.random.default_rng(10 + dim)
    A, b = _affine_field(dim, rng)
    n = 30
    x = 0.45 + rng.uniform(0.0, 0.3, (n, dim))
    x0 = x.copy()
    strides, origin, offset, nn = _grid(dim)
    gvel = (_node_positions(dim) @ A.T + b)[None]
    lp = np.full((n, dim), 0.25) if shape == "gimp" else None
    v = np.zeros((n, dim))
    C = np.zeros((n, 3, 3))
    L = np.zeros((n, 3, 3))
    dt = 1e-3
    layout = grid_layout(origin, offset, 1.0 / DX, strides, np.full(dim, -1.0),
                        np.full(dim, 2.0))
    bad = g2p_affine(static_tags(dim, SHAPES[shape]), False, x, v, C, layout, gvel, dt,
                     lp=lp, Lout=L)
    assert bad == -1
    assert np.abs(L[:, :dim, :dim] - A).max() < 1e-10  # the gradient the deformation takes
    assert np.abs(v - (x0 @ A.T + b)).max() < 1e-12
    assert np.abs(C[:, :dim, :dim] - A).max() < 1e-10
    assert np.abs(x - (x0 + dt * v)).max() < 1e-15


def _spinning_disc(velocity_update, shape, omega=2.0):
    mpm = dict(shape=shape, transfer="usl", velocity_update=velocity_update,
               mass_cutoff=1e-300)
    if velocity_update == "pic":
        mpm.update(velocity_update="flip", flip=0.0)
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[20, 20]),
               time=dict(end=1e9, dt=2e-4), gravity=[0, 0], mpm=mpm)
    sc.material("rubber", model="neo_hookean", E=1e4, nu=0.3, rho=1000.0)
    sc.body(name="disc", material="rubber", shape="disc", centre=[0.5, 0.5], radius=0.2,
            ppc=2)
    sim = sc.simulation(write_output=False)
    p = sim.particles
    r = p["x"] - 0.5
    p["v"][:, 0] = -omega * r[:, 1]
    p["v"][:, 1] = omega * r[:, 0]
    if "C" in p:  # the rigid rotation's velocity gradient
        p["C"][:, 0, 1] = -omega
        p["C"][:, 1, 0] = omega
    return sim


def _angular_momentum(sim, shape):
    """sum m x x v plus the affine part sum m (C D)_yx - (C D)_xy (Jiang 2015 §5.4), with
    D = dx^2/4 I (quadratic) or dx^2/3 I (cubic)."""
    p = sim.particles
    m, x, v = p["mass"], p["x"], p["v"]
    L = np.sum(m * (x[:, 0] * v[:, 1] - x[:, 1] * v[:, 0]))
    if "C" in p:
        d = sim.mpm.grid.dx ** 2 * {"quadratic": 0.25, "cubic": 1.0 / 3.0}[shape]
        L += np.sum(m * d * (p["C"][:, 1, 0] - p["C"][:, 0, 1]))
    return L


@pytest.mark.parametrize("transfer", ["apic", "mls"])
@pytest.mark.parametrize("shape", ["quadratic", "cubic"])
def test_affine_transfers_conserve_angular_momentum(transfer, shape):
    sim = _spinning_disc(transfer, shape)
    L0 = _angular_momentum(sim, shape)
    sim.run(max_steps=150)
    assert abs(_angular_momentum(sim, shape) / L0 - 1.0) < 1e-11
    # it spins against its own stiffness (the internal forces are in the balance): the
    # centrifugal stretch at the centre, rho omega^2 R^2 (3 + nu)/8, is about 70 Pa
    assert 30.0 < np.abs(sim.particles["sigma"]).max() < 300.0


def test_pic_loses_angular_momentum():
    sim = _spinning_disc("pic", "quadratic")
    L0 = _angular_momentum(sim, "quadratic")
    sim.run(max_steps=150)
    assert _angular_momentum(sim, "quadratic") / L0 < 0.99


def _scene(**mpm):
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[8, 8]),
               time=dict(end=0.1, dt=1e-4), mpm=mpm)
    sc.material("m", model="neo_hookean", E=1e4, nu=0.3, rho=1000.0)
    sc.body(name="b", material="m", shape="box", min=[0.3, 0.3], max=[0.6, 0.6], ppc=2)
    return sc


@pytest.mark.parametrize("mpm, key", [
    (dict(shape="linear", velocity_update="mls"), "mpm.velocity_update"),
    (dict(shape="gimp", velocity_update="mls"), "mpm.velocity_update"),
    (dict(shape="quadratic", transfer="musl", velocity_update="mls"), "mpm.velocity_update"),
    (dict(shape="quadratic", velocity_update="apic", flip=0.5), "mpm.flip"),
])
def test_bad_affine_options_name_the_key(mpm, key):
    with pytest.raises(ConfigError) as e:
        _scene(**mpm).simulation(write_output=False)
    assert e.value.key == key


@pytest.mark.parametrize("shape", ["linear", "gimp", "cpdi", "quadratic"])
@pytest.mark.parametrize("transfer", ["usl", "usf", "musl"])
def test_apic_runs_with_every_shape_and_scheme(shape, transfer):
    """A falling block: APIC moves it like free fall until it lands (mean velocity
    -g t to rounding before it touches anything)."""
    sc = _scene(shape=shape, transfer=transfer, velocity_update="apic")
    sc.set("gravity", [0.0, -9.81])
    sim = sc.simulation(write_output=False)
    sim.run(max_steps=200)
    vy = sim.particles["v"][:, 1]
    assert np.allclose(vy, -9.81 * sim.time, rtol=1e-9, atol=0)
