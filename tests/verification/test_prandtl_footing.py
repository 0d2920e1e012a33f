"""Prandtl's strip footing (cases/prandtl_footing.toml and prandtl_footing_sph.toml, issue
21): a rigid rough footing pushed into weightless von Mises soil in plane strain; the
pressure under it, from the reaction of its `[[prescribed]]` constraint, levels off at the
limit (2 + pi) c_u (Prandtl 1920; Hill 1950, ch. VIII). Measured at a settlement of 0.05 B
(bench/accuracy_plastic.py, docs/plasticity.md): MPM with GIMP converges from above, slowly
(the footing's edge is smeared over a cell; the isochoric plastic flow locks low-order MPM
a little): 1.230, 1.142, 1.106 times the limit with cells of B/10, B/20, B/40; SPH 0.982
and 1.009 at spacings of B/10 and B/20. CI runs MPM at B/10 and B/20 and SPH at B/10."""
import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph.bench.accuracy_plastic import AT, footing, level_at, pressure_curve
from pmpmsph.parallel.distributor import Distributor

SPH_COARSE = 0.982  # measured at B/10; 1.009 at B/20


def curve(family, cell):
    sim, held = footing(Distributor(MPI.COMM_SELF), family, cell)
    s, q, _ = pressure_curve(sim, held, sim.case.time.end)
    return s, q


@pytest.mark.slow
def test_mpm_footing_levels_off_and_converges_to_prandtl():
    coarse, fine = curve("MPM", 0.1), curve("MPM", 0.05)
    q_coarse, q_fine = level_at(*coarse, AT), level_at(*fine, AT)
    assert q_coarse == pytest.approx(1.230, abs=0.01)
    assert q_fine == pytest.approx(1.142, abs=0.01)
    assert q_fine - 1.0 < 0.65 * (q_coarse - 1.0)  # the error shrinks with the cell
    s, q = fine
    assert level_at(s, q, 0.04) < level_at(s, q, AT) < 1.03 * level_at(s, q, 0.04)
    assert level_at(s, q, 0.01) < 0.7 * level_at(s, q, AT)  # after an elastic rise


def test_sph_footing_reaches_prandtl():
    s, q = curve("SPH UL", 0.1)
    assert np.all(np.isfinite(q))
    assert level_at(s, q, AT) == pytest.approx(SPH_COARSE, abs=0.01)
