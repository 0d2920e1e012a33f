"""Drucker-Prager plasticity at finite strain (pmpmsph/materials/drucker_prager.py), one
material point at a time (issue 21, item 4's single-point tests): triaxial compression's
yield stress and the oedometric curve against closed forms, the stress after a return on
the cone (or at its apex) to 1e-10, dissipation >= 0 on random strain paths with and
without dilatancy, objectivity, and the configuration checks."""
import math

import numpy as np
import pytest

from pmpmsph.errors import ConfigError
from pmpmsph.materials import MODELS, material_from_table
from pmpmsph.materials.dispatch import compute_stress, strain_energy
from pmpmsph.materials.drucker_prager import DruckerPrager, plane_strain_match
from plastic_state import assert_rotated

SAND = DruckerPrager(E=5e7, nu=0.3, rho=1800.0, friction_angle=30.0)
CLAY = DruckerPrager(E=2e7, nu=0.35, rho=1900.0, friction_angle=20.0, cohesion=2e4,
                     dilatancy_angle=10.0)


def step(F, state, mat):
    sigma = np.full((3, 3), np.nan)
    compute_stress(mat.type_code, F, np.zeros((3, 3)), 0.0, state, mat.params(3), sigma)
    return sigma


def energy(F, state, mat):
    return strain_energy(mat.type_code, F, state, mat.params(3))


def invariants(tau):
    p = np.trace(tau) / 3.0
    dev = tau - p * np.eye(3)
    return p, math.sqrt(0.5 * np.sum(dev * dev))


def yield_function(tau, mat):
    eta, xi = plane_strain_match(mat.friction_angle)
    p, root_j2 = invariants(tau)
    return root_j2 + eta * p - xi * mat.cohesion


def elastic_F(tau, mat):
    """The diagonal F whose Hencky strain carries the diagonal Kirchhoff stress tau."""
    t = np.diag(tau)
    p = t.mean()
    e = p / (3.0 * mat.bulk) + (t - p) / (2.0 * mat.mu)
    return np.diag(np.exp(e))


def test_registered_and_plane_strain_match():
    assert MODELS["drucker_prager"] is DruckerPrager
    eta, xi = plane_strain_match(30.0)
    t = math.tan(math.radians(30.0))
    assert eta == pytest.approx(3 * t / math.sqrt(9 + 12 * t * t), rel=1e-15)
    assert xi == pytest.approx(3 / math.sqrt(9 + 12 * t * t), rel=1e-15)
    assert plane_strain_match(0.0) == (0.0, 1.0)

@pytest.mark.parametrize("mat", [SAND, CLAY], ids=["sand", "clay"])
def test_triaxial_compression_yield_stress(mat):
    """Under a confining pressure s_c the axial stress difference at yield is
    q* = (xi c + eta s_c) / (1/sqrt(3) - eta/3): elastic just below, plastic just above,
    and back on the cone after the return."""
    eta, xi = plane_strain_match(mat.friction_angle)
    for sc in (1e4, 1e5, 1e6):
        q = (xi * mat.cohesion + eta * sc) / (1.0 / math.sqrt(3.0) - eta / 3.0)
        for factor, plastic in ((0.999, False), (1.001, True)):
            tau = np.diag([-sc, -sc, -sc - factor * q])
            F = elastic_F(tau, mat)
            state = mat.initial_state()
            sigma = step(F, state, mat)
            assert (state[6] > 0.0) == plastic
            tau_out = np.linalg.det(F) * sigma
            if plastic:
                assert abs(yield_function(tau_out, mat)) < 1e-10 * q
            else:
                assert np.abs(tau_out - tau).max() < 1e-9 * q


@pytest.mark.parametrize("mat", [SAND, CLAY], ids=["sand", "clay"])
@pytest.mark.parametrize("increments", [1, 7, 200])
def test_oedometric_compression_against_the_closed_form(mat, increments):
    """F = diag(lambda, 1, 1), lambda < 1, in any number of increments: a fixed direction
    in logarithmic strain, on which the cone's return is affine, so the total step's return
    is exact. e = ln lambda; p_t = K e, sqrt(J2_t) = 2 G |e| / sqrt(3);
    dgamma = f_t / (G + K eta eta_bar); sqrt(J2) = sqrt(J2_t) - G dgamma, p = p_t - K eta_bar
    dgamma; tau = p 1 + sqrt(J2)/sqrt(J2_t) 2 G dev(e); sigma = tau / lambda."""
    G, K = mat.mu, mat.bulk
    eta, xi = plane_strain_match(mat.friction_angle)
    eta_bar, _ = plane_strain_match(mat.dilatancy_angle)
    lam_end = 0.97
    state = mat.initial_state()
    for k in range(1, increments + 1):
        sigma = step(np.diag([1.0 + (lam_end - 1.0) * k / increments, 1.0, 1.0]), state, mat)
    e = math.log(lam_end)
    pt, rt = K * e, 2.0 * G * abs(e) / math.sqrt(3.0)
    ft = rt + eta * pt - xi * mat.cohesion
    assert ft > 0.0
    dg = ft / (G + K * eta * eta_bar)
    p = pt - K * eta_bar * dg
    dev = 2.0 * G * e * np.array([2.0, -1.0, -1.0]) / 3.0 * (rt - G * dg) / rt
    want = np.diag(p + dev) / lam_end
    assert np.abs(sigma - want).max() < 1e-10 * np.abs(want).max()
    assert state[6] == pytest.approx(dg / math.sqrt(3.0), rel=1e-10)


