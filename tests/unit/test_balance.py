"""Load balancing by measured time (`[parallel] balance_by = "time"`): the modelled work of
each layer is scaled by its owner's measured seconds per work unit, so a rank that runs
slower per particle is given fewer layers."""
import numpy as np
import pytest

from pmpmsph.parallel.balance import balanced_faces, calibrated_work, imbalance


def test_calibration_reproduces_the_measured_times_and_moves_the_face():
    work = np.ones(10)
    faces = np.array([0, 5, 10])
    busy = [2.0, 1.0]  # rank 0 took twice as long for the same modelled work
    scaled = calibrated_work(faces, work, busy)
    np.testing.assert_allclose([scaled[:5].sum(), scaled[5:].sum()], busy)
    assert imbalance(faces, scaled) == pytest.approx(2.0 / 1.5 - 1.0)
    new = balanced_faces(scaled, 2, 1)
    assert new[1] == 4  # 4 layers x 0.4 s against 1 x 0.4 + 5 x 0.2: 1.6 s / 1.4 s
    assert imbalance(new, scaled) < imbalance(faces, scaled)


def test_a_rank_without_work_takes_the_mean_rate():
    work = np.array([0.0, 0.0, 3.0, 3.0])
    faces = np.array([0, 2, 4])
    scaled = calibrated_work(faces, work, [0.0, 6.0])
    np.testing.assert_allclose(scaled, [0.0, 0.0, 3.0, 3.0])


class _Slabs:
    """The parts of a Decomposition that `LoadBalancer.propose` reads (one process)."""

    def __init__(self, faces, ncells=10):
        self.faces = np.array(faces)
        self.size = len(faces) - 1
        self.ncells = ncells
        self.min_slab = 1
        self.dist = self

    def sum(self, a):
        return a

    def cell_of(self, x):
        return np.clip(np.floor(x[:, 0]).astype(np.int64), 0, self.ncells - 1)


def test_a_marginal_measured_imbalance_moves_faces_only_when_seen_twice_in_a_row():
    from pmpmsph.parallel.balance import LoadBalancer

    dec = _Slabs([0, 5, 10])
    x = np.repeat(np.arange(10) + 0.5, 100)[:, None]  # 100 particles in each cell layer
    lb = LoadBalancer(every=25, threshold=0.2)
    slow_left = [1.6, 1.0]  # imbalance 0.23 (< 3 x threshold): marginal
    assert lb.propose(dec, x, 0.0, slow_left)[0] is None         # first sighting: wait
    assert lb.propose(dec, x, 0.0, [1.0, 2.0])[0] is None        # the other rank: noise
    assert lb.propose(dec, x, 0.0, slow_left)[0] is None         # seen once again
    faces, before, after = lb.propose(dec, x, 0.0, slow_left)    # twice in a row: move
    assert faces is not None and faces[1] < 5 and after < 0.5 * before
    assert lb.propose(dec, x, 0.0, None)[0] is None               # the model: balanced


def test_a_large_measured_imbalance_moves_faces_at_once():
    from pmpmsph.parallel.balance import LoadBalancer

    dec = _Slabs([0, 5, 10])
    x = np.repeat(np.arange(10) + 0.5, 100)[:, None]
    faces, before, after = LoadBalancer(every=25, threshold=0.05).propose(dec, x, 0.0,
                                                                          [2.0, 1.0])
    assert before > 0.15 and faces is not None and faces[1] < 5


def test_particles_weigh_by_their_method():
    """The modelled work counts an SPH particle as PARTICLE_COST[1] MPM points and a wall
    particle as PARTICLE_COST[2]: 5 layers of SPH water against 5 of MPM points and walls
    (the same number of particles) are not balanced, and the face moves into the water."""
    from pmpmsph.parallel.balance import PARTICLE_COST, LoadBalancer, layer_work

    dec = _Slabs([0, 5, 10])
    x = np.repeat(np.arange(10) + 0.5, 100)[:, None]
    method = np.repeat([1] * 5 + [0, 2] * 2 + [0], 100).astype(np.int8)
    work = layer_work(dec, x, 0.0, method)
    np.testing.assert_allclose(work[:5], 100 * PARTICLE_COST[1])
    np.testing.assert_allclose(work[5:], 100 * PARTICLE_COST[[0, 2, 0, 2, 0]])
    np.testing.assert_array_equal(layer_work(dec, x, 0.0), np.full(10, 100.0))
    faces, before, after = LoadBalancer(every=25, threshold=0.05).propose(
        dec, x, 0.0, None, method)
    assert before > 0.2 and faces is not None and faces[1] == 4
    assert after < 0.5 * before
