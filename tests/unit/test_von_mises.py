"""J2 plasticity at finite strain (pmpmsph/materials/von_mises.py), one material point at a
time, no solver (issue 21, item 4's single-point tests): the closed-form uniaxial-strain
curve with hardening, the stress after a return on the yield surface, dissipation >= 0 on
random strain paths, objectivity, the elastic range as Hencky elasticity, the eigen solver,
and the configuration checks."""
import math

import numpy as np
import pytest

from pmpmsph.errors import ConfigError
from pmpmsph.materials import MODELS, material_from_table
from pmpmsph.materials.dispatch import compute_stress, strain_energy, wave_speed
from pmpmsph.materials.eigen import sym_eigen
from pmpmsph.materials.von_mises import VonMises
from plastic_state import assert_rotated, elastic_b, random_rotation

MAT = VonMises(E=200e9, nu=0.3, rho=7800.0, yield_stress=250e6, hardening=2e9)
G, K = MAT.mu, MAT.bulk


def step(F, state, mat=MAT):
    """The stress at F from `state` (updated in place, as G2P does once a step)."""
    sigma = np.full((3, 3), np.nan)
    compute_stress(mat.type_code, F, np.zeros((3, 3)), 0.0, state, mat.params(3), sigma)
    return sigma


def energy(F, state, mat=MAT):
    return strain_energy(mat.type_code, F, state, mat.params(3))


def mises(tau):
    dev = tau - np.trace(tau) / 3.0 * np.eye(3)
    return math.sqrt(1.5 * np.sum(dev * dev))


def random_path(rng, steps, amp):
    """F along a random walk of small increments F <- (I + dt L) F (3D)."""
    F = np.eye(3)
    out = []
    for _ in range(steps):
        F = (np.eye(3) + amp * rng.standard_normal((3, 3))) @ F
        out.append(F.copy())
    return out


def test_registered_by_its_own_module():
    assert MODELS["von_mises"] is VonMises and MODELS["j2"] is VonMises
    state = MAT.initial_state()
    assert np.all(step(np.eye(3), state) == 0.0) and energy(np.eye(3), state) == 0.0
    # be = 1, alpha = 0, no plastic flow, Fn = 1
    assert np.array_equal(state, [1, 1, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1])


def test_eigen_pairs_to_round_off():
    rng = np.random.default_rng(1)
    for scale in (1.0, 1e-9, 1e6):
        A = rng.standard_normal((3, 3))
        A = scale * (A + A.T)
        w, v = sym_eigen(A[0, 0], A[1, 1], A[2, 2], A[0, 1], A[1, 2], A[0, 2])
        V = np.array(v).reshape(3, 3)
        assert np.abs(V @ np.diag(w) @ V.T - A).max() < 1e-14 * np.abs(A).max()
        assert np.abs(V.T @ V - np.eye(3)).max() < 1e-14
    w, v = sym_eigen(2.0, 2.0, 2.0, 0.0, 0.0, 0.0)  # repeated: the identity frame
    assert w == (2.0, 2.0, 2.0) and v == (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)


@pytest.mark.parametrize("increments", [1, 7, 200])
def test_uniaxial_strain_against_the_closed_form(increments):
    """F = diag(lambda, 1, 1) loaded in any number of increments: a radial path in
    logarithmic strain, so the return of the total step is exact. With e = ln lambda the
    trial Mises stress is 2 G |e|; past sigma_y, alpha = (2 G |e| - sigma_y)/(3 G + H),
    q = sigma_y + H alpha, and tau_xx = K e + 2/3 q sign(e), tau_yy = tau_zz = K e - 1/3 q
    sign(e); sigma = tau / lambda."""
    for lam_end in (1.01, 0.985):
        state = MAT.initial_state()
        for k in range(1, increments + 1):
            lam = 1.0 + (lam_end - 1.0) * k / increments
            sigma = step(np.diag([lam, 1.0, 1.0]), state)
        e = math.log(lam_end)
        alpha = (2.0 * G * abs(e) - MAT.yield_stress) / (3.0 * G + MAT.hardening)
        assert alpha > 0.0  # well past the yield point (2 G e / sigma_y ~ 6)
        q = MAT.yield_stress + MAT.hardening * alpha
        want = np.diag([K * e + 2.0 / 3.0 * q * np.sign(e), K * e - q / 3.0 * np.sign(e),
                        K * e - q / 3.0 * np.sign(e)]) / lam_end
        assert np.abs(sigma - want).max() < 1e-10 * np.abs(want).max()
        assert state[6] == pytest.approx(alpha, rel=1e-10)


