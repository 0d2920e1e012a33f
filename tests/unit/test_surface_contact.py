"""Multi-field contact decided from the particles' surfaces (kernels/mpm/contact.py): each
field's reach along its normal at a node, and contact only where the two reaches overlap."""
import numpy as np
import pytest

from pmpmsph.kernels.mpm.contact import contact_normals, multi_field_contact, surface_reach

DX = 0.1
SHAPE = (6, 6)  # nodes; global node 0 at the origin
STRIDES = np.array([6, 1], dtype=np.int64)


def _node(i, j):
    return i * STRIDES[0] + j * STRIDES[1]


def _reach(x, vol, field, normals, support=1.5):
    reach = np.full((2, SHAPE[0] * SHAPE[1]), -np.inf)
    surface_reach(2, x, vol, field, None, np.zeros(2), np.zeros(2, np.int64), 1.0 / DX,
                  STRIDES, support, normals, reach)
    return reach


def test_normals_are_unit_and_opposite_where_two_fields_meet():
    nn = SHAPE[0] * SHAPE[1]
    mass = np.zeros((2, nn))
    grad = np.zeros((2, nn, 2))
    k = _node(2, 2)
    mass[:, k] = (1.0, 2.0)
    grad[0, k] = (0.0, -3.0)   # field 0 below the node, field 1 above
    grad[1, k] = (0.0, 5.0)
    mass[0, _node(1, 1)] = 1.0  # one field only: no normal
    normals = np.ones((2, nn, 2))
    reach = np.zeros((2, nn))
    contact_normals(2, mass, grad, np.zeros(2, np.bool_), 1e-12, normals, reach)
    assert normals[0, k] == pytest.approx([0.0, -1.0])
    assert normals[1, k] == pytest.approx([0.0, 1.0])
    assert np.all(normals[:, _node(1, 1)] == 0.0)
    # the reaches start at -inf where the fields meet, NaN (no contact node) elsewhere
    assert np.all(np.isneginf(reach[:, k]))
    assert np.isnan(reach).sum() == reach.size - 2
    # where a fluid (field 0) meets a solid, both take the solid's normal
    grad[1, k] = (0.6, 0.8)
    contact_normals(2, mass, grad, np.array([True, False]), 1e-12, normals, reach)
    assert normals[1, k] == pytest.approx([0.6, 0.8])
    assert normals[0, k] == pytest.approx([-0.6, -0.8])


def test_reach_is_the_furthest_particle_surface_along_the_normal():
    """Two particles of field 0 (half-side 0.025) at 0.03 and 0.08 below node (2, 2) on the
    normal (0, 1): its reach is the nearer one's top, -0.03 + 0.025; at 45 degrees the
    square reaches sqrt(2) times its half-side."""
    nn = SHAPE[0] * SHAPE[1]
    normals = np.zeros((2, nn, 2))
    k, d = _node(2, 2), _node(3, 3)
    normals[0, k] = (0.0, 1.0)
    normals[0, d] = (np.sqrt(0.5), np.sqrt(0.5))
    x = np.array([[0.2, 0.17], [0.21, 0.12]])
    vol = np.full(2, 0.05**2)
    reach = _reach(x, vol, np.zeros(2, np.int64), normals)
    assert reach[0, k] == pytest.approx(-0.03 + 0.025, abs=1e-14)
    # node (3, 3) at (0.3, 0.3): the first particle is (-0.1, -0.13) from it
    assert reach[0, d] == pytest.approx((-0.1 - 0.13) * np.sqrt(0.5) + 0.025 * np.sqrt(2.0),
                                        abs=1e-14)
    assert np.all(np.isneginf(reach[1]))
    # a node beyond the support is not reached
    far = _reach(x, vol, np.zeros(2, np.int64), normals, support=0.5)
    assert np.isneginf(far[0, d])


@pytest.mark.parametrize("gap, touching", [(-0.01, True), (0.0, True), (0.0079, True),
                                           (0.0081, False), (0.01, False)])
def test_contact_acts_only_where_the_surfaces_meet(gap, touching):
    """Field 0's top surface at y = 0.2 - 0.005, field 1's bottom at 0.2 - 0.005 + gap, both
    seen from node (2, 2); field 1 falls onto field 0 at rest at 2 m/s: in contact if the
    surfaces meet within the step of 0.004 s (a gap of 0.008)."""
    nn = SHAPE[0] * SHAPE[1]
    k = _node(2, 2)
    normals = np.zeros((2, nn, 2))
    normals[0, k] = (0.0, 1.0)
    normals[1, k] = (0.0, -1.0)
    h = 0.025
    x = np.array([[0.2, 0.2 - 0.005 - h], [0.2, 0.2 - 0.005 + gap + h]])
    reach = _reach(x, np.full(2, (2 * h)**2), np.array([0, 1]), normals)
    assert reach[0, k] + reach[1, k] == pytest.approx(-gap, abs=1e-14)
    mass = np.zeros((2, nn))
    mass[:, k] = (3.0, 1.0)
    vel = np.zeros((2, nn, 2))
    vel[1, k] = (0.5, -2.0)     # approaching, with a tangential part
    dv = np.zeros((2, nn, 2))
    momentum = (mass[:, k, None] * vel[:, k]).sum(axis=0)
    multi_field_contact(2, mass, normals, reach, vel, dv, 0.0, 1e-12, 0.004)
    if touching:  # the normal velocities are the centre of mass's; frictionless: x kept
        assert vel[0, k] == pytest.approx([0.0, -0.5])
        assert vel[1, k] == pytest.approx([0.5, -0.5])
    else:
        assert vel[0, k] == pytest.approx([0.0, 0.0])
        assert vel[1, k] == pytest.approx([0.5, -2.0])
    assert (mass[:, k, None] * vel[:, k]).sum(axis=0) == pytest.approx(momentum)
    assert dv[:, k] == pytest.approx(vel[:, k] - np.array([[0.0, 0.0], [0.5, -2.0]]))


def test_separating_fields_are_left_alone():
    nn = SHAPE[0] * SHAPE[1]
    k = _node(2, 2)
    normals = np.zeros((2, nn, 2))
    normals[0, k] = (0.0, 1.0)
    normals[1, k] = (0.0, -1.0)
    reach = np.zeros((2, nn))   # overlapping surfaces
    mass = np.zeros((2, nn))
    mass[:, k] = (1.0, 1.0)
    vel = np.zeros((2, nn, 2))
    vel[1, k] = (0.0, 1.0)      # field 1 moving away upwards
    dv = np.zeros((2, nn, 2))
    multi_field_contact(2, mass, normals, reach, vel, dv, 0.3, 1e-12, 0.01)
    assert vel[1, k] == pytest.approx([0.0, 1.0]) and np.all(dv == 0.0)
