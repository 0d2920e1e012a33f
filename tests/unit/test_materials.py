"""Constitutive models (pmpmsph.materials): stress, energy, wave speed and config validation."""
import math

import numpy as np
import pytest

from pmpmsph.errors import ConfigError
from pmpmsph.materials import (MODELS, NPAR, PAR_RHO0, HartmannNeff, LinearElastic, Maxwell,
                               NeoHookean, StVenantKirchhoff, TaitFluid, material_from_table)
from pmpmsph.materials import dispatch, registry
from pmpmsph.materials.dispatch import compute_stress, strain_energy, wave_speed
from pmpmsph.materials.elastic import (stress_hartmann_neff, stress_linear_elastic,
                                       stress_neo_hookean, stress_stvk)
from pmpmsph.materials.fluid import stress_tait_fluid
from pmpmsph.materials.maxwell import stress_maxwell

MATS = {
    "linear_elastic": LinearElastic(E=2.0e5, nu=0.3, rho=1000.0),
    "stvk": StVenantKirchhoff(E=2.0e5, nu=0.25, rho=1200.0),
    "neo_hookean": NeoHookean(E=1.0e5, nu=0.35, rho=1500.0),
    "hartmann_neff": HartmannNeff(mu=1.25e6, k=5.833e6, rho=3.0),
    "maxwell": Maxwell(mu=1.25e6, k=5.833e6, eta=2.0e5, rho=3.0),
    "tait_fluid": TaitFluid(rho=1000.0, kappa=2.0e6, gamma=7.0, mu=1.0e-3),
}
SOLIDS = ["linear_elastic", "stvk", "neo_hookean", "hartmann_neff", "maxwell"]
FINITE = ["stvk", "neo_hookean", "hartmann_neff", "maxwell", "tait_fluid"]
ZERO = np.zeros((3, 3))


def stress(mat, F, L=ZERO, dt=1e-4, state=None, dim=3):
    sigma = np.full((3, 3), np.nan)
    st = mat.initial_state() if state is None else state
    compute_stress(mat.type_code, F, L, dt, st, mat.params(dim), sigma)
    return sigma


def energy(mat, F, state=None, dim=3):
    st = mat.initial_state() if state is None else state
    return strain_energy(mat.type_code, F, st, mat.params(dim))


def random_F(rng, dim, amp=0.15):
    while True:
        F = np.eye(3)
        if dim == 1:
            F[0, 0] += amp * rng.standard_normal()
        else:
            F[:dim, :dim] += amp * rng.standard_normal((dim, dim))
        if np.linalg.det(F) > 0.5:
            return F


def rotation(rng, dim):
    Q = np.eye(3)
    if dim == 2:
        a = rng.uniform(0.3, 2.8)
        Q[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
        return Q
    q, r = np.linalg.qr(rng.standard_normal((3, 3)))
    q = q * np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] *= -1.0
    return q


def unimodular_spd(rng, dim):
    A = random_F(rng, dim, 0.2)
    C = A.T @ A
    return C / np.cbrt(np.linalg.det(C))


def sym6(C):
    return np.array([C[0, 0], C[1, 1], C[2, 2], C[0, 1], C[1, 2], C[0, 2]])


def full(s):
    return np.array([[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]])


def rel(a, b):
    if np.size(b) == 0:
        return 0.0
    return np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300)


def modulus(mat):
    return mat.rho0 * mat.sound_speed() ** 2


# ------------------------------------------------------------------ reference state
@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("name", list(MATS))
def test_zero_stress_and_energy_at_identity(name, dim):
    mat = MATS[name]
    sigma = stress(mat, np.eye(3), dim=dim)
    assert np.max(np.abs(sigma)) <= 1e-12 * modulus(mat)
    assert abs(energy(mat, np.eye(3), dim=dim)) <= 1e-12 * modulus(mat)


