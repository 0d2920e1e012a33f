"""Lazy migration (parallel/migration.py `MigrationSchedule`): due once the farthest stray past
a slab face plus twice the next step's move passes SLACK times the reach, from measured
positions (`kernels.partition.max_stray`), whatever moved them."""
from types import SimpleNamespace

import numpy as np

from pmpmsph.kernels.partition import max_stray
from pmpmsph.parallel.migration import MigrationSchedule


def test_max_stray_is_the_distance_past_the_slab():
    x = np.array([[0.5, 9.0], [1.3, 0.0], [-0.25, 0.0], [0.9, 0.0]])
    assert max_stray(x, 0, 0.0, 1.0, 4) == 1.3 - 1.0
    assert max_stray(x, 0, 0.0, 1.0, 1) == 0.0  # inside
    assert max_stray(x, 0, 0.0, 1.0, 3) == max(0.25, 1.3 - 1.0)
    x[3, 0] = np.nan
    assert np.isnan(max_stray(x, 0, 0.0, 1.0, 4))


def test_due_from_the_stray_and_the_next_move():
    dist = SimpleNamespace(size=2)
    sched = MigrationSchedule(dist, lazy=True, reach=0.01)
    assert sched.lazy and not sched.every_step
    limit = MigrationSchedule.SLACK * 0.01
    assert not sched.due(speed=0.0, stray=0.0, dt=1e-3)
    assert not sched.due(speed=1.0, stray=limit - 2.0e-3 - 1e-6, dt=1e-3)
    assert sched.due(speed=1.0, stray=limit - 2.0e-3 + 1e-6, dt=1e-3)
    assert sched.due(speed=0.0, stray=1.0, dt=1e-3)  # a jump, not a speed: still due
    assert sched.due(speed=float("nan"), stray=0.0, dt=1e-3)  # a broken state migrates
    one = MigrationSchedule(SimpleNamespace(size=1), lazy=True, reach=0.01)
    assert not one.lazy and not one.due(speed=1.0, stray=1.0, dt=1.0)
    eager = MigrationSchedule(dist, lazy=False)
    assert eager.every_step and eager.due(speed=0.0, stray=None, dt=1.0)
