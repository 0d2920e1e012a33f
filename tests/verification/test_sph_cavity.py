"""Lid-driven cavity at Re = 100 in SPH (pmpmsph/bench/scenes.py `sph_cavity`): viscous
fluid, no-slip dummy walls that carry the wall's velocity (the lid) and transmit shear, the
Morris et al. (1997) laminar viscosity and the stress form with the walls' extrapolated
viscous stress (kernels/sph/walls.py). Reference: Ghia, Ghia & Shin (1982), u on the
vertical centre line; the four points the issue names (y = 0.2813, 0.4531 (the minimum),
0.7344, 0.8516) within 3 % of the lid speed, at 30 x 30 particles, u averaged over the last
3 s of 20 (the flow is steady from about 12 s).

Measured (this build, 30 x 30): Morris 1.85 % at the four points, 4.0 % over the 15
interior points of Ghia's table (the ones within a spacing of the lid are the worst: the
profile there is resolved by one particle row); the stress form 2.9 % and 8.5 %, held here
to 3.5 % and 10 % (its near-lid profile is the weaker one; see the accuracy map for its
convergence). Before the walls
carried their velocity and viscous stress (a wall at rest could not drive the lid, and the
stress form's wall pairs carried -p I alone) the flow could not be set up at all. 20 s per
run.
"""
import pytest
from mpi4py import MPI

from pmpmsph.bench.accuracy_fluids import CAVITY, run_cavity
from pmpmsph.parallel.distributor import Distributor


@pytest.mark.parametrize("laminar", ["morris", "stress"])
def test_cavity_centre_line_against_ghia(laminar):
    method = next(m for m in CAVITY["methods"] if m["laminar"] == laminar)
    sim, _, res = run_cavity(Distributor(MPI.COMM_SELF), method, 30, quick=False)
    key_points, all_points = (0.03, 0.06) if laminar == "morris" else (0.035, 0.10)
    assert res["error"] < key_points, res
    assert res["aux"] < all_points, res
    assert sim.time == pytest.approx(20.0)