def test_elastic_range_is_hencky_elasticity():
    eps = 1e-5 * np.array([[1.0, 0.4, -0.3], [0.4, -2.0, 0.5], [-0.3, 0.5, 0.7]])
    F = np.eye(3) + eps
    state = MAT.initial_state()
    sigma = step(F, state)
    w, v = np.linalg.eigh(F @ F.T)
    e = v @ np.diag(0.5 * np.log(w)) @ v.T
    J = np.linalg.det(F)
    tau = K * np.trace(e) * np.eye(3) + 2.0 * G * (e - np.trace(e) / 3.0 * np.eye(3))
    assert mises(tau) < MAT.yield_stress and state[6] == 0.0
    assert np.abs(sigma - tau / J).max() < 1e-9 * np.abs(tau).max()
    # no plastic flow: be = F F^T
    assert np.abs(elastic_b(state) - F @ F.T).max() < 1e-15 and state[7] == 0.0


def test_returns_onto_the_yield_surface_and_dissipates():
    """On random strain paths: after a plastic step the Mises stress of tau = J sigma lies
    on sigma_y + H alpha to 1e-10, alpha never decreases, det Cp^-1 stays 1, and the energy
    at the new state is not above that at the state before (the return's dissipation,
    sigma_y dgamma + (3 G + H)/2 dgamma^2 >= 0, with dgamma the plastic increment)."""
    rng = np.random.default_rng(7)
    plastic = 0
    for _ in range(6):
        state = MAT.initial_state()
        for F in random_path(rng, 60, 4e-4):
            before = state.copy()
            sigma = step(F, state)
            dgamma = state[6] - before[6]
            assert dgamma >= 0.0
            tau = np.linalg.det(F) * sigma
            if dgamma > 0.0:
                plastic += 1
                surface = MAT.yield_stress + MAT.hardening * state[6]
                assert abs(mises(tau) - surface) < 1e-10 * surface
                drop = energy(F, before) - energy(F, state)
                ref = MAT.yield_stress * dgamma
                assert drop >= 0.0
                assert drop == pytest.approx(ref + 0.5 * (3 * G + MAT.hardening) * dgamma ** 2,
                                             rel=1e-6, abs=1e-12 * ref)
            else:
                assert mises(tau) <= MAT.yield_stress + MAT.hardening * state[6]
            # isochoric plastic flow: det be = J^2
            assert np.linalg.det(elastic_b(state)) == pytest.approx(np.linalg.det(F) ** 2,
                                                                    rel=1e-12)
    assert plastic > 100  # the paths went well into plastic flow


def test_objective_under_a_superposed_rotation():
    """F -> Q F along the same path: sigma -> Q sigma Q^T, the same plastic state (be
    rotated, alpha the same)."""
    rng = np.random.default_rng(11)
    path = random_path(rng, 40, 5e-4)
    Q = random_rotation(rng)
    s1, s2 = MAT.initial_state(), MAT.initial_state()
    for F in path:
        a = step(F, s1)
        b = step(Q @ F, s2)
    assert s1[6] > 0.0
    assert np.abs(b - Q @ a @ Q.T).max() < 1e-9 * np.abs(a).max()
    assert_rotated(s2, s1, Q)


def test_perfect_plasticity_and_wave_speed():
    mat = VonMises(E=1e7, nu=0.25, rho=2000.0, yield_stress=1e4)
    state = mat.initial_state()
    sigma = step(np.diag([1.05, 1.0, 1.0]), state, mat)
    assert mises(1.05 * sigma) == pytest.approx(1e4, rel=1e-10)
    c = math.sqrt((mat.bulk + 4.0 / 3.0 * mat.mu) / 2000.0)
    assert wave_speed(mat.type_code, mat.params(2), 0.9) == pytest.approx(c, rel=1e-14)
    assert mat.sound_speed(2) == pytest.approx(c, rel=1e-14)