# ------------------------------------------------------------------ symmetry, objectivity
@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("name", FINITE)
def test_symmetric_and_objective(name, dim):
    rng = np.random.default_rng(10 * dim + FINITE.index(name))
    mat = MATS[name]
    F = random_F(rng, dim)
    Q = rotation(rng, dim)
    L = np.zeros((3, 3))
    if name == "tait_fluid":
        L[:dim, :dim] = 50.0 * rng.standard_normal((dim, dim))
    # superposed rigid rotation: F -> Q F, L -> Q L Q^T + W (W skew, the spin of Q(t))
    W = np.zeros((3, 3))
    W[:dim, :dim] = rng.standard_normal((dim, dim))
    W = W - W.T
    s1 = mat.initial_state()
    s2 = mat.initial_state()
    if name == "maxwell":
        s1[:] = sym6(unimodular_spd(rng, dim))
        s2[:] = s1
    sig = stress(mat, F, L, 1e-3, s1, dim)
    sig_rot = stress(mat, Q @ F, Q @ L @ Q.T + W, 1e-3, s2, dim)
    assert np.array_equal(sig, sig.T)
    assert np.array_equal(sig_rot, sig_rot.T)
    assert rel(sig_rot, Q @ sig @ Q.T) < 1e-10
    assert rel(s2, s1) < 1e-12  # C_i lives on the reference configuration: unaffected by Q


def test_linear_elastic_is_small_strain_only():
    """sym(F) - I is not objective: the error under a rotation Q = I + theta W is
    O(theta |grad u| + theta^2), so the model is for small strain and small rotation only."""
    mat = MATS["linear_elastic"]
    rng = np.random.default_rng(3)
    H = rng.standard_normal((3, 3))
    F = np.eye(3) + 1e-4 * H

    def rot(theta):
        c, s = math.cos(theta), math.sin(theta)
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    sig = stress(mat, F)
    assert np.array_equal(sig, sig.T)
    small = rel(stress(mat, rot(1e-5) @ F), rot(1e-5) @ sig @ rot(1e-5).T)
    large = rel(stress(mat, rot(0.5) @ F), rot(0.5) @ sig @ rot(0.5).T)
    assert small < 1e-3
    assert large > 1.0


# ------------------------------------------------------------------ stress <-> energy
def fd_gradient(fun, F, h=1e-6):
    P = np.zeros((3, 3))
    for i in range(3):
        for j in range(3):
            Fp = F.copy()
            Fm = F.copy()
            Fp[i, j] += h
            Fm[i, j] -= h
            P[i, j] = (fun(Fp) - fun(Fm)) / (2.0 * h)
    return P


@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("name", list(MATS))
def test_kirchhoff_stress_from_energy(name, dim):
    rng = np.random.default_rng(100 + 7 * dim + list(MATS).index(name))
    mat = MATS[name]
    F = random_F(rng, dim)
    state = mat.initial_state()
    if name == "maxwell":
        state[:] = sym6(unimodular_spd(rng, dim))
    state0 = state.copy()
    P = fd_gradient(lambda G: energy(mat, G, state, dim), F)
    sigma = stress(mat, F, ZERO, 0.0, state, dim)  # dt = 0: C_i held fixed
    assert rel(state, state0) < 1e-14
    if name == "linear_elastic":
        # small-strain theory: sigma = d psi / d eps = d psi / d F
        assert rel(P, sigma) < 1e-6
    else:
        tau = P @ F.T
        assert rel(tau, np.linalg.det(F) * sigma) < 1e-6


# ------------------------------------------------------------------ 1D bar
@pytest.mark.parametrize("name", ["linear_elastic", "stvk", "neo_hookean"])
def test_1d_bar_is_uniaxial_stress(name):
    mat = MATS[name]
    par = mat.params(1)
    assert par[0] == 0.0 and par[1] == 0.5 * mat.E
    eps = 1e-6
    F = np.diag([1.0 + eps, 1.0, 1.0])
    sigma = stress(mat, F, dim=1)
    assert sigma[0, 0] == pytest.approx(mat.E * eps, rel=1e-5)
    assert abs(sigma[1, 1]) <= 1e-12 * mat.E * eps
    assert abs(sigma[2, 2]) <= 1e-12 * mat.E * eps
    assert energy(mat, F, dim=1) == pytest.approx(0.5 * mat.E * eps * eps, rel=1e-5)
    assert wave_speed(mat.type_code, par, 1.0) == pytest.approx(math.sqrt(mat.E / mat.rho))
    assert mat.sound_speed(1) == pytest.approx(math.sqrt(mat.E / mat.rho))


