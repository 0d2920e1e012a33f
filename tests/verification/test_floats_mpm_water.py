"""Floating blocks in MPM water against Archimedes (issue 19, item 1; docs/floats.md): five
of the floats bench's six rectangles (none a shipped case's block), MPM water (APIC,
quadratic B-splines, MUSL, cells of two spacings, started hydrostatic, the tank's walls the
grid's slip faces, wave absorbers 0.1 wide at its ends) and the block in its own velocity
field, the multi-field contact deciding from the particles' surfaces (kernels/mpm/
contact.py), or an SPH block in the same water. Spacing 0.01, T = 4 s; the submerged
fraction is the mean over the last fifth, measured from the block's own geometry against
two water levels: the far-field top rows (`error`) and the rest level of the seeded water
with the block in it (`error_level`); "settle" the block's largest vertical speed over the
last tenth over its impact speed (pmpmsph/bench/floats.py).

Measured (this build), MPM block, error / error_level / settle: block 0 (0.10 x 0.06,
s = 0.80) -1.3 / -1.3 % / 0.001, block 2 (0.14 x 0.04, s = 0.95) +0.5 / -1.5 % / 0.003,
block 3 (0.12 x 0.06, s = 0.65) +0.1 / -1.7 % / 0.002, block 4 (0.06 x 0.05, s = 0.90)
-1.9 / -2.6 % / 0.001, block 5 (0.16 x 0.08, s = 0.70) +0.2 / -0.9 % / 0.002; the rest-level
draft's slope over the last fifth ("drift", per second, relative) -1.1, -1.2, +0.2, -0.7,
-0.4 %. NOT within
3 %: block 1 (0.08 x 0.04, s = 0.5, 4 cells wide), -16.8 / -17.5 %. At spacing 0.005 and
T = 3 the blocks sit -2 to -6 % (docs/floats.md: the errors scatter by 0.2-0.4 spacings and
are not shown to converge). SPH block 0 in the same water: +1.4 / +0.2 %, passing through
Archimedes' draft while still sinking; the other SPH blocks are not within 3 % (-35 to +5 %).
"""
import pytest
from mpi4py import MPI

from pmpmsph.bench.floats import BLOCKS, float_run
from pmpmsph.parallel.distributor import Distributor


def _run(combo, block):
    w, h, s, drop = BLOCKS[block]
    return float_run(combo, dist=Distributor(MPI.COMM_SELF), width=w, height=h, ratio=s,
                     drop=drop, spacing=0.01, end=4.0, cell_spacings=2, shape="quadratic")


@pytest.mark.parametrize("block, expected, expected_level", [(0, -0.013, -0.013),
                                                             (2, 0.005, -0.015),
                                                             (3, 0.001, -0.017),
                                                             (4, -0.019, -0.026),
                                                             (5, 0.002, -0.009)])
def test_mpm_block_in_mpm_water_floats_at_archimedes(block, expected, expected_level):
    r = _run("mpm_in_mpm", block)
    assert abs(r["error"]) < 0.03 and abs(r["error_level"]) < 0.03
    assert r["error"] == pytest.approx(expected, abs=0.003)
    assert r["error_level"] == pytest.approx(expected_level, abs=0.003)
    assert r["settle"] < 0.01      # the bound: at rest
    assert abs(r["drift"]) < 0.015  # the draft's change over the last 0.8 s: 0.2-1.2 %/s


def test_sph_block_in_mpm_water_passes_archimedes_still_sinking():
    """Block 0 only: the other SPH blocks are not within 3 % (docs/floats.md). NOT settled
    either, though `settle` passes: the block is still sinking at about 1.3 mm/s (0.3 % of
    its impact speed, under the issue's 1 % bound) through Archimedes' draft, -7 % at t = 2
    (rest level), +3 % at t = 5; the mean over 3.2-4 s is what is asserted."""
    r = _run("sph_in_mpm", 0)
    assert abs(r["error"]) < 0.03 and abs(r["error_level"]) < 0.03
    assert r["error"] == pytest.approx(0.014, abs=0.003)
    assert r["error_level"] == pytest.approx(0.002, abs=0.003)
    assert r["settle"] < 0.01
    assert r["drift"] == pytest.approx(0.0315, abs=0.003)  # still sinking: +3.2 % a second
