"""Multi-field contact on N ranks equals one rank (DESIGN.md §4): the bodies' reaches at the
nodes the slab faces cut are the largest over the ranks (GridHalo.maximum)."""
import numpy as np
import pytest

from mpi_util import assert_equals_one_rank, serial, world
from pmpmsph.bench.floats import float_scene

pytestmark = pytest.mark.mpi


def test_mpm_block_in_mpm_water_equals_one_rank():
    """A block 0.1 wide across the middle of a tank 0.5 wide (the slab faces of 2 and 3
    ranks cut it), released on the surface of MPM water, each in its own velocity field:
    300 steps with the contact acting under and beside the block."""
    dist = world()
    kw = dict(spacing=0.01, cell_spacings=2, drop=0.0, end=1.0)
    sim = float_scene("mpm_in_mpm", **kw).simulation(dist=dist, write_output=False)
    ref = float_scene("mpm_in_mpm", **kw).simulation(dist=serial(), write_output=False)
    sim.run(max_steps=300)
    ref.run(max_steps=300)
    block = ref.particles["body"] == 1
    assert np.mean(ref.particles["v"][block, 1]) < -1e-3  # sinking into the water
    assert_equals_one_rank(dist, sim, ref, ("x", "v", "sigma", "F"))
