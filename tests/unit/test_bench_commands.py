"""The bench commands of issue 19 run end to end at a tiny size (their figures are measured
on an idle machine, not here): `floats` and `coupled`."""
import argparse

import numpy as np
from mpi4py import MPI

from pmpmsph.bench import coupled_speed, floats
from pmpmsph.parallel.distributor import Distributor


def test_coupled_speed_prints_time_per_step(capsys):
    args = argparse.Namespace(spacing=0.02, steps=2)
    assert coupled_speed.run(args, Distributor(MPI.COMM_SELF)) == 0
    out = capsys.readouterr().out
    assert "ranks 1  particles 2342" in out and "ms/step by phase" in out


def test_archimedes_fraction_of_an_incompressible_block():
    """In nearly incompressible water the fraction is the density ratio; in the bench's
    Tait water (kappa = 2e4) the water is denser at depth, so the block floats higher."""
    kappa = floats.KAPPA
    try:
        floats.KAPPA = 1e12
        assert abs(floats.archimedes_fraction(0.8 * 997.0 * 0.1 * 0.06, 0.1, 0.06) - 0.8) < 1e-6
    finally:
        floats.KAPPA = kappa
    assert 0.79 < floats.archimedes_fraction(0.8 * 997.0 * 0.1 * 0.06, 0.1, 0.06) < 0.8


def test_float_run_measures_a_block(tmp_path):
    r = floats.float_run("mpm_in_mpm", spacing=0.02, end=0.05, width=0.12, height=0.06,
                         drop=0.02, cell_spacings=2)
    assert np.isfinite(r["fraction"]) and r["particles"] > 0
    # dropped from 0.02 above the surface, it has not reached it at t = 0.05 s
    assert r["fraction"] < 0.0
