"""ParticleSet.epoch: it changes whenever a row may hold another particle (the mirror clamps
cache the rows they find by gid on it: physics/sph/mirror_clamp.py), and only then."""
import numpy as np

from pmpmsph.particles import ParticleSet


def _set(n):
    p = ParticleSet(2)
    p.append({"gid": np.arange(n), "x": np.random.default_rng(0).random((n, 2))})
    return p


def test_epoch_changes_whenever_rows_change_particle():
    p = _set(6)
    seen = [p.epoch]

    def changed():
        seen.append(p.epoch)
        return seen[-1] != seen[-2]

    p.take(np.array([5, 4, 3, 2, 1, 0]))
    assert changed() and list(p["gid"]) == [5, 4, 3, 2, 1, 0]
    p.remove(np.array([0]))
    assert changed() and p.n_owned == 5
    p.append_halo({"gid": np.array([9]), "x": np.zeros((1, 2))})
    assert changed() and p.n_total == 6
    p.drop_halo()
    assert changed() and p.n_total == p.n_owned
    p.append({"gid": np.array([7]), "x": np.zeros((1, 2))})
    assert changed()


def test_epoch_stays_while_rows_keep_their_particles():
    p = _set(4)
    e = p.epoch
    p.drop_halo()                 # (no halo to drop)
    p["x"][:] += 1.0              # values change, rows keep their particles
    p.move(np.array([1]), 0, np.array([3.0]))
    assert p.epoch == e


def test_move_sets_several_axes_and_takes_no_rows():
    """`move` as the prescribed velocities use it: all held axes of the rows at once, and a
    rank that owns none of a constraint's rows (no error there: the others would wait)."""
    p = _set(4)
    x = p["x"].copy()
    p.move(np.array([0, 2]), np.array([0, 1]), np.array([[5.0, 6.0], [7.0, 8.0]]))
    x[[0, 2]] = [[5.0, 6.0], [7.0, 8.0]]
    assert np.array_equal(p["x"], x)
    p.move(np.zeros(0, np.int64), np.array([0, 1]), np.zeros((0, 2)))
    assert np.array_equal(p["x"], x)