# ------------------------------------------------------------------ Tait fluid
@pytest.mark.parametrize("gamma", [7.0, 1.4, 1.0])
def test_tait_pressure_and_potential(gamma):
    mat = TaitFluid(rho=1000.0, kappa=2.0e6, gamma=gamma)
    for J in (0.9, 0.97, 1.0, 1.04, 1.3):
        F = np.diag([J, 1.0, 1.0])
        sigma = stress(mat, F)
        p_eq50 = mat.kappa * ((1.0 / J) ** gamma - 1.0)  # rho/rho0 = 1/J
        assert np.allclose(sigma, -p_eq50 * np.eye(3), rtol=1e-12, atol=1e-9)
        h = 1e-6
        dpsi = (energy(mat, np.diag([J + h, 1.0, 1.0]))
                - energy(mat, np.diag([J - h, 1.0, 1.0]))) / (2.0 * h)
        assert dpsi == pytest.approx(-p_eq50, rel=1e-6, abs=1e-3)
        # sound speed sqrt(dp/drho), rho = rho0 / J
        rho = mat.rho0 / J
        dp = mat.kappa * (((rho + 1e-3) / mat.rho0) ** gamma
                          - ((rho - 1e-3) / mat.rho0) ** gamma) / 2e-3
        assert wave_speed(mat.type_code, mat.params(3), J) == pytest.approx(math.sqrt(dp),
                                                                            rel=1e-7)
    assert energy(mat, np.eye(3)) == 0.0
    assert energy(mat, np.diag([0.8, 1.0, 1.0])) > 0.0
    assert energy(mat, np.diag([1.25, 1.0, 1.0])) > 0.0


def test_tait_viscous_stress_eq49():
    mat = TaitFluid(rho=1000.0, kappa=2.0e6, mu=0.5)
    rng = np.random.default_rng(5)
    L = rng.standard_normal((3, 3))
    F = np.diag([0.95, 1.0, 1.0])
    p = mat.kappa * ((1 / 0.95) ** 7 - 1.0)
    d = 0.5 * (L + L.T)
    expected = 2.0 * mat.mu * (d - np.trace(d) / 3.0 * np.eye(3)) - p * np.eye(3)
    assert rel(stress(mat, F, L), expected) < 1e-12
    assert mat.max_stable_viscous_dt(0.01) == pytest.approx(0.125 * 1e-4 * 1000.0 / 0.5)
    assert math.isinf(TaitFluid(rho=1.0, kappa=1.0).max_stable_viscous_dt(0.01))


# ------------------------------------------------------------------ Maxwell
def maxwell_reference(F, Ci, dt, mu, k, eta):
    """Seed 004 eqs. 14, 16, 17 literally, with numpy linear algebra."""
    J = np.linalg.det(F)
    C = F.T @ F
    Cbar = J ** (-2.0 / 3.0) * C
    X = Ci + dt * mu / eta * Cbar
    Ci_new = np.linalg.det(X) ** (-1.0 / 3.0) * X
    A = Cbar @ np.linalg.inv(Ci_new)
    A_dev = A - np.trace(A) / 3.0 * np.eye(3)
    Cinv = np.linalg.inv(C)
    T = mu * Cinv @ A_dev + k / 10.0 * (J ** 5 - J ** -5) * Cinv
    return F @ T @ F.T / J, Ci_new


@pytest.mark.parametrize("dim", [2, 3])
def test_maxwell_matches_eqs_14_16_17(dim):
    rng = np.random.default_rng(40 + dim)
    mat = MATS["maxwell"]
    F = random_F(rng, dim, 0.25)
    Ci = unimodular_spd(rng, dim)
    state = sym6(Ci)
    dt = 0.03
    sigma = stress(mat, F, ZERO, dt, state, dim)
    sig_ref, Ci_ref = maxwell_reference(F, Ci, dt, mat.mu, mat.k, mat.eta)
    assert rel(full(state), Ci_ref) < 1e-12
    assert rel(sigma, sig_ref) < 1e-10


