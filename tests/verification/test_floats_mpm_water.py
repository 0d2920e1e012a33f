"""Floating blocks in MPM water against Archimedes (issue 19, item 1; docs/floats.md): four of
the floats bench's rectangles (none a shipped case's block), MPM water (APIC, quadratic
B-splines, MUSL, cells of two spacings, started hydrostatic) and the block in its own
velocity field, the multi-field contact deciding from the particles' surfaces
(kernels/mpm/contact.py), or an SPH block in the same water. Spacing 0.01, T = 3 s; the
submerged fraction is the mean over the last fifth, measured from the block's own geometry,
"settle" the block's largest vertical speed over the last tenth over its impact speed
(pmpmsph/bench/floats.py).

Measured (this build), MPM block: block 0 (0.10 x 0.06, s = 0.80) -0.8 %, block 2 (0.14 x
0.04, s = 0.95) +0.5 %, block 3 (0.12 x 0.06, s = 0.65) -1.5 %, block 5 (0.16 x 0.08,
s = 0.70) -0.4 %, settle 0.001-0.002. The two narrow blocks (3-4 cells wide) are not within
3 % at this spacing (block 1 -21.5 %, block 4 -15.9 %); at spacing 0.005 all six are within
-4.3 to +1.7 % (docs/floats.md). With GIMP instead, or the earlier centre-of-mass gap check
(block 0: -18.6 %), they float high. SPH block 0 in the same water: -5.5 %.
"""
import pytest
from mpi4py import MPI

from pmpmsph.bench.floats import BLOCKS, float_run
from pmpmsph.parallel.distributor import Distributor


def _run(combo, block):
    w, h, s, drop = BLOCKS[block]
    return float_run(combo, dist=Distributor(MPI.COMM_SELF), width=w, height=h, ratio=s,
                     drop=drop, spacing=0.01, end=3.0, cell_spacings=2, shape="quadratic")


@pytest.mark.parametrize("block, expected", [(0, -0.008), (2, 0.005), (3, -0.015),
                                             (5, -0.004)])
def test_mpm_block_in_mpm_water_floats_at_archimedes(block, expected):
    r = _run("mpm_in_mpm", block)
    assert abs(r["error"]) < 0.03 and r["error"] == pytest.approx(expected, abs=0.005)
    assert r["settle"] < 0.01      # the bound: at rest


def test_sph_block_in_mpm_water_floats_high():
    """NOT within 3 %: the SPH block rides 0.3 of its spacing high."""
    r = _run("sph_in_mpm", 0)
    assert r["error"] == pytest.approx(-0.055, abs=0.01)
    assert r["settle"] < 0.01
