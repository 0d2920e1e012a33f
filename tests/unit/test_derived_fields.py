"""The output fields computed when a snapshot is written (io/derived_fields.py): pressure,
von Mises stress, equivalent plastic strain and the yield flag, on a plastic impact."""
import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph.errors import ConfigError
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.scene_api import Scene

YIELD, HARDENING = 3e8, 1e8


def _bars(model="von_mises", fields=None):
    """Two aluminium bars meeting at 2 x 200 m/s (tests/unit/test_von_mises.py, coarser)."""
    out = {} if fields is None else {"output": {"fields": fields}}
    sc = Scene(2, time=dict(end=6e-6, cfl=0.3), gravity=[0.0, 0.0],
               grid=dict(origin=[0.0, 0.0], length=[0.08, 0.04], cells=[32, 16]),
               mpm=dict(shape="gimp", transfer="usl"), **out)
    if model == "von_mises":
        sc.material("al", model="von_mises", E=70e9, nu=0.33, rho=2700.0,
                    yield_stress=YIELD, hardening=HARDENING)
    else:
        sc.material("al", model="neo_hookean", E=70e9, nu=0.33, rho=2700.0)
    for name, lo, v in (("a", 0.0075, 200.0), ("b", 0.04, -200.0)):
        sc.body(name=name, material="al", shape="box", min=[lo, 0.01], max=[lo + 0.0325, 0.03],
                spacing=0.00125, velocity=[v, 0.0])
    return sc.simulation(dist=Distributor(MPI.COMM_SELF), write_output=False)


def test_plastic_fields_in_default_output_and_on_the_yield_surface():
    sim = _bars()
    assert {"pressure", "mises", "plastic_strain", "yielding"} <= set(sim.case.output.fields)
    sim.run()
    out = sim.snapshot_fields()
    p = sim.particles
    n = p.n_owned
    sigma = p["sigma"][:n]
    assert np.allclose(out["pressure"], -np.trace(sigma, axis1=1, axis2=2) / 3.0, rtol=0,
                       atol=1e-12 * YIELD)
    dev = sigma + out["pressure"][:, None, None] * np.eye(3)
    assert np.allclose(out["mises"], np.sqrt(1.5 * np.sum(dev * dev, axis=(1, 2))), rtol=1e-14)
    alpha = out["plastic_strain"]
    assert np.array_equal(alpha, p["mstate"][:n, 6])
    flow = out["yielding"].astype(bool)
    assert out["yielding"].dtype == np.uint8 and 0.05 < flow.mean() < 0.95
    # the rows that flowed in the last update sit on the yield surface: J q = sigma_y + H alpha
    # (q the Mises stress of the Kirchhoff stress); the others inside it
    J = np.linalg.det(p["F"][:n])
    ratio = J * out["mises"] / (YIELD + HARDENING * alpha)
    assert np.abs(ratio[flow] - 1.0).max() < 1e-10
    assert ratio[~flow].max() <= 1.0 + 1e-10
    assert alpha[flow].min() > 0.0


def test_plastic_fields_refused_without_a_plastic_material():
    with pytest.raises(ConfigError) as err:
        _bars("neo_hookean", fields=["gid", "x", "plastic_strain"])
    assert err.value.key == "output.fields[2]"
    sim = _bars("neo_hookean", fields=["gid", "x", "pressure", "mises"])
    assert "plastic_strain" not in sim.case.output.fields
    out = sim.snapshot_fields()
    assert np.allclose(out["pressure"], 0.0) and np.allclose(out["mises"], 0.0)