@pytest.mark.parametrize("dim", [2, 3])
def test_maxwell_with_huge_eta_is_hartmann_neff(dim):
    rng = np.random.default_rng(50 + dim)
    hn = MATS["hartmann_neff"]
    mx = Maxwell(mu=hn.mu, k=hn.k, eta=1e30, rho=hn.rho)
    state = mx.initial_state()
    for _ in range(5):
        F = random_F(rng, dim, 0.3)
        sig_mx = stress(mx, F, ZERO, 1e-3, state, dim)
        assert rel(sig_mx, stress(hn, F, dim=dim)) < 1e-12
        assert energy(mx, F, state, dim) == pytest.approx(energy(hn, F, dim=dim), rel=1e-12)
    assert rel(full(state), np.eye(3)) < 1e-14


@pytest.mark.parametrize("dim", [2, 3])
def test_maxwell_relaxes_deviatoric_stress(dim):
    rng = np.random.default_rng(60 + dim)
    mat = Maxwell(mu=1.0e6, k=4.0e6, eta=1.0e4, rho=2.0)
    F = random_F(rng, dim, 0.3)
    J = np.linalg.det(F)
    dt = 1e-3  # dt mu / eta = 0.1
    state = mat.initial_state()

    def dev(s):
        return s - np.trace(s) / 3.0 * np.eye(3)

    norms = []
    for _ in range(300):
        sigma = stress(mat, F, ZERO, dt, state, dim)
        assert abs(np.linalg.det(full(state)) - 1.0) < 1e-10
        norms.append(np.max(np.abs(dev(sigma))))
        # the volumetric part is not affected by the relaxation
        p_vol = mat.k / 10.0 * (J ** 5 - J ** -5) / J
        assert np.trace(sigma) / 3.0 == pytest.approx(p_vol, rel=1e-9)
    assert np.all(np.diff(norms) <= 1e-9 * norms[0])
    assert norms[-1] < 1e-8 * norms[0]
    # the fixed point of eq. 16 is C_i = C-bar
    C = F.T @ F
    assert rel(full(state), C / np.cbrt(np.linalg.det(C))) < 1e-9


# ------------------------------------------------------------------ wave speed
def uniaxial_c2(mat, J, dim=3):
    """J^2 d sigma_xx / dJ / rho0 under F = diag(J, 1, 1) by central differences."""
    h = 1e-6
    sp = stress(mat, np.diag([J + h, 1.0, 1.0]), ZERO, 0.0, None, dim)[0, 0]
    sm = stress(mat, np.diag([J - h, 1.0, 1.0]), ZERO, 0.0, None, dim)[0, 0]
    return J * J * (sp - sm) / (2.0 * h) / mat.rho0


@pytest.mark.parametrize("name", SOLIDS)
def test_solid_wave_speed(name):
    mat = MATS[name]
    par = mat.params(3)
    c0 = mat.sound_speed()
    assert wave_speed(mat.type_code, par, 1.0) == pytest.approx(c0, rel=1e-12)
    assert uniaxial_c2(mat, 1.0) == pytest.approx(c0 ** 2, rel=1e-6)
    for J in (0.6, 0.85, 1.2, 1.5):
        c = wave_speed(mat.type_code, par, J)
        if name == "linear_elastic":
            assert c == pytest.approx(c0, rel=1e-12)
        else:
            expected = math.sqrt(max(c0 ** 2, uniaxial_c2(mat, J)))
            assert c == pytest.approx(expected, rel=1e-6)
            assert c >= c0 * (1.0 - 1e-12)
    if name in ("linear_elastic", "stvk", "neo_hookean"):
        assert c0 == pytest.approx(math.sqrt((mat.lam + 2.0 * mat.mu) / mat.rho))
    else:
        assert c0 == pytest.approx(math.sqrt((mat.k + 4.0 / 3.0 * mat.mu) / mat.rho))


