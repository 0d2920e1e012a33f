"""Every registered grid boundary condition (kernels/mpm/grid_conditions) on single nodes: the
velocity it leaves, the FLIP increment changed by the same amount, and the mirror image that
makes the normal velocity odd about a wall; the registry feeds `[[boundaries]] type`."""
import numpy as np
import pytest

from pmpmsph.config.case import BC_KINDS
from pmpmsph.kernels.mpm.grid_bc import BC_CODES, apply_grid_bc, mirror_grid_bc
from pmpmsph.kernels.mpm.grid_conditions.registry import condition_named, grid_conditions
from pmpmsph.physics.mpm.boundary import GridBoundaries
from pmpmsph.scene_api import Scene

DIM = 2
NORMAL = np.array([0.0, -1.0, 0.0])  # outward normal of a floor
WALL = np.array([0.3, 0.0, 0.0])     # a wall sliding along itself


def impose(kind, v, mu=0.5):
    """Apply condition `kind` to one node of two velocity fields holding `v` and -v."""
    gvel = np.array([[v], [[-c for c in v]]], float)
    gdv = np.full_like(gvel, 0.25)
    before = gvel.copy(), gdv.copy()
    apply_grid_bc(DIM, np.array([0]), np.array([BC_CODES[kind]]), NORMAL[None, :],
                  np.array([mu]), WALL[None, :], gvel, gdv)
    return gvel, gdv, before


def test_choices_come_from_the_registry():
    assert BC_KINDS == tuple(c.name for c in grid_conditions())
    assert {c.code for c in grid_conditions()} == set(range(len(BC_KINDS)))


@pytest.mark.parametrize("kind", BC_KINDS)
def test_increment_moves_with_the_velocity(kind):
    gvel, gdv, (v0, dv0) = impose(kind, [0.4, 0.7, 0.0])
    np.testing.assert_allclose(gdv - dv0, gvel - v0, atol=1e-15)


def test_fixed_takes_the_wall_velocity():
    gvel, _, _ = impose("fixed", [0.4, 0.7, 0.0])
    np.testing.assert_array_equal(gvel[:, 0, :DIM], [WALL[:DIM], WALL[:DIM]])


def test_slip_removes_the_normal_component_only():
    gvel, _, _ = impose("slip", [0.4, 0.7, 0.0])
    np.testing.assert_allclose(gvel[0, 0, :DIM], [0.4, 0.0], atol=1e-15)
    np.testing.assert_allclose(gvel[1, 0, :DIM], [-0.4, 0.0], atol=1e-15)


def test_friction_is_one_sided_coulomb():
    # field 0 moves into the floor (v.n = 0.7 > 0): normal removed, tangent 0.4 reduced by
    # mu v.n = 0.35; field 1 leaves it (v.n < 0): untouched
    gvel, _, _ = impose("friction", [0.4, -0.7, 0.0], mu=0.5)
    np.testing.assert_allclose(gvel[0, 0, :DIM], [0.4 - 0.5 * 0.7, 0.0], atol=1e-15)
    np.testing.assert_allclose(gvel[1, 0, :DIM], [-0.4, 0.7], atol=1e-15)
    # friction strong enough stops the tangent entirely (no reversal)
    gvel, _, _ = impose("friction", [0.4, -0.7, 0.0], mu=5.0)
    np.testing.assert_allclose(gvel[0, 0, :DIM], [0.0, 0.0], atol=1e-15)


@pytest.mark.parametrize("kind", [c.name for c in grid_conditions() if c.mirror is not None])
def test_mirror_makes_the_wall_velocity_what_the_stencil_sees(kind):
    """Node 1 (outside) mirrors node 0 (inside): the average of the two, what a symmetric
    stencil interpolates on the wall between them, has no normal component, and for a no-slip
    wall it is the wall's velocity."""
    gvel = np.array([[[0.4, 0.7, 0.0], [9.0, 9.0, 0.0]]])
    gdv = np.array([[[0.1, 0.2, 0.0], [9.0, 9.0, 0.0]]])
    mirror_grid_bc(DIM, np.array([1]), np.array([0]), BC_CODES[kind], NORMAL, WALL, gvel, gdv)
    on_wall = 0.5 * (gvel[0, 0] + gvel[0, 1])
    assert on_wall @ NORMAL == pytest.approx(0.0, abs=1e-15)
    assert (0.5 * (gdv[0, 0] + gdv[0, 1])) @ NORMAL == pytest.approx(0.0, abs=1e-15)
    if kind == "fixed":
        np.testing.assert_allclose(on_wall, WALL, atol=1e-15)
    else:  # slip keeps the tangential velocity
        assert on_wall[0] == pytest.approx(0.4)


def test_friction_does_not_mirror():
    assert condition_named("friction").mirror is None


def test_a_gate_acts_until_its_time_and_again_after_going_back():
    """A boundary with `until` (a gate) is in the active set for time < until only; the set
    is re-read when time crosses a gate's time, either way (a restart may go back)."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[8, 8]),
               time=dict(end=1.0, cfl=0.5))
    sc.material("m", model="linear_elastic", E=1e3, nu=0.3, rho=1000)
    sc.body(name="b", material="m", shape="box", min=[0.2, 0.2], max=[0.4, 0.4], ppc=2)
    sc.boundary(face="y-", type="fixed")
    sc.boundary(box=dict(min=[0.5, 0.0], max=[0.5, 1.0]), type="slip", normal=[1, 0],
                until=0.25)
    sc.boundary(face="x+", type="slip", until=0.5)
    sim = sc.simulation()
    bcs = sim.mpm.bcs
    assert isinstance(bcs, GridBoundaries)
    vel, dv = sim.mpm.grid.vel, sim.mpm.grid.dv
    for time, active in ((0.0, (0, 1, 2)), (0.1, (0, 1, 2)), (0.25, (0, 2)), (0.3, (0, 2)),
                         (0.5, (0,)), (0.9, (0,)), (0.2, (0, 1, 2)), (0.6, (0,))):
        bcs.apply(time, vel, dv)
        assert bcs.active_key == active, time
        assert len(bcs._arrays[0]) == sum(len(bcs.parts[j][0]) for j in active)
