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
from plastic_state import assert_rotated, random_rotation

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
    Q = random_rotation(rng)
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


# tension cut-off: sigma_t = 1e4 Pa, below the apex c cot(phi) = 5.49e4 Pa
CUT = DruckerPrager(E=2e7, nu=0.35, rho=1900.0, friction_angle=20.0, cohesion=2e4,
                    dilatancy_angle=10.0, tensile_strength=1e4)


def corner_radius(mat):
    """sqrt(J2) of the cone at p = sigma_t."""
    eta, xi = plane_strain_match(mat.friction_angle)
    return xi * mat.cohesion - eta * mat.tensile_strength


def trial_tau(p, root_j2):
    """A diagonal Kirchhoff stress with mean p and sqrt(J2) = root_j2 (axial deviator)."""
    s = root_j2 / math.sqrt(3.0)
    return np.diag([p + 2.0 * s, p - s, p - s])


@pytest.mark.parametrize("increments", [1, 7, 200])
def test_tension_stops_at_the_cut_off(increments):
    """Uniaxial strain, equal triaxial and unequal triaxial extension, in any number of
    increments: the mean Kirchhoff stress ends on p = sigma_t to 1e-10, inside the cone."""
    for end in ([1.01, 1.0, 1.0], [1.004, 1.004, 1.004], [1.01, 1.002, 0.999]):
        state = CUT.initial_state()
        for k in range(1, increments + 1):
            F = np.diag([1.0 + (x - 1.0) * k / increments for x in end])
            sigma = step(F, state, CUT)
        tau = np.linalg.det(F) * sigma
        p, _ = invariants(tau)
        assert abs(p - CUT.tensile_strength) < 1e-10 * CUT.tensile_strength
        assert yield_function(tau, CUT) <= 1e-10 * CUT.cohesion
        assert state[7] == 1.0


def test_cut_off_and_corner_returns():
    """Trial states built in each region (the diagonal F of a chosen trial tau): past the
    cut-off with sqrt(J2_t) below the corner's radius r_c, the mean stress drops to sigma_t
    and the deviator is kept (alpha unchanged: the flow is volumetric); in the corner region
    the stress is sigma_t 1 + (r_c / sqrt(J2_t)) dev tau_t and alpha grows by
    (sqrt(J2_t) - r_c) / (sqrt(3) G); just outside the corner region, on the cone's side,
    the return is the cone's (the same stress as without the cut-off)."""
    G, K = CUT.mu, CUT.bulk
    eta_bar, _ = plane_strain_match(CUT.dilatancy_angle)
    st, rc = CUT.tensile_strength, corner_radius(CUT)
    # cut-off
    tau_t = trial_tau(st + 5e3, 0.5 * rc)
    state = CUT.initial_state()
    F = elastic_F(tau_t, CUT)
    tau = np.linalg.det(F) * step(F, state, CUT)
    dev_t = tau_t - np.trace(tau_t) / 3.0 * np.eye(3)
    assert np.abs(tau - (st * np.eye(3) + dev_t)).max() < 1e-10 * st
    assert state[6] == 0.0 and state[7] == 1.0
    # corner
    rho_t = 2.0 * rc
    for extra in (1e3, 1e5):
        tau_t = trial_tau(st + K * eta_bar * (rho_t - rc) / G + extra, rho_t)
        state = CUT.initial_state()
        F = elastic_F(tau_t, CUT)
        tau = np.linalg.det(F) * step(F, state, CUT)
        dev_t = tau_t - np.trace(tau_t) / 3.0 * np.eye(3)
        want = st * np.eye(3) + rc / rho_t * dev_t
        assert np.abs(tau - want).max() < 1e-10 * st
        assert state[6] == pytest.approx((rho_t - rc) / (math.sqrt(3.0) * G), rel=1e-10)
    # the cone's side of the boundary: as without the cut-off
    no_cut = DruckerPrager(E=CUT.E, nu=CUT.nu, rho=CUT.rho, friction_angle=20.0,
                           cohesion=2e4, dilatancy_angle=10.0)
    tau_t = trial_tau(st + K * eta_bar * (rho_t - rc) / G - 1e2, rho_t)
    F = elastic_F(tau_t, CUT)
    s1, s2 = CUT.initial_state(), no_cut.initial_state()
    a, b = step(F, s1, CUT), step(F, s2, no_cut)
    assert np.abs(a - b).max() < 1e-12 * np.abs(b).max() and s1[6] == s2[6] > 0.0
    p, _ = invariants(np.linalg.det(F) * a)
    assert p < st


