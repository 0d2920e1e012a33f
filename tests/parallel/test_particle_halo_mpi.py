"""ParticleHalo: each rank receives exactly the neighbours' particles within the halo width
of its faces, with their field values, and the owned rows are untouched."""
import numpy as np
import pytest

from mpi_util import world
from scenes import dam_break

pytestmark = pytest.mark.mpi


def test_halo_contents():
    from pmpmsph.parallel.particle_halo import ParticleHalo

    dist = world()
    sim = dam_break().simulation(dist=dist)
    sim.run(max_steps=50)
    p, dec = sim.particles, sim.decomposition
    width = 0.5
    owned_before = {k: p[k].copy() for k in ("gid", "x", "v")}
    halo = ParticleHalo(dec, p, width)
    n_recv = halo.exchange()
    assert p.n_total == p.n_owned + n_recv
    for k, v in owned_before.items():
        assert np.array_equal(p[k], v)
    # the expected halo: every particle of any rank within `width` outside my slab's faces
    gid_all = np.concatenate(dist.comm.allgather(owned_before["gid"]))
    x_all = np.concatenate(dist.comm.allgather(owned_before["x"]))
    v_all = np.concatenate(dist.comm.allgather(owned_before["v"]))
    xa = x_all[:, dec.axis]
    lo = dec.origin + dec.lo_cell * dec.dx
    hi = dec.origin + dec.hi_cell * dec.dx
    owner = dec.owner(x_all)
    want = np.zeros(len(gid_all), bool)
    if dec.left is not None:
        want |= (owner == dec.left) & (xa >= lo - width)
    if dec.right is not None:
        want |= (owner == dec.right) & (xa < hi + width)
    got_gid = p.with_halo("gid")[p.n_owned:]
    assert np.array_equal(np.sort(got_gid), np.sort(gid_all[want]))
    order = np.argsort(got_gid)
    ref = np.argsort(gid_all[want])
    assert np.array_equal(p.with_halo("x")[p.n_owned:][order], x_all[want][ref])
    assert np.array_equal(p.with_halo("v")[p.n_owned:][order], v_all[want][ref])
    assert dist.sum(n_recv) > 0
    # a second exchange rebuilds, not accumulates
    assert halo.exchange() == n_recv and p.n_total == p.n_owned + n_recv