def test_unknown_type_code_gives_nan():
    sigma = np.zeros((3, 3))
    par = np.zeros(NPAR)
    compute_stress(99, np.eye(3), ZERO, 1e-3, np.zeros(0), par, sigma)
    assert np.all(np.isnan(sigma))
    assert math.isnan(strain_energy(99, np.eye(3), np.zeros(0), par))
    assert math.isnan(wave_speed(99, par, 1.0))


def test_dispatch_calls_the_model_functions():
    rng = np.random.default_rng(7)
    F = random_F(rng, 3)
    L = rng.standard_normal((3, 3))
    funcs = {"linear_elastic": stress_linear_elastic, "stvk": stress_stvk,
             "neo_hookean": stress_neo_hookean, "hartmann_neff": stress_hartmann_neff,
             "maxwell": stress_maxwell, "tait_fluid": stress_tait_fluid}
    for name, fun in funcs.items():
        mat = MATS[name]
        direct = np.zeros((3, 3))
        fun(F, L, 1e-3, mat.initial_state(), mat.params(3), direct)
        assert rel(direct, stress(mat, F, L, 1e-3)) < 1e-13  # fastmath may reorder


# ------------------------------------------------------------------ registry
def test_registry_objects():
    # the type codes are part of the restart and output files: they must not move
    codes = {"linear_elastic": 0, "stvk": 1, "neo_hookean": 2, "hartmann_neff": 3,
             "maxwell": 4, "tait_fluid": 5}
    for name, mat in MATS.items():
        assert mat.type_code == codes[name]
        assert registry.model_of_code(mat.type_code).config is type(mat)
        assert mat.fluid == (name == "tait_fluid")
        assert mat.model == name
        for dim in (1, 2, 3):
            par = mat.params(dim)
            assert par.dtype == np.float64 and par.shape == (NPAR,)
            assert par[PAR_RHO0] == mat.rho0
        st = mat.initial_state()
        assert st.dtype == np.float64 and st.shape == (mat.state_size,)
    assert MATS["maxwell"].state_size == 6
    assert list(MATS["maxwell"].initial_state()) == [1, 1, 1, 0, 0, 0]
    ne = MATS["neo_hookean"]
    assert ne.params(3)[1] == pytest.approx(ne.E / (2 * (1 + ne.nu)))
    assert ne.params(2)[0] == pytest.approx(ne.E * ne.nu / ((1 + ne.nu) * (1 - 2 * ne.nu)))
    with pytest.raises(ValueError):
        ne.params(4)


def test_material_from_table_good():
    m = material_from_table({"model": "neo_hookean", "E": 1e5, "nu": 0.3, "rho": 1500},
                            "materials.rubber", 2)
    assert m == NeoHookean(E=1e5, nu=0.3, rho=1500.0)
    assert isinstance(material_from_table({"model": "st_venant_kirchhoff", "E": 1, "nu": 0,
                                           "rho": 1}, "m", 3), StVenantKirchhoff)
    for alias in ("tait", "tait_fluid", "newtonian_fluid"):
        t = material_from_table({"model": alias, "rho": 1000, "kappa": 2e6}, "m", 2)
        assert t == TaitFluid(rho=1000.0, kappa=2e6, gamma=7.0, mu=0.0)
    hn = material_from_table({"model": "hartmann_neff", "E": 3.5, "nu": 0.4, "rho": 3},
                             "m", 2)
    assert hn.mu == pytest.approx(1.25)
    assert hn.k == pytest.approx(3.5 / (3 * 0.2))
    mx = material_from_table({"model": "maxwell", "mu": 1.25, "k": 5.833, "eta": 0.2,
                              "rho": 3}, "m", 2)
    assert mx == Maxwell(mu=1.25, k=5.833, eta=0.2, rho=3.0)
    assert set(MODELS) >= {"linear_elastic", "stvk", "neo_hookean", "hartmann_neff",
                           "maxwell", "tait", "tait_fluid", "newtonian_fluid"}


RUBBER = {"model": "neo_hookean", "E": 1e5, "nu": 0.3, "rho": 1500}


