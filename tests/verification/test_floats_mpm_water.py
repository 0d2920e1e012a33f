"""Floating blocks in MPM water against Archimedes (issue 19, item 1; docs/floats.md): two of
the floats bench's rectangles (none a shipped case's block), MPM water (APIC, GIMP, MUSL,
cells of two spacings, started hydrostatic) and the block in its own velocity field, the
multi-field contact deciding from the particles' surfaces (kernels/mpm/contact.py), or an
SPH block in the same water. Spacing 0.01, T = 3 s; the submerged fraction is the mean over
the last fifth, measured from the block's own geometry (pmpmsph/bench/floats.py).

Measured (this build): block 0 (0.10 x 0.06, s = 0.8) MPM in MPM +3.9 %, SPH in MPM -7.0 %;
block 3 (0.12 x 0.06, s = 0.65) MPM in MPM +3.9 %. With the earlier centre-of-mass gap
check (1.5): -18.6 % and -14.8 % for block 0. NOT the issue's 3 % for every block; at
spacing 0.005 the MPM blocks 0-2 and 4 are within +0.8 to +3.9 % (docs/floats.md).
"""
import pytest
from mpi4py import MPI

from pmpmsph.bench.floats import BLOCKS, float_run
from pmpmsph.parallel.distributor import Distributor


@pytest.mark.parametrize("combo, block, expected", [("mpm_in_mpm", 0, 0.039),
                                                    ("mpm_in_mpm", 3, 0.039),
                                                    ("sph_in_mpm", 0, -0.070)])
def test_block_in_mpm_water_floats_near_archimedes(combo, block, expected):
    w, h, s, drop = BLOCKS[block]
    r = float_run(combo, dist=Distributor(MPI.COMM_SELF), width=w, height=h, ratio=s,
                  drop=drop, spacing=0.01, end=3.0, cell_spacings=2)
    assert r["error"] == pytest.approx(expected, abs=0.01)
    assert r["settle"] < 0.05      # measured 0.006-0.011: nearly at rest
