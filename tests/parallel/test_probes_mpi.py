"""`[[probes]]` on N ranks read what they read on one (DESIGN.md §4 invariant; docs/probes.md):
RUN/probes.csv of an N-rank run equals the rows of the one-rank run to 1e-10 of each
column's scale. Run under `scripts/mpirun -n 2` and `-n 3`; the serial reference runs on
MPI.COMM_SELF in the same processes (rows kept in memory: no output folder)."""
import os

import numpy as np
import pytest

from mpi_util import serial, world
from pmpmsph.io.diagnostics import read_diagnostics
from scenes import loaded_bar, sph_dam_break

pytestmark = pytest.mark.mpi


def _dam_break_probes():
    """The SPH dam break (slabs along y, balanced every 25 steps: water crosses the faces)
    with points in the falling column and on the floor, two gauges and the walls' force."""
    sc = sph_dam_break(dx=0.05, balance_every=25, axis="x")
    sc.data["probes"] = [
        dict(name="low", kind="point", position=[0.5, 0.3],
             fields=["pressure", "density", "velocity", "stress"]),
        dict(name="toe", kind="point", position=[1.2, 0.1], fields=["pressure", "velocity"]),
        dict(name="g_mid", kind="gauge", position=[0.5]),
        dict(name="g_toe", kind="gauge", position=[1.5], step=0.01),
        dict(name="tank", kind="force", walls=True),
    ]
    sc.data["output"] = dict(probes_every=0.004)
    return sc


def _bar_probes():
    """The loaded MPM bar (fixed face, traction, a [[prescribed]] block until 0.01 s)."""
    sc = loaded_bar()
    sc.data["probes"] = [
        dict(name="held", kind="force", prescribed=0),
        dict(name="mid", kind="point", position=[1.0, 0.2], fields=["stress", "velocity"]),
    ]
    sc.data["output"] = dict(probes_every=0.002)
    return sc


def _compare(dist, path, rows):
    """probes.csv at `path` (written by the N-rank run) against the one-rank `rows`."""
    if not dist.is_root:
        return
    table = read_diagnostics(path)
    assert list(table) == list(rows[0])
    assert np.array_equal(table["step"], [r["step"] for r in rows])
    for key in table:
        ref = np.array([r[key] for r in rows], float)
        got = np.asarray(table[key], float)
        assert np.array_equal(np.isnan(got), np.isnan(ref)), key
        finite = np.abs(ref[np.isfinite(ref)])  # (a dry gauge reads nan all along)
        scale = max(finite.max(), 1e-300) if len(finite) else 1.0
        np.testing.assert_allclose(got, ref, rtol=0.0, atol=1e-10 * scale, equal_nan=True,
                                   err_msg=key)


@pytest.mark.parametrize("scene,steps", [(_dam_break_probes, 300), (_bar_probes, 150)])
def test_probes_equal_one_rank(scene, steps, shared_dir):
    dist = world()
    out = os.path.join(shared_dir, scene.__name__)
    sim = scene().simulation(dist=dist, out_dir=out, overwrite=True)
    ref = scene().simulation(dist=serial(), write_output=False)
    sim.run(max_steps=steps)
    sim.close()
    ref.run(max_steps=steps)
    assert len(ref.probes.rows) > 5
    _compare(dist, os.path.join(out, "probes.csv"), ref.probes.rows)
    if scene is _dam_break_probes:  # the probes read something: wet gauges, a loaded floor
        last = ref.probes.rows[-1]
        assert 0.5 < last["g_mid_elevation"] < 2.0
        assert last["low_pressure"] > 0.0 and last["tank_fy"] < 0.0
