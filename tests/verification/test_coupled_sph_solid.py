"""An SPH solid in MPM water (issue 5, "an SPH solid in an MPM fluid"): scene 7's float the
other way round (cases/coupled_sph_solid_float.toml; seed 003 §8.7, BENCHMARKS.md scene 7):
an SPH ice triangle (neo-Hookean, E = 2e5, nu = 0.3, rho_s = 917) floating on MPM Tait water
(rho_f = 997, kappa = 2e3, gamma = 7, mu = 0.98), released at rest near its equilibrium in
hydrostatic water; the coupling of physics/sph/solid_in_fluid.py (the water's pressure on the ice
through the SPH mirror pair, the ice's own kinematics over the ice alone, and the ice's own
grid velocity field in frictionless contact with the water's).

Reference: Archimedes' principle in the Tait water at rest, for the seeded lattice body
(test_coupled_fsi.py's archimedes_draft_lattice: each point's square cell) and the exact
triangle of the seeded mass; drafts are the far-field surface minus the block's bottom face.
Measured (this build: the grid contact acts where the particle surfaces meet,
kernels/mpm/contact.py):
  spacing 0.01 (this test), t = 5-6 s: mean draft 0.1144 (0.1143-0.1144) against 0.1137
    (lattice, +0.6 %) and 0.1104 (triangle, +3.6 %); total energy 83.37 J after the first
    step, 82.87 J at t = 6, kinetic energy 4e-6 J at t = 6; the nearest water point 0.88
    spacing from a block particle; about 30 s of run on one core. With the earlier
    centre-of-mass gap check at 1.5 (the case's setting then): 0.1136 (-0.1 %), 0.90 spacing.
  spacing 0.005 (the case): see cases/coupled_sph_solid_float.toml.
Variants at spacing 0.01 (the comparisons of physics/sph/solid_in_fluid.py), with the
centre-of-mass gap check: at 1 the water row below the block closes in on it (0.34
spacing at t = 2, 0.04 at t = 4.8) and the block creeps past Archimedes (0.1126 over
t = 1.5-2, 0.1142 at t = 4.8, still sinking); without the grid contact
(mpm.contact = "single": the pressure pairs alone)
it sinks at a steady 1 mm/s (0.1145 at t = 4.8, 20 water points inside the block's
lattice); with the contact alone (no pressure pairs) at 3 mm/s, 24 water points inside its
lattice by t = 1.8 (draft 0.1145); with the solid's velocity gradient summed over the water
too it fails at t = 0.41 s.
NOT met: the approach to equilibrium is slow (about 5 s; PIC water, physics/sph/solid_in_fluid.py).
"""
import sys
from pathlib import Path

import numpy as np
from mpi4py import MPI

from pmpmsph import load_case_file
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.simulation import Simulation

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_coupled_fsi import (
    _float_draft,
    archimedes_draft_lattice,
    archimedes_draft_triangle,
    assert_float_intact,
)

CASE = Path(__file__).resolve().parents[2] / "cases" / "coupled_sph_solid_float.toml"


def _nearest_water(sim):
    """Least distance from a water point to a block particle."""
    p = sim.particles
    x, body = p["x"][: p.n_owned], p["body"][: p.n_owned]
    xw, xb = x[body == 0], x[body == 1]
    return float(np.sqrt(((xw[:, None, :] - xb[None, :, :]) ** 2).sum(-1)).min())


def test_sph_block_floats_on_mpm_water_at_archimedes():
    """The case at half its resolution (spacing 0.01 for water and block, h = 0.013), run
    to T = 6 s (the block settles by t = 5 in the PIC water). Asserted: the mean draft over
    t = 5-6 s against Archimedes for the seeded lattice body within 1 % (measured -0.1 %);
    the block is at rest (kinetic energy at T below 1e-3 J) and no energy is made (total at T
    not above its value after the first step); the block's particles are in contact on the
    grid (their own field) and no water point came within 0.75 spacing of a block particle
    (the lattices do not interpenetrate; measured 0.90); no particle lost, mass exact, all
    finite, det F > 0 on the block."""
    sp = 0.01
    sets = [(f"bodies[{i}].spacing", sp) for i in range(2)] + [("time.end", 6.0)]
    sim = Simulation(load_case_file(CASE, overrides=sets), dist=Distributor(MPI.COMM_SELF))
    p = sim.particles
    n0, m0 = p.n_owned, p["mass"].sum()
    block = p["body"] == 1
    d_lattice = archimedes_draft_lattice(p["x"][block, 1], sp, p["mass"][block].sum())
    d_triangle = archimedes_draft_triangle(p["mass"][block].sum())
    energy, drafts, contact, gaps = [], [], [], []

    def track(s):
        if not energy:
            energy.append(s.diagnostics()["total"])
        contact.append(s.mpm.n_p2g - s.mpm.n_stress)
        if s.step_count % 500 == 0:
            gaps.append(_nearest_water(s))
        if s.time >= 5.0:
            drafts.append(_float_draft(s, sp))

    sim.run(on_step=track)
    assert abs(sim.time - 6.0) < 1e-9
    assert_float_intact(sim, n0, m0)
    block = p["body"] == 1
    assert min(contact) == block.sum()   # every block particle is near the water here
    gaps.append(_nearest_water(sim))
    diag = sim.diagnostics()
    d_sim = float(np.mean(drafts))
    print(f"draft {d_sim:.4f} (t = 5-6: {min(drafts):.4f}-{max(drafts):.4f}); Archimedes "
          f"lattice {d_lattice:.4f} ({d_sim / d_lattice - 1:+.4f}), triangle {d_triangle:.4f} "
          f"({d_sim / d_triangle - 1:+.3f}); energy {energy[0]:.3f} -> {diag['total']:.3f} J, "
          f"kinetic {diag['kinetic']:.2e} J; nearest water {min(gaps) / sp:.2f} spacing")
    assert diag["total"] <= energy[0]
    assert diag["kinetic"] < 1e-3
    assert min(gaps) > 0.75 * sp
    assert abs(d_sim / d_lattice - 1.0) < 0.01
