"""Snapshots and checkpoints of a running Simulation on N ranks (DESIGN.md §6, §8).

Run with `scripts/mpirun -n 2 (or 3) .venv/bin/python -m pytest -m mpi tests/parallel`.
Serial references run in the same job on COMM_SELF; assertions are on global quantities
(sorted by gid) and do not depend on the number of ranks. Every rank makes the same
collective calls in the same order; rank-0-only checks come after the last collective.
"""
import os

import numpy as np
import pytest

from mpi_util import gathered, rel_diff, serial, world
from pmpmsph import Scene
from pmpmsph.errors import ConfigError
from pmpmsph.io import list_snapshots, read_snapshot
from pmpmsph.io.checkpoint import read_checkpoint, write_checkpoint
from scenes import dam_break, two_disks

pytestmark = [pytest.mark.mpi, pytest.mark.timeout(300)]


def fields(sim):
    """The compared state: fluid-only scenes store J instead of F (`mpm.deformation`)."""
    return ("x", "v", "F" if "F" in sim.particles else "J", "sigma", "mass", "vol")


def by_gid(data):
    order = np.argsort(data["gid"])
    return {k: np.asarray(v)[order] for k, v in data.items()}


def left_only():
    """A block in the left slab only: the last rank (and, on 3 ranks, the middle one)
    owns no particle, and never gets one (no balancing)."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1.2, 0.4], cells=[36, 12]),
               time=dict(end=1.0, dt=1e-3), gravity=[0, -9.81],
               parallel=dict(axis="x", balance_every=0))
    sc.material("m", model="neo_hookean", E=1e4, nu=0.3, rho=1000.0)
    sc.body(name="b", material="m", shape="box", min=[0.05, 0.1], max=[0.3, 0.3], ppc=2)
    sc.boundary(face="y-", type="fixed")
    return sc


def dam_break_double():
    """Snapshots every 25 steps in double precision: they are compared with a serial run to
    1e-10, and float32 could round two such values apart."""
    return dam_break().set("output.every_steps", 25).set("output.precision", "double")


def test_snapshot_on_n_ranks_equals_serial_after_sorting(shared_dir):
    dist = world()
    out = os.path.join(shared_dir, "par")
    sim = dam_break_double().simulation(dist=dist, out_dir=out)
    n = dist.sum(sim.particles.n_owned)
    sim.run(max_steps=50)
    sim.close()
    ok = None
    if dist.is_root:
        ref = dam_break_double().simulation(
            dist=serial(), out_dir=os.path.join(shared_dir, "ser"))
        ref.run(max_steps=50)
        ref.close()
        a, b = os.path.join(out, "particles.h5"), os.path.join(shared_dir, "ser", "particles.h5")
        assert [(i.step, i.n_total) for i in list_snapshots(a)] == \
            [(i.step, i.n_total) for i in list_snapshots(b)] == [(0, n), (25, n), (50, n)]
        for index in range(3):
            ta, sa, da = read_snapshot(a, index)
            tb, sb, db = read_snapshot(b, index)
            assert (sa, ta) == (sb, tb)
            da, db = by_gid(da), by_gid(db)
            assert list(da) == list(db)
            for k in da:
                if index == 0:  # before any step: bit for bit
                    np.testing.assert_array_equal(da[k], db[k], err_msg=k)
                else:
                    assert rel_diff(da[k], db[k]) < 1e-10, k
        ok = True
    assert dist.bcast(ok)


def test_rank_without_particles_writes_snapshot_and_checkpoint(shared_dir):
    dist = world()
    out = os.path.join(shared_dir, "left")
    sim = left_only().simulation(dist=dist, out_dir=out)
    counts = dist.gather_counts(sim.particles.n_owned)
    assert counts[-1] == 0 and counts[0] > 0
    sim.run(max_steps=5)
    path = sim.write_checkpoint()
    sim.close()
    names = fields(sim)
    mine = gathered(dist, sim, names)
    ok = None
    if dist.is_root:
        head, rows = read_checkpoint(path)
        assert head["counts"] == counts.tolist() and head["n_ranks"] == dist.size
        assert head["step"] == 5 and head["layout"] == ("mpio" if dist.size > 1 else "serial")
        rows = by_gid(rows)
        for k in names:
            np.testing.assert_array_equal(rows[k], mine[k], err_msg=k)
        _, step, snap = read_snapshot(os.path.join(out, "particles.h5"))
        assert step == 5 and len(snap["gid"]) == counts.sum()
        ok = True
    assert dist.bcast(ok)


@pytest.mark.parametrize("mode", ["auto", "per-rank"])
def test_checkpoint_on_n_ranks_restores_the_same_state(shared_dir, mode):
    """Written on N ranks after 60 steps; restored on N ranks and on one rank: the same
    particles bit for bit; 60 more steps from either equal 120 uninterrupted steps."""
    dist = world()
    path = os.path.join(shared_dir, f"ck_{mode}", "checkpoint.h5")
    sim = two_disks(contact="multi").simulation(dist=dist)
    sim.run(max_steps=60)
    p = sim.particles
    dec = sim.decomposition
    attrs = {"case": "", "dim": 2, "time": sim.time, "step": sim.step_count, "dt": sim.dt,
             "next_snapshot_time": 0.0, "axis": dec.axis, "faces": dec.faces}
    write_checkpoint(dist, path, {k: p[k] for k in p.fields(migrate=True)}, attrs, mode=mode)
    before = gathered(dist, sim, p.fields(migrate=True))

    again = two_disks(contact="multi").simulation(dist=dist)
    again.restore_checkpoint(path)
    after = gathered(dist, again, p.fields(migrate=True))
    for k in before:
        np.testing.assert_array_equal(after[k], before[k], err_msg=k)
    assert (again.time, again.step_count, again.dt) == (sim.time, sim.step_count, sim.dt)
    assert np.array_equal(again.decomposition.faces, dec.faces)

    sim.run(max_steps=60)
    again.run(max_steps=60)
    names = fields(sim)
    ref = gathered(dist, sim, names)
    cont = gathered(dist, again, names)
    one = two_disks(contact="multi").simulation(dist=serial())
    one.restore_checkpoint(path)
    assert one.particles.n_owned == len(before["gid"])
    one.run(max_steps=60)
    solo = by_gid({k: one.particles[k] for k in ("gid",) + names})
    for k in names:
        np.testing.assert_array_equal(cont[k], ref[k], err_msg=k)  # same ranks: bit for bit
        assert rel_diff(solo[k], ref[k]) < 1e-10, k                 # one rank: round-off


def test_serial_checkpoint_restores_on_n_ranks(shared_dir):
    """Restart on a different rank count: written by one rank, continued on N."""
    dist = world()
    path = os.path.join(shared_dir, "one", "checkpoint.h5")
    if dist.is_root:
        one = dam_break(balance_every=0).simulation(dist=serial())
        one.out_dir = os.path.dirname(path)
        one.run(max_steps=40)
        one.write_checkpoint(path)
    dist.barrier()
    sim = dam_break(balance_every=25).simulation(dist=dist)
    sim.restore_checkpoint(path)
    assert sim.step_count == 40
    owned = dist.gather_counts(sim.particles.n_owned)
    assert owned.sum() == dam_break().simulation(dist=serial()).particles.n_owned
    sim.run(max_steps=60)
    ref = dam_break(balance_every=0).simulation(dist=serial())
    ref.run(max_steps=100)
    names = fields(sim)
    mine = gathered(dist, sim, names)
    theirs = by_gid({k: ref.particles[k] for k in ("gid",) + names})
    for k in names:
        assert rel_diff(mine[k], theirs[k]) < 1e-10, k


def test_checkpoint_of_another_case_is_refused_everywhere(shared_dir):
    dist = world()
    path = os.path.join(shared_dir, "other", "checkpoint.h5")
    sim = two_disks().simulation(dist=dist)
    p = sim.particles
    fields = {k: p[k] for k in p.fields(migrate=True)}
    fields["lp"] = np.zeros((p.n_owned, 2))  # a field this case does not declare (GIMP's)
    write_checkpoint(dist, path, fields, {"dim": 2, "time": 0.0, "step": 0, "dt": 1e-3,
                                          "next_snapshot_time": 0.0, "axis": -1,
                                          "faces": np.zeros(0, np.int64)})
    with pytest.raises(ConfigError, match="fields"):
        sim.restore_checkpoint(path)
    with pytest.raises(ConfigError, match="--restart"):
        sim.restore_checkpoint(os.path.join(shared_dir, "nowhere.h5"))
