"""The Mooney-Rivlin solid (pmpmsph/materials/mooney_rivlin.py): the material added as one
file through the registry. Stress against its energy, its limits, objectivity, wave speed,
the configuration checks, and a run (scene 3's two disks)."""
import math
from pathlib import Path

import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph.config.load import load_case_text
from pmpmsph.errors import ConfigError
from pmpmsph.materials import MODELS, material_from_table
from pmpmsph.materials.dispatch import compute_stress, strain_energy, wave_speed
from pmpmsph.materials.mooney_rivlin import MooneyRivlin
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.simulation import Simulation

ROOT = Path(__file__).resolve().parents[2]
MAT = MooneyRivlin(C10=3.0e5, C01=1.2e5, k=5.0e6, rho=1100.0)
NONE = np.zeros(0)


def stress(F, mat=MAT):
    sigma = np.full((3, 3), np.nan)
    compute_stress(mat.type_code, F, np.zeros((3, 3)), 0.0, NONE, mat.params(3), sigma)
    return sigma


def energy(F, mat=MAT):
    return strain_energy(mat.type_code, F, NONE, mat.params(3))


def random_F(rng, dim, amp=0.2):
    while True:
        F = np.eye(3)
        F[:dim, :dim] += amp * rng.standard_normal((dim, dim))
        if np.linalg.det(F) > 0.5:
            return F


def test_registered_by_its_own_module():
    assert MODELS["mooney_rivlin"] is MooneyRivlin
    assert np.all(stress(np.eye(3)) == 0.0) and energy(np.eye(3)) == 0.0


@pytest.mark.parametrize("dim", [2, 3])
def test_kirchhoff_stress_is_the_derivative_of_the_energy(dim):
    """tau = dpsi/dF F^T (central differences, step 1e-6)."""
    rng = np.random.default_rng(3)
    for _ in range(5):
        F = random_F(rng, dim)
        dpsi = np.zeros((3, 3))
        for i in range(3):
            for j in range(3):
                d = np.zeros((3, 3))
                d[i, j] = 1e-6
                dpsi[i, j] = (energy(F + d) - energy(F - d)) / 2e-6
        tau = np.linalg.det(F) * stress(F)
        assert np.abs(dpsi @ F.T - tau).max() < 1e-6 * np.abs(tau).max()


def test_closed_forms_neo_hookean_limit_and_objectivity():
    rng = np.random.default_rng(5)
    F = random_F(rng, 3)
    J = np.linalg.det(F)
    Bb = J ** (-2.0 / 3.0) * F @ F.T
    I = np.eye(3)

    def dev(A):
        return A - np.trace(A) / 3.0 * I
    c10, c01, k = MAT.C10, MAT.C01, MAT.k
    want = (2.0 * dev((c10 + c01 * np.trace(Bb)) * Bb - c01 * Bb @ Bb) / J + k * (J - 1) * I)
    assert np.abs(stress(F) - want).max() < 1e-10 * np.abs(want).max()
    nh = MooneyRivlin(C10=c10, C01=0.0, k=k, rho=1.0)
    assert np.abs(stress(F, nh) - (2 * c10 * dev(Bb) / J + k * (J - 1) * I)).max() < 1e-4
    q, r = np.linalg.qr(rng.standard_normal((3, 3)))
    Q = q * np.sign(np.diag(r))
    if np.linalg.det(Q) < 0:
        Q[:, 0] *= -1
    assert np.abs(stress(Q @ F) - Q @ stress(F) @ Q.T).max() < 1e-9 * np.abs(want).max()


def test_small_strain_is_linear_elastic_with_mu_2_c10_plus_c01():
    eps = 1e-7 * np.array([[1.0, 0.4, -0.3], [0.4, -2.0, 0.5], [-0.3, 0.5, 0.7]])
    mu = 2.0 * (MAT.C10 + MAT.C01)
    lam = MAT.k - 2.0 / 3.0 * mu
    lin = lam * np.trace(eps) * np.eye(3) + 2.0 * mu * eps
    assert np.abs(stress(np.eye(3) + eps) - lin).max() < 1e-6 * np.abs(lin).max()


def test_wave_speed_is_that_of_uniaxial_strain():
    """c^2 = J^2 d sigma_xx/dJ / rho0 in F = diag(J, 1, 1) where that exceeds the at-rest
    value (k + 4/3 mu)/rho0, which it never falls below."""
    par = MAT.params(3)
    c0 = MAT.sound_speed()
    assert wave_speed(MAT.type_code, par, 1.0) == pytest.approx(c0, rel=1e-14)
    for J in (0.6, 0.8, 0.95, 1.05, 1.3, 1.8):
        sxx = [stress(np.diag([J + s, 1.0, 1.0]))[0, 0] for s in (-1e-6, 1e-6)]
        c2 = J * J * (sxx[1] - sxx[0]) / 2e-6 / MAT.rho
        assert wave_speed(MAT.type_code, par, J) == pytest.approx(
            math.sqrt(max(c2, c0 * c0)), rel=1e-6)


def test_configuration_checks():
    m = material_from_table({"model": "mooney_rivlin", "C10": 1e5, "C01": -2e4, "k": 1e7,
                             "rho": 1000}, "materials.rubber", 2)
    assert m == MooneyRivlin(C10=1e5, C01=-2e4, k=1e7, rho=1000.0)
    for table, key in (({"C10": 1e5, "C01": -1e5, "k": 1e7, "rho": 1}, "materials.r.C10"),
                       ({"C10": 1e5, "C01": 0, "k": -1, "rho": 1}, "materials.r.k"),
                       ({"C10": 1e5, "C01": 0, "k": 1e7}, "materials.r.rho"),
                       ({"C10": 1e5, "C01": 0, "k": 1e7, "rho": 1, "E": 3}, "materials.r.E")):
        with pytest.raises(ConfigError) as err:
            material_from_table({"model": "mooney_rivlin", **table}, "materials.r", 2)
        assert err.value.key == key


def test_two_disks_of_mooney_rivlin_rubber():
    """Scene 3 (cases/two_disks.toml) with the disks in Mooney-Rivlin rubber of the case's
    small-strain moduli (mu = E/(2 (1 + nu)) split 70/30 between C10 and C01, k = E/(3 (1 -
    2 nu))), to T = 2 (past the first contact). Measured: total energy -0.128 % (neo-Hookean
    -0.129 %), kinetic minimum 0.129 J at t = 1.96 (neo-Hookean 0.134 J), momentum 2e-11."""
    E, nu = 1000.0, 0.3
    mu, k = E / (2 * (1 + nu)), E / (3 * (1 - 2 * nu))
    text = (ROOT / "cases" / "two_disks.toml").read_text().replace(
        'model = "stvk"\nE = 1000.0\nnu = 0.3\n',
        f'model = "mooney_rivlin"\nC10 = {0.35 * mu!r}\nC01 = {0.15 * mu!r}\nk = {k!r}\n')
    case = load_case_text(text, overrides=[("time.end", 2.0)])
    sim = Simulation(case, dist=Distributor(MPI.COMM_SELF))
    e0 = sim.diagnostics()["total"]
    kinetic = []
    while sim.time < 2.0 - 1e-12:
        sim.step()
        if len(kinetic) < sim.time * 100:
            kinetic.append(sim.diagnostics()["kinetic"])
    d = sim.diagnostics()
    assert abs(d["total"] / e0 - 1.0) < 0.003
    assert abs(d["px"]) < 1e-9 and abs(d["py"]) < 1e-9
    assert 0.11 < min(kinetic) < 0.15  # the disks met and squeezed (neo-Hookean: 0.134)
