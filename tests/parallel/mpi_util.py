"""Helpers for tests run under mpirun: gather a field sorted by gid, a serial reference."""
import numpy as np
import pytest

from pmpmsph.parallel.distributor import Distributor


def world():
    dist = Distributor()
    if dist.size < 2:
        pytest.skip("needs mpirun with 2 or more ranks")
    return dist


def serial():
    from mpi4py import MPI

    return Distributor(MPI.COMM_SELF)


def gathered(dist, sim, names):
    """Global arrays of `names`, sorted by gid, on every rank."""
    p = sim.particles
    gid = np.concatenate(dist.allgather(p["gid"].copy()))
    order = np.argsort(gid)
    out = {"gid": gid[order]}
    for name in names:
        out[name] = np.concatenate(dist.allgather(p[name].copy()))[order]
    return out


def rel_diff(a, b):
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def assert_equals_one_rank(dist, sim, ref, names, exact=(), rtol=1e-10):
    """The N-rank run `sim` holds the particles of the one-rank run `ref` (matched by gid):
    `exact` fields bit for bit, `names` to `rtol` relative (DESIGN.md §4 invariant)."""
    mine = gathered(dist, sim, tuple(names) + tuple(exact))
    p = ref.particles
    order = np.argsort(p["gid"])
    assert np.array_equal(mine["gid"], p["gid"][order])
    for name in exact:
        assert np.array_equal(mine[name], p[name][order]), name
    for name in names:
        assert rel_diff(mine[name], p[name][order]) < rtol, name
