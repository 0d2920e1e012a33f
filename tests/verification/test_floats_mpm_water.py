"""Floating blocks in MPM water against Archimedes (issue 19, item 1; docs/floats.md): three
of the floats bench's rectangles (none a shipped case's block), MPM water (APIC, quadratic
B-splines, MUSL, cells of two spacings, started hydrostatic, the tank's walls the grid's slip
faces, wave absorbers 0.1 wide at its ends) and the block in its own velocity field, the
multi-field contact deciding from the particles' surfaces (kernels/mpm/contact.py), or an SPH
block in the same water. Spacing 0.01, T = 3 s; the submerged fraction is the mean over the
last fifth, measured from the block's own geometry against two water levels: the far-field
top rows (`error`) and the rest level of the seeded water with the block in it
(`error_level`); "settle" the block's largest vertical speed over the last tenth over its
impact speed (pmpmsph/bench/floats.py).

Measured (this build), MPM block, error / error_level / settle: block 0 (0.10 x 0.06,
s = 0.80) +1.0 / -0.9 % / 0.004, block 2 (0.14 x 0.04, s = 0.95) +2.6 / -1.5 % / 0.004,
block 5 (0.16 x 0.08, s = 0.70) +2.8 / -0.2 % / 0.005. Not within 3 % on both at this
spacing: block 3 (settle 0.013), the narrow blocks 1 (-18 %) and 4 (-3.6 / -3.7 %); at
spacing 0.005 the blocks sit 0.5-2 mm higher (-2 to -5 %, docs/floats.md: not explained).
SPH block 0 in the same water: -0.8 / -3.3 %.
"""
import pytest
from mpi4py import MPI

from pmpmsph.bench.floats import BLOCKS, float_run
from pmpmsph.parallel.distributor import Distributor


def _run(combo, block):
    w, h, s, drop = BLOCKS[block]
    return float_run(combo, dist=Distributor(MPI.COMM_SELF), width=w, height=h, ratio=s,
                     drop=drop, spacing=0.01, end=3.0, cell_spacings=2, shape="quadratic")


@pytest.mark.parametrize("block, expected, expected_level", [(0, 0.010, -0.009),
                                                             (2, 0.026, -0.015),
                                                             (5, 0.028, -0.002)])
def test_mpm_block_in_mpm_water_floats_at_archimedes(block, expected, expected_level):
    r = _run("mpm_in_mpm", block)
    assert abs(r["error"]) < 0.03 and abs(r["error_level"]) < 0.03
    assert r["error"] == pytest.approx(expected, abs=0.005)
    assert r["error_level"] == pytest.approx(expected_level, abs=0.005)
    assert r["settle"] < 0.01      # the bound: at rest


def test_sph_block_in_mpm_water():
    """Within 3 % of the top rows' level, NOT of the water's rest level (-3.3 %)."""
    r = _run("sph_in_mpm", 0)
    assert r["error"] == pytest.approx(-0.008, abs=0.005)
    assert r["error_level"] == pytest.approx(-0.033, abs=0.005)
    assert r["settle"] < 0.01
