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
    gid = np.concatenate(dist.comm.allgather(p["gid"].copy()))
    order = np.argsort(gid)
    out = {"gid": gid[order]}
    for name in names:
        out[name] = np.concatenate(dist.comm.allgather(p[name].copy()))[order]
    return out


def rel_diff(a, b):
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))
