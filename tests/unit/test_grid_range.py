"""`Grid.work_range`: only the node layers the particles can reach are reset and solved, and
the result is the full grid's, bit for bit (physics/mpm/grid.py)."""
import numpy as np

from pmpmsph.config.case import GridSpec
from pmpmsph.physics.mpm.grid import Grid
from pmpmsph.scene_api import Scene


def _grid():
    return Grid(GridSpec(origin=(0.0, 0.0), cell_size=(0.1, 0.1), cells=(20, 10)))


def test_range_covers_the_particles_and_hulls_the_last_one():
    g = _grid()  # 21 + 2 x 2 pad node layers along x
    stride = g.strides[0]
    x = np.array([[0.55, 0.3], [0.95, 0.7]])
    # cells 5 and 9 are node layers 7 and 11 (two pad layers); two layers of margin
    assert g.work_range(x, 2, margin=2) == (5 * stride, 14 * stride)
    x[:, 0] += 1.0  # the particles move on: the new range is hulled with the old one
    assert g.work_range(x, 2, margin=2) == (5 * stride, 24 * stride)
    assert g.work_range(x, 2, margin=2) == (15 * stride, 24 * stride)
    # layers shared with neighbours are kept even without particles
    assert g.work_range(x, 0, margin=2, keep_lo=7) == (0, 24 * stride)
    assert g.work_range(x, 0, margin=2, keep_lo=7, keep_hi=7) == (0, 25 * stride)
    x[0, 0] = np.nan  # a failing step: every node
    assert g.work_range(x, 2, margin=2) == (0, g.n_nodes)


def _dam(trim):
    sc = Scene(2, grid=dict(origin=[0, 0], length=[16, 4], cells=[128, 32]),
               time=dict(end=1.0, dt=1e-3), gravity=[0, -9.81],
               mpm=dict(shape="quadratic", transfer="musl"))
    sc.material("water", model="tait", rho=1000.0, kappa=2e5, gamma=7.0, mu=0.01)
    sc.body(name="water", material="water", shape="box", min=[0, 0], max=[2, 2], ppc=2)
    for face in ("x-", "x+", "y-", "y+"):
        sc.boundary(face=face, type="slip")
    sim = sc.simulation()
    if not trim:
        every = sim.mpm.grid.shape[0]
        sim.mpm._keep = (every, every)
    return sim


def test_trimmed_grid_gives_the_full_grids_state_bit_for_bit():
    """A dam break whose front runs into the empty half of the tank: 300 steps with the
    trimmed grid equal those with every node reset and solved, exactly; the untouched
    nodes hold zeros."""
    runs = []
    for trim in (True, False):
        sim = _dam(trim)
        sim.run(max_steps=300)
        runs.append(sim)
    t, f = runs
    assert t.mpm._span[1] - t.mpm._span[0] < t.mpm.grid.n_nodes  # it did trim
    for name in ("x", "v", "J", "sigma"):
        assert np.array_equal(t.particles[name], f.particles[name]), name
    a, b = t.mpm._span
    outside = np.r_[0:a, b:t.mpm.grid.n_nodes]
    assert not np.any(t.mpm.grid.mass[:, outside]) and not np.any(t.mpm.grid.vel[:, outside])
    assert np.array_equal(t.mpm.grid.vel, f.mpm.grid.vel)
