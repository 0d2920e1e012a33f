"""Prandtl's strip footing (cases/prandtl_footing.toml and prandtl_footing_sph.toml, issue
21): a rigid rough footing pushed into weightless von Mises soil in plane strain; the
pressure under it, from the reaction of its `[[prescribed]]` constraint, tends to the limit
(2 + pi) c_u (Prandtl 1920; Hill 1950, ch. VIII). Measured at a settlement of 0.05 B
(bench/accuracy_plastic.py, docs/plasticity.md), cells or spacings of B/10, B/20, B/40:

    MPM GIMP USL with F-bar     0.840  0.972  1.039   (from below; still rising with s)
    MPM GIMP USL, no F-bar      1.230  1.142  1.106   (locked: from above)
    SPH UL                      0.982  1.010  1.010   (levelled off)

CI runs the coarse two of MPM with F-bar, the coarsest without, and SPH at B/10."""
import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph.bench.accuracy_plastic import AT, footing, level_at, pressure_curve
from pmpmsph.parallel.distributor import Distributor


def curve(family, cell, fbar=True):
    sim, held = footing(Distributor(MPI.COMM_SELF), family, cell, fbar=fbar)
    s, q, _ = pressure_curve(sim, held, sim.case.time.end)
    return s, q


@pytest.mark.slow
def test_mpm_footing_with_fbar_converges_to_prandtl():
    coarse, fine = curve("MPM", 0.1), curve("MPM", 0.05)
    q_coarse, q_fine = level_at(*coarse, AT), level_at(*fine, AT)
    assert q_coarse == pytest.approx(0.840, abs=0.01)
    assert q_fine == pytest.approx(0.972, abs=0.01)
    assert abs(q_fine - 1.0) < 0.25 * abs(q_coarse - 1.0)  # the error shrinks with the cell
    s, q = fine
    assert level_at(s, q, 0.01) < 0.7 * level_at(s, q, AT)  # after an elastic rise


def test_mpm_footing_without_fbar_locks():
    s, q = curve("MPM", 0.1, fbar=False)
    assert level_at(s, q, AT) == pytest.approx(1.230, abs=0.01)


def test_sph_footing_reaches_prandtl():
    s, q = curve("SPH UL", 0.1)
    assert np.all(np.isfinite(q))
    assert level_at(s, q, AT) == pytest.approx(0.982, abs=0.01)