@pytest.mark.parametrize("change, key, words", [
    ({"nu": 0.5}, "nu", "Poisson ratio must be < 0.5"),
    ({"nu": -1.0}, "nu", "Poisson ratio"),
    ({"rho": -1}, "rho", "> 0"),
    ({"E": None}, "E", "missing"),
    ({"model": "rubbery"}, "model", "valid models: linear_elastic"),
    ({"model": None}, "model", "missing"),
    ({"colour": "red"}, "colour", "unknown key"),
    ({"E": float("nan")}, "E", "finite"),
    ({"E": float("inf")}, "E", "finite"),
    ({"E": True}, "E", "number"),
    ({"E": "1e5"}, "E", "number"),
    ({"E": 0}, "E", "> 0"),
])
def test_material_from_table_errors(change, key, words):
    table = dict(RUBBER)
    for k, v in change.items():
        if v is None:
            del table[k]
        else:
            table[k] = v
    with pytest.raises(ConfigError) as exc:
        material_from_table(table, "materials.rubber", 2)
    assert exc.value.key == f"materials.rubber.{key}"
    assert words in exc.value.reason


@pytest.mark.parametrize("table, key", [
    ({"model": "tait", "rho": 1000, "kappa": 0}, "kappa"),
    ({"model": "tait", "rho": 1000, "kappa": 1e6, "gamma": 0}, "gamma"),
    ({"model": "tait", "rho": 1000, "kappa": 1e6, "mu": -1e-3}, "mu"),
    ({"model": "tait", "kappa": 1e6}, "rho"),
    ({"model": "tait", "rho": 1000, "kappa": 1e6, "E": 1}, "E"),
    ({"model": "maxwell", "mu": 1, "k": 1, "eta": 0, "rho": 1}, "eta"),
    ({"model": "maxwell", "mu": 1, "k": 1, "rho": 1}, "eta"),
    ({"model": "hartmann_neff", "mu": -1, "k": 1, "rho": 1}, "mu"),
    ({"model": "hartmann_neff", "mu": 1, "k": 0, "rho": 1}, "k"),
    ({"model": "hartmann_neff", "E": 1, "nu": 0.5, "rho": 1}, "nu"),
    ({"model": "hartmann_neff", "E": 1, "nu": 0.3, "mu": 1, "rho": 1}, "mu"),
])
def test_material_from_table_errors_other_models(table, key):
    with pytest.raises(ConfigError) as exc:
        material_from_table(table, "materials.x", 3)
    assert exc.value.key == f"materials.x.{key}"


def test_not_a_table():
    with pytest.raises(ConfigError) as exc:
        material_from_table("neo_hookean", "materials.rubber", 2)
    assert exc.value.key == "materials.rubber"


def test_register_refuses_a_taken_code_or_name():
    from dataclasses import dataclass, replace
    from typing import ClassVar

    from pmpmsph.materials.registry import Model, register

    taken = registry.model_of_code(2)

    @dataclass(frozen=True)
    class Clash(NeoHookean):
        type_code: ClassVar[int] = 2
        model: ClassVar[str] = "clash"

    with pytest.raises(ValueError, match="type code 2"):
        register(replace(taken, config=Clash))

    @dataclass(frozen=True)
    class Alias(NeoHookean):
        type_code: ClassVar[int] = 90
        model: ClassVar[str] = "alias"
        aliases: ClassVar[tuple] = ("tait",)

    with pytest.raises(ValueError, match="'tait'"):
        register(Model(Alias, taken.stress, taken.energy, taken.wave_speed))
    assert 90 not in [m.code for m in registry.models()]


def test_the_dispatch_and_the_choice_list_come_from_the_registry():
    codes = [m.code for m in registry.models()]
    assert list(MODELS.values())[0] is registry.model_of_code(codes[0]).config
    for model in registry.models():
        assert MODELS[model.name] is model.config
        assert dispatch._STRESS_BY_CODE[model.code] is model.stress
        assert dispatch._ENERGY_BY_CODE[model.code] is model.energy
