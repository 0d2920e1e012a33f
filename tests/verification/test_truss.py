"""Scene 2 (BENCHMARKS.md): square truss hanging under its own weight, large strain (seed 003,
thesis §8.2, tables 6-9), neo-Hookean, E = 1e5, nu = 0.3, rho = 1500, g = 1400, alpha_d = 25.

The thesis' "N x N grid" is read as N cells across the undeformed square (h = 0.06/N, see
cases/truss_2d.toml); its top edge is "fixed vertically" (v_y = 0 on the top face, v_x free,
so the top row can contract: the converged l_x ~ 0.033 is about half the width).

With linear hats the thesis hits "extension instability" at 7 x 7 and 8 x 8 cells with 5 x 5
and 20 x 20 points; BENCHMARKS.md asks that GIMP and B-splines run stably there.

test_linear_hats_fail_like_the_thesis: reproduces the thesis' failures (a RunError within the
first swing, t < 0.1: the first stretch peak is at t ~ 0.02).

test_smooth_shapes_are_stable: GIMP and quadratic/cubic B-splines with 20 x 20 points at 7 x 7
and 8 x 8 cells must run through the phase where linear fails and the first oscillations
(to t = 0.3, when damping alpha_d = 25 has reduced the swing to e^{-3.75} ~ 2 %), lose no
particle, stay finite, and give l_y, l_x in a band around the converged 0.120 / 0.033 (thesis
500 x 500 points). Band: with 20 points the measured span misses half a point spacing
(0.0015) at each end, stretched about 3.4x at the top (static neo-Hookean uniaxial stretch
there) and 1x at the bottom, so l_y(20 pts) ~ 0.120 - 0.0066 = 0.113, and l_x ~ 0.033 * 0.95;
we allow 0.100 < l_y < 0.130 and 0.024 < l_x < 0.040 (the spread of the thesis' own
tables 6-9 plus the residual swing). 5 x 5 points are not included: at 7-8 cells their
spacing is already 1.4-1.6 cells, ~5 cells once stretched, beyond the 1-2 cell support of any
of these shape functions (and GIMP refuses spacing > cell size).
Measured (this build): every GIMP/B-spline configuration fails during the first swing
(t ~ 0.02-0.05; the material separates near the top where the dynamic stretch reaches 4-5),
so test_smooth_shapes_are_stable FAILS — see the report; this is a solver weakness (no
cpGIMP/CPDI, no boundary-modified B-splines), not a test problem.
"""
from pathlib import Path

import numpy as np
import pytest

from pmpmsph import load_case_file
from pmpmsph.errors import RunError
from pmpmsph.simulation import Simulation

CASE = Path(__file__).resolve().parents[2] / "cases" / "truss_2d.toml"
L = 0.06


def truss(ncell, npts, shape, end, dt=5e-5):
    h = L / ncell
    ny = int(np.ceil(4 * L / h))
    overrides = [("mpm.shape", shape), ("grid.cell_size", h), ("grid.origin", [-2 * h, -ny * h]),
                 ("grid.cells", [ncell + 4, ny]), ("bodies[0].count", [npts, npts]),
                 ("time.dt", dt), ("time.end", end)]
    return Simulation(load_case_file(CASE, overrides=overrides))


def spans(x0, x):
    """l_y: first-to-last point of the centre column(s); l_x: of the top row."""
    d = np.abs(x0[:, 0] - L / 2)
    centre = d <= d.min() + 1e-12
    cols = np.unique(x0[centre, 0])
    ly = np.mean([np.ptp(x[centre & (x0[:, 0] == c), 1]) for c in cols])
    top = x0[:, 1] >= x0[:, 1].max() - 1e-12
    return ly, np.ptp(x[top, 0])


@pytest.mark.parametrize("ncell", [7, 8])
@pytest.mark.parametrize("npts", [5, 20])
def test_linear_hats_fail_like_the_thesis(ncell, npts):
    sim = truss(ncell, npts, "linear", end=0.3)
    with pytest.raises(RunError) as info:
        sim.run()
    print(f"scene 2, linear, {ncell}x{ncell} cells, {npts}x{npts} points: fails at "
          f"t = {sim.time:.4f}: {info.value.cause}")
    assert sim.time < 0.1


@pytest.mark.parametrize("shape", ["gimp", "quadratic", "cubic"])
@pytest.mark.parametrize("ncell", [7, 8])
def test_smooth_shapes_are_stable(shape, ncell):
    sim = truss(ncell, 20, shape, end=0.3)
    x0 = sim.particles["x"].copy()
    n0 = len(x0)
    try:
        sim.run()
    except RunError as exc:
        pytest.fail(f"scene 2, {shape}, {ncell}x{ncell} cells, 20x20 points: {exc} "
                    f"(t = {sim.time:.4f})")
    x = sim.particles["x"]
    assert len(x) == n0
    assert np.all(np.isfinite(x)) and np.all(np.isfinite(sim.particles["sigma"]))
    lo = np.array(sim.case.grid.origin)
    hi = np.array(sim.case.grid.upper)
    assert np.all((x >= lo) & (x <= hi))
    ly, lx = spans(x0, x)
    print(f"scene 2, {shape}, {ncell}x{ncell} cells, 20x20 points: l_y = {ly:.4f}, "
          f"l_x = {lx:.4f} at t = {sim.time:.2f}")
    assert 0.100 < ly < 0.130
    assert 0.024 < lx < 0.040
