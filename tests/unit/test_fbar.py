"""F-bar for MPM (kernels/mpm/fbar.py, `[mpm] fbar`): the kernel that scales F to the
averaged volume change, and the choice's checks."""
import numpy as np
import pytest

from pmpmsph.errors import ConfigError
from pmpmsph.kernels.mpm.fbar import fbar_stress
from pmpmsph.kernels.mpm.views import material_table
from pmpmsph.materials.dispatch import compute_stress, material_tag
from pmpmsph.materials.elastic import NeoHookean
from pmpmsph.materials.von_mises import VonMises
from pmpmsph.scene_api import Scene

CLAY = VonMises(E=5e6, nu=0.3, rho=1000.0, yield_stress=1.7e4)
RUBBER = NeoHookean(E=5e6, nu=0.3, rho=1000.0)


@pytest.mark.parametrize("dim", [1, 2, 3])
def test_fbar_keeps_the_deviatoric_part_and_takes_the_average(dim):
    rng = np.random.default_rng(dim)
    n = 6
    F = np.tile(np.eye(3), (n, 1, 1))
    F[:, :dim, :dim] += 0.05 * rng.standard_normal((n, dim, dim))
    J = np.linalg.det(F)
    vol0 = rng.uniform(1.0, 2.0, n)
    vol = J * vol0
    Jbar = np.zeros((n, dim))
    Jbar[:, 0] = J * rng.uniform(0.9, 1.1, n)
    mat = np.array([0, 1, 0, 1, 0, 0], np.int32)  # material 1 (rubber) is not averaged
    types = np.array([CLAY.type_code, RUBBER.type_code], np.int32)
    params = np.stack([CLAY.params(3), RUBBER.params(3)])
    states = np.tile(CLAY.initial_state(), (n, 1))
    sigma = np.zeros((n, 3, 3))
    F0, vol_before = F.copy(), vol.copy()
    table = material_table(material_tag(types), types, params)
    bad = fbar_stress(dim, np.array([True, False]), table, mat, F, vol, vol0, Jbar, 1e-3, states,
                      sigma)
    assert bad == -1
    for p in range(n):
        if mat[p] == 1:  # untouched
            assert np.array_equal(F[p], F0[p]) and vol[p] == vol_before[p]
            assert np.all(sigma[p] == 0.0)
            continue
        assert np.linalg.det(F[p]) == pytest.approx(Jbar[p, 0], rel=1e-13)
        assert vol[p] == pytest.approx(Jbar[p, 0] * vol0[p], rel=1e-14)
        # the same isochoric part: F / J^(1/dim) on the dim x dim block
        iso = F[p, :dim, :dim] / Jbar[p, 0] ** (1.0 / dim)
        assert np.abs(iso - F0[p, :dim, :dim] / J[p] ** (1.0 / dim)).max() < 1e-13
        assert np.array_equal(F[p, dim:, dim:], F0[p, dim:, dim:])
        ref = np.zeros((3, 3))
        compute_stress(CLAY.type_code, F[p], np.zeros((3, 3)), 1e-3, CLAY.initial_state(),
                       CLAY.params(3), ref)
        assert np.abs(sigma[p] - ref).max() <= 1e-12 * np.abs(ref).max()


def test_fbar_needs_a_plastic_mpm_body():
    sc = Scene(2, time=dict(end=0.1, cfl=0.5), grid=dict(origin=[0, 0], length=[1, 1],
                                                        cells=[4, 4]), mpm=dict(fbar=True))
    sc.material("rubber", model="neo_hookean", E=1e5, nu=0.3, rho=1000.0)
    sc.body(name="b", material="rubber", shape="box", min=[0.2, 0.2], max=[0.6, 0.6], ppc=2)
    with pytest.raises(ConfigError) as err:
        sc.case()
    assert err.value.key == "mpm.fbar"
