"""The reaction of a `[[prescribed]]` constraint (physics/loads.py PrescribedVelocity), the
diagnostics columns reaction{j}_x, ...: an elastic column under gravity held at its foot.
The only forces on the column are gravity and the constraint's, so over every diagnostics
row the mean reaction is the momentum change over the time plus the weight,
R_y = dP_y / dt + M g, exactly (to round-off) in MPM and in SPH."""
import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph.io.diagnostics import read_diagnostics
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.scene_api import Scene

G = 9.81


def _column(method, tmp_path=None):
    kw = (dict(grid=dict(origin=[0.0, 0.0], length=[1.0, 1.0], cells=[20, 20]))
          if method == "mpm" else dict(domain=dict(min=[0.0, 0.0], max=[1.0, 1.0])))
    sc = Scene(2, time=dict(end=0.15, cfl=0.3), gravity=[0.0, -G],
               output=dict(every=0.05, diagnostics_every=10),
               prescribed=[dict(body="col", box=dict(min=[0.0, 0.0], max=[1.0, 0.3]),
                                velocity=[0.0, 0.0])], **kw)
    sc.material("rubber", model="neo_hookean", E=1e5, nu=0.3, rho=1000.0)
    sc.body(name="col", material="rubber", shape="box", min=[0.4, 0.2], max=[0.6, 0.8],
            spacing=0.025, method=method)
    out = dict(out_dir=str(tmp_path), overwrite=True) if tmp_path else dict(write_output=False)
    return sc.simulation(dist=Distributor(MPI.COMM_SELF), **out)


@pytest.mark.parametrize("method", ["mpm", "sph"])
def test_reaction_balances_momentum_and_weight(method):
    sim = _column(method)
    rows = [sim.diagnostics()]
    weight = rows[0]["mass"] * G
    assert np.isnan(rows[0]["reaction0_y"])  # no step yet
    while sim.time < sim.case.time.end - 1e-12:
        for _ in range(10):
            sim.step()
        rows.append(sim.diagnostics())
    assert len(rows) > 5
    for a, b in zip(rows[:-1], rows[1:]):
        dt = b["time"] - a["time"]
        assert abs(b["reaction0_y"] - ((b["py"] - a["py"]) / dt + weight)) < 1e-12 * weight
        assert abs(b["reaction0_x"] - (b["px"] - a["px"]) / dt) < 1e-12 * weight
    assert 0.5 * weight < rows[-1]["reaction0_y"] < 2.0 * weight  # the column rests on it


def test_reaction_columns_in_diagnostics_csv(tmp_path):
    sim = _column("mpm", tmp_path)
    sim.run()
    table = read_diagnostics(tmp_path / "diagnostics.csv")
    assert "reaction0_x" in table and "reaction0_y" in table and "reaction0_z" not in table
    assert np.isnan(table["reaction0_y"][0]) and np.all(np.isfinite(table["reaction0_y"][1:]))
    assert np.all(table["reaction0_y"][1:] > 0.0)
