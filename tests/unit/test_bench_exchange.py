"""`python -m pmpmsph.bench exchange` (bench/exchange.py): the per-step exchange time is the
halo, migration and coupling phases of the run's timers, per rank, over the timed steps."""
from pathlib import Path

import pytest

from pmpmsph.bench.exchange import EXCHANGE, measure
from pmpmsph.parallel.distributor import Distributor

CASE = Path(__file__).resolve().parents[2] / "cases" / "two_disks_contact.toml"


def test_exchange_is_the_sum_of_its_phases_on_one_rank():
    (row,) = measure(str(CASE), steps=20, repeat=2, dist=Distributor.serial())
    phases = row["phases"]
    assert {"p2g", "grid", "g2p"} <= set(phases)   # the MPM step's phases, us per step
    assert row["exchange"] == pytest.approx(sum(phases.get(k, 0.0) for k in EXCHANGE),
                                            abs=1.5)  # (phases rounded to 0.1, < 0.5 left out)
    assert row["step"] >= sum(phases[k] for k in ("p2g", "grid", "g2p"))