def test_cut_off_at_the_apex_is_the_cone_alone():
    """tensile_strength = c cot(phi) gives the cone-and-apex return to round-off on random
    paths through tension and shear."""
    eta, xi = plane_strain_match(20.0)
    apex = DruckerPrager(E=2e7, nu=0.35, rho=1900.0, friction_angle=20.0, cohesion=2e4,
                         dilatancy_angle=10.0, tensile_strength=2e4 / math.tan(math.radians(20)))
    assert apex.params(3)[7] == pytest.approx(xi * 2e4 / eta, rel=1e-14)
    rng = np.random.default_rng(17)
    s1, s2 = apex.initial_state(), CLAY.initial_state()
    F = np.eye(3)
    for _ in range(80):
        F = (np.eye(3) + 2e-3 * (rng.standard_normal((3, 3)) + 0.5 * np.eye(3))) @ F
        a, b = step(F, s1, apex), step(F, s2, CLAY)
        assert np.abs(a - b).max() <= 1e-9 * (np.abs(b).max() + CLAY.cohesion)
    assert s2[6] > 0.0 and abs(s1[6] - s2[6]) <= 1e-9 * s2[6]


def test_cut_off_returns_dissipate_on_random_paths():
    """Random paths alternating stretch and shear: after every plastic step the stress is
    inside both surfaces and on one of them (or the corner) to 1e-10, alpha never
    decreases, and the energy drop of the return is >= 0; the cut-off, the corner and the
    cone are all met."""
    rng = np.random.default_rng(23)
    st = CUT.tensile_strength
    scale = CUT.cohesion
    seen = {"cut": 0, "cone": 0}
    for _ in range(8):
        state = CUT.initial_state()
        F = np.eye(3)
        for k in range(60):
            bias = 0.6 * np.eye(3) if (k // 10) % 2 == 0 else -0.6 * np.eye(3)
            F = (np.eye(3) + 1e-3 * (rng.standard_normal((3, 3)) + bias)) @ F
            before = state.copy()
            tau = np.linalg.det(F) * step(F, state, CUT)
            p, _ = invariants(tau)
            f = yield_function(tau, CUT)
            assert state[6] >= before[6]
            assert p <= st + 1e-10 * scale and f <= 1e-10 * scale
            if state[7] == 1.0:
                on_cut = abs(p - st) <= 1e-10 * scale
                assert on_cut or abs(f) <= 1e-10 * scale
                seen["cut" if on_cut else "cone"] += 1
                assert energy(F, before, CUT) - energy(F, state, CUT) >= -1e-12 * scale
    assert seen["cut"] > 20 and seen["cone"] > 20


def test_cut_off_is_objective():
    rng = np.random.default_rng(29)
    Q = random_rotation(rng)
    s1, s2 = CUT.initial_state(), CUT.initial_state()
    F = np.eye(3)
    for _ in range(40):
        F = (np.eye(3) + 5e-4 * (rng.standard_normal((3, 3)) + np.eye(3))) @ F
        a = step(F, s1, CUT)
        b = step(Q @ F, s2, CUT)
    p, _ = invariants(np.linalg.det(F) * a)
    assert p == pytest.approx(CUT.tensile_strength, rel=1e-10)  # on the cut-off
    assert np.abs(b - Q @ a @ Q.T).max() < 1e-9 * np.abs(a).max()
    assert_rotated(s2, s1, Q)


def test_tensile_strength_checks():
    base = {"model": "drucker_prager", "E": 1e7, "nu": 0.3, "rho": 1800}
    ok = material_from_table({**base, "friction_angle": 30, "cohesion": 1e4,
                              "tensile_strength": 5e3}, "materials.m", 2)
    assert ok.tensile_strength == 5e3 and ok.params(2)[7] == 5e3
    assert material_from_table({**base, "friction_angle": 30}, "materials.m",
                               2).params(2)[7] == -1.0  # no cut-off: the cone alone
    material_from_table({**base, "friction_angle": 0, "cohesion": 1e4,
                         "tensile_strength": 1e9}, "materials.m", 2)  # no apex
    material_from_table({**base, "friction_angle": 30, "tensile_strength": 0.0},
                        "materials.m", 2)  # cohesionless: the apex is 0
    for extra in ({"friction_angle": 30, "cohesion": 1e4, "tensile_strength": 1.8e4},
                  {"friction_angle": 30, "tensile_strength": 1.0},
                  {"friction_angle": 30, "cohesion": 1e4, "tensile_strength": -1.0}):
        with pytest.raises(ConfigError) as err:
            material_from_table({**base, **extra}, "materials.m", 2)
        assert err.value.key == "materials.m.tensile_strength"