def test_a_cohesionless_material_carries_no_tension():
    for F in (np.diag([1.01, 1.0, 1.0]), np.diag([1.002, 1.003, 1.0])):
        state = SAND.initial_state()
        assert np.abs(step(F, state, SAND)).max() == 0.0 and state[6] > 0.0
    state = CLAY.initial_state()  # a cohesive one stops at the apex p = xi c / eta
    sigma = step(np.diag([1.05, 1.05, 1.05]), state, CLAY)
    eta, xi = plane_strain_match(CLAY.friction_angle)
    tau = 1.05 ** 3 * sigma
    assert np.abs(tau - xi * CLAY.cohesion / eta * np.eye(3)).max() < 1e-9 * xi * CLAY.cohesion


@pytest.mark.parametrize("mat", [SAND, CLAY], ids=["sand", "clay"])
def test_returns_onto_the_cone_and_dissipates(mat):
    """Random compressive-shear paths: after every plastic step the stress is on the cone
    (or at its apex) to 1e-10, alpha never decreases, and the energy at the new state is
    not above that at the state before (plastic work tau : de_p >= 0 for eta_bar <= eta)."""
    rng = np.random.default_rng(5)
    plastic = 0
    shear = np.zeros((3, 3))
    shear[0, 1] = 1.0
    for _ in range(6):
        state = mat.initial_state()
        F = np.diag([0.995, 0.997, 1.0])  # start under some pressure
        for _ in range(60):
            F = (np.eye(3) + 1e-3 * (rng.standard_normal((3, 3)) + shear)) @ F
            before = state.copy()
            sigma = step(F, state, mat)
            tau = np.linalg.det(F) * sigma
            scale = abs(np.trace(tau)) + mat.cohesion
            assert state[6] >= before[6]
            if state[6] > before[6]:
                plastic += 1
                p, root_j2 = invariants(tau)
                apex = root_j2 <= 1e-9 * scale
                assert apex or abs(yield_function(tau, mat)) <= 1e-10 * scale
                assert energy(F, before, mat) - energy(F, state, mat) >= -1e-12 * scale
            else:
                assert yield_function(tau, mat) <= 1e-10 * scale
    assert plastic > 50


def test_objective_under_a_superposed_rotation():
    rng = np.random.default_rng(13)
    q, r = np.linalg.qr(rng.standard_normal((3, 3)))
    Q = q * np.sign(np.diag(r))
    if np.linalg.det(Q) < 0:
        Q[:, 0] *= -1
    s1, s2 = CLAY.initial_state(), CLAY.initial_state()
    F = np.diag([0.99, 0.995, 1.0])
    shear = np.zeros((3, 3))
    shear[0, 1] = 2e-3
    for _ in range(40):
        F = (np.eye(3) + 5e-4 * rng.standard_normal((3, 3)) + shear) @ F
        a = step(F, s1, CLAY)
        b = step(Q @ F, s2, CLAY)
    assert s1[6] > 0.0
    assert np.abs(b - Q @ a @ Q.T).max() < 1e-9 * np.abs(a).max()
    assert_rotated(s2, s1, Q)


def test_configuration_checks():
    m = material_from_table({"model": "drucker_prager", "E": 1e7, "nu": 0.3, "rho": 1800,
                             "friction_angle": 30}, "materials.sand", 2)
    assert m == DruckerPrager(E=1e7, nu=0.3, rho=1800.0, friction_angle=30.0)
    base = {"E": 1e7, "nu": 0.3, "rho": 1800}
    for table, key in (({**base}, "materials.m.friction_angle"),
                       ({**base, "friction_angle": 95}, "materials.m.friction_angle"),
                       ({**base, "friction_angle": 30, "dilatancy_angle": 35},
                        "materials.m.dilatancy_angle"),
                       ({**base, "friction_angle": 30, "cohesion": -1},
                        "materials.m.cohesion"),
                       ({**base, "friction_angle": 0}, "materials.m.cohesion")):
        with pytest.raises(ConfigError) as err:
            material_from_table({"model": "drucker_prager", **table}, "materials.m", 2)
        assert err.value.key == key