def test_configuration_checks():
    m = material_from_table({"model": "von_mises", "E": 1e7, "nu": 0.3, "rho": 2000,
                             "yield_stress": 5e4}, "materials.clay", 2)
    assert m == VonMises(E=1e7, nu=0.3, rho=2000.0, yield_stress=5e4, hardening=0.0)
    for table, key in (({"E": 1e7, "nu": 0.3, "rho": 1}, "materials.m.yield_stress"),
                       ({"E": 1e7, "nu": 0.3, "rho": 1, "yield_stress": -1.0},
                        "materials.m.yield_stress"),
                       ({"E": 1e7, "nu": 0.3, "rho": 1, "yield_stress": 1.0,
                         "hardening": -5.0}, "materials.m.hardening"),
                       ({"E": 1e7, "nu": 0.6, "rho": 1, "yield_stress": 1.0},
                        "materials.m.nu")):
        with pytest.raises(ConfigError) as err:
            material_from_table({"model": "von_mises", **table}, "materials.m", 2)
        assert err.value.key == key


@pytest.mark.parametrize("method", ["mpm", "sph"])
def test_two_bars_collide_and_yield(method):
    """Two aluminium bars (plane strain) meet at 2 x 200 m/s, far past the impact velocity
    of first yield (sigma_y / (rho c) ~ 20 m/s): the material near the contact flows, the
    state is carried per particle, momentum stays zero and the stored energy ends far
    below the kinetic energy of the start (the rest was dissipated by plastic flow). A run
    of the model in both methods, not a verification (that is the footing's and the column
    collapse's). Measured at t = 3e-5: MPM (GIMP, USL) mean alpha 0.153 (max 0.62), stored
    energy 10.8 % of the start; SPH 0.114 (max 0.43), 4.7 %."""
    from mpi4py import MPI

    from pmpmsph.parallel.distributor import Distributor
    from pmpmsph.scene_api import Scene

    kw = (dict(grid=dict(origin=[0.0, 0.0], length=[0.1, 0.05], cells=[40, 20]),
               mpm=dict(shape="gimp", transfer="usl")) if method == "mpm" else
          dict(sph=dict(h_factor=1.3), domain=dict(min=[0.0, 0.0], max=[0.1, 0.05])))
    sc = Scene(2, time=dict(end=3e-5, cfl=0.3), gravity=[0.0, 0.0], **kw)
    sc.material("al", model="von_mises", E=70e9, nu=0.33, rho=2700.0, yield_stress=3e8,
                hardening=1e8)
    for name, lo, v in (("a", 0.01, 200.0), ("b", 0.04125, -200.0)):
        sc.body(name=name, material="al", shape="box", min=[lo, 0.01], max=[lo + 0.03, 0.03],
                spacing=0.00125, velocity=[v, 0.0], method=method)
    sim = sc.simulation(dist=Distributor(MPI.COMM_SELF))
    e0 = sim.diagnostics()["total"]
    sim.run()
    d = sim.diagnostics()
    alpha = sim.particles["mstate"][:, 6]
    assert np.all(np.isfinite(sim.particles["sigma"]))
    mv = e0 / 200.0  # each bar's momentum m v (e0 = 2 x m v^2 / 2)
    assert abs(d["px"]) < 1e-8 * mv  # (MPM: 2e-9, the nodes under the mass cut-off)
    assert 0.05 < alpha.mean() < 0.3 and alpha.max() < 1.0
    assert d["total"] < 0.2 * e0


def test_long_simple_shear_keeps_every_digit():
    """Simple shear to gamma = 1000 in steps of 0.01 (perfectly plastic): the stress stays on
    the yield surface to round-off and det be = J^2 = 1. With the state stored as the plastic
    Cp^-1 (be = F Cp^-1 F^T) the entries of F and Cp^-1 grow as gamma and gamma^2 and the
    product lost every digit: a sheared Drucker-Prager block ended in NaN."""
    mat = VonMises(E=1e7, nu=0.3, rho=2000.0, yield_stress=1e4)
    state = mat.initial_state()
    F = np.eye(3)
    for _ in range(100_000):
        F[0, 1] += 0.01
        sigma = step(F, state, mat)
    assert F[0, 1] == pytest.approx(1000.0)
    assert mises(sigma) == pytest.approx(mat.yield_stress, rel=1e-10)  # J = 1: sigma = tau
    assert np.linalg.det(elastic_b(state)) == pytest.approx(1.0, rel=1e-10)
    assert state[6] == pytest.approx(1000.0 / math.sqrt(3.0), rel=1e-3)  # gamma / sqrt 3
