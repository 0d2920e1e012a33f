"""Fluids store J = det F instead of F (`mpm.deformation`, `particles.J_FIELD`).

A fluid's stress depends on J and the velocity gradient only (seed 003, eqs. 49-50), and
J <- det(I + dt L) J is the determinant of F <- (I + dt L) F (eq. 82). So the J-only run of a
scene must be the full-F run up to rounding: 200 steps of the throughput scene (a falling
Tait block hitting the floor, quadratic B-splines) and 100 of a viscous 3D drop agree to 1e-10,
with J equal to det F. "auto" picks J exactly when every MPM material is a fluid; J alone is
refused, naming the key, for solids and SPH.
"""
import numpy as np
import pytest

from pmpmsph.bench.throughput import mpm_peer_scene
from pmpmsph.errors import ConfigError
from pmpmsph.scene_api import Scene


def _pair(make):
    runs = {}
    for mode in ("F", "J"):
        sc = make()
        sc.set("mpm.deformation", mode)
        runs[mode] = sc.simulation(write_output=False)
    return runs


def _viscous_drop_3d():
    sc = Scene(3, grid=dict(origin=[0, 0, 0], length=[1, 1, 1], cells=[8, 8, 8]),
               time=dict(end=1e9, cfl=0.4), gravity=[0, 0, -9.81],
               mpm=dict(shape="gimp", transfer="musl", flip=0.9))
    sc.material("oil", model="tait", rho=900.0, kappa=2e4, gamma=7.0, mu=5.0)
    sc.body(name="drop", material="oil", shape="box", min=[0.3, 0.3, 0.4],
            max=[0.6, 0.6, 0.7], ppc=2, velocity=[0.5, 0.0, -1.0])
    for face in ("x-", "x+", "y-", "y+", "z-", "z+"):
        sc.boundary(face=face, type="slip")
    return sc


@pytest.mark.parametrize("make, steps", [(lambda: mpm_peer_scene(32), 200),
                                         (_viscous_drop_3d, 100)],
                         ids=["tait_2d_pic_usl", "viscous_3d_gimp_musl"])
def test_J_storage_equals_F_storage(make, steps):
    runs = _pair(make)
    full, lean = runs["F"], runs["J"]
    assert "F" in full.particles and "F" not in lean.particles and "J" in lean.particles
    full.run(max_steps=steps)
    lean.run(max_steps=steps)
    for name in ("x", "v", "sigma", "vol"):
        a, b = lean.particles[name], full.particles[name]
        assert np.abs(a - b).max() <= 1e-10 * np.abs(b).max(), name
    detF = np.linalg.det(full.particles["F"])
    assert np.abs(lean.particles["J"] - detF).max() <= 1e-10
    assert np.abs(detF - 1.0).max() > 1e-4  # it was compressed
    assert full.diagnostics()["strain"] == pytest.approx(lean.diagnostics()["strain"],
                                                         rel=1e-9)


def test_auto_picks_J_for_fluids_only():
    assert "J" in mpm_peer_scene(16).simulation(write_output=False).particles
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[8, 8]),
               time=dict(end=1.0, dt=1e-4))
    sc.material("steel", model="linear_elastic", E=1e5, nu=0.3, rho=1000.0)
    sc.body(name="b", material="steel", shape="box", min=[0.2, 0.2], max=[0.6, 0.6], ppc=2)
    assert "F" in sc.simulation(write_output=False).particles
    sc.set("mpm.deformation", "J")
    with pytest.raises(ConfigError) as err:
        sc.simulation(write_output=False)
    assert err.value.key == "mpm.deformation"
