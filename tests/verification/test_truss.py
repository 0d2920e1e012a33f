"""Scene 2 (BENCHMARKS.md): square truss hanging under its own weight, large strain (seed 003,
thesis §8.2, tables 6-9), neo-Hookean, E = 1e5, nu = 0.3, rho = 1500, g = 1400, alpha_d = 25.

The thesis' "N x N grid" is read as N cells across the undeformed square (h = 0.06/N, see
cases/truss_2d.toml); its top edge is "fixed vertically" (v_y = 0 on the top face, v_x free,
so the top row can contract: the converged l_x ~ 0.033 is about half the width).

With linear hats the thesis hits "extension instability" at 7 x 7 and 8 x 8 cells with 5 x 5
and 20 x 20 points; BENCHMARKS.md asks that GIMP and B-splines run stably there.

test_linear_hats_fail_like_the_thesis: reproduces the thesis' failures (a RunError within the
first swing, t < 0.1). Measured: all four stop at t = 0.018-0.020 (the lower part falls freely
until the tension wave from the top reaches it, ~7 ms, and the first stretch peak tears it).

test_linear_hats_with_100x100_points_match_the_thesis: where the thesis' linear hats work
(3 x 3 and 4 x 4 cells, 100 x 100 points), ours reproduce its l_y within 7 % and l_x within 12 %.

test_cpdi_runs_stably_where_linear_hats_fail: the same 7 x 7 and 8 x 8 cells with 20 x 20
points and CPDI (`mpm.shape = "cpdi"`, convected particle domains, Sadeghirad et al. 2011)
run through the phase where linear hats fail and the first oscillations (to t = 0.3, when
damping alpha_d = 25 has reduced the swing to e^{-3.75} ~ 2 %), lose no particle, stay
finite, and give l_y, l_x in a band around the converged 0.120 / 0.033 (thesis 500 x 500
points). Band: with 20 points the measured span misses half a point spacing (0.0015) at each
end, stretched about 3.4x at the top (static neo-Hookean uniaxial stretch there) and 1x at
the bottom, so l_y(20 pts) ~ 0.120 - 0.0066 = 0.113, and l_x ~ 0.033 * 0.95; we allow
0.100 < l_y < 0.130 and 0.024 < l_x < 0.040 (the spread of the thesis' own tables 6-9 plus
the residual swing). Measured: l_y = 0.1138, l_x = 0.0309 on both grids.

Why CPDI and not GIMP or B-splines: with uniform GIMP and quadratic/cubic B-splines every
one of these configurations separates near the top at t = 0.008-0.010 and a piece falls out
of the grid at t = 0.020 (tests/verification/test_truss.py history; reproduce with
--set mpm.shape=gimp). The stretch there reaches 2.5-5 during the first swing, so the
particle spacing passes a cell while the particle's support stays one cell wide: the node
between two rows loses one of them, their positions run apart while F stays finite (the
"extension instability" is numerical fracture). CPDI's domain is F diag(lp), so each
particle's support stretches with the material and neighbouring domains keep sharing nodes;
positions and F then agree (the row gaps equal F_yy times the spacing to 3 %).
Not met: 5 x 5 points (spacing 1.6 cells, so one particle per 2.5 cells) with CPDI and
`mpm.cpdi_reach = 6` pass the first two swings but the top row slides sideways off the
grid at t = 0.08 (8 x 8 cells); GIMP cannot seed spacings above a cell at all.
"""
from pathlib import Path

import numpy as np
import pytest

from pmpmsph import load_case_file
from pmpmsph.errors import RunError
from pmpmsph.simulation import Simulation

CASE = Path(__file__).resolve().parents[2] / "cases" / "truss_2d.toml"
L = 0.06
#: thesis tables 6 and 7, 100 x 100 points: (l_y, l_x) on 3 x 3 and 4 x 4 cells
THESIS_100 = {3: (0.1190, 0.0345), 4: (0.1206, 0.0326)}


def by_gid(sim, name):
    """A particle field in gid (seeding) order: the solver re-sorts its rows by grid cell."""
    p = sim.particles
    return p[name][np.argsort(p["gid"])]


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


@pytest.mark.parametrize("ncell", [3, 4])
def test_linear_hats_with_100x100_points_match_the_thesis(ncell):
    """Where the thesis' linear hats work (3 x 3 and 4 x 4 cells, 100 x 100 points) ours must
    give its l_y within 7 % and l_x within 12 % (we stop at t = 0.5, by when alpha_d = 25 has
    settled the swing: t = 1 gives the same to 1e-4; the thesis ran to T = 2).
    Measured (this build, dt = 5e-5): 3 x 3: l_y = 0.1228 (+3.2 %), l_x = 0.0311 (-9.9 %);
    4 x 4: l_y = 0.1272 (+5.5 %), l_x = 0.0310 (-4.9 %). With dt = 1e-5 l_y(4 x 4) = 0.1242:
    the elongation depends on dt by ~2 % (positions and F drift apart at first order in dt
    during the violent first swing, see the report)."""
    sim = truss(ncell, 100, "linear", end=0.5)
    x0 = by_gid(sim, "x").copy()
    sim.run()
    x = by_gid(sim, "x")
    assert np.all(np.isfinite(x))
    ly, lx = spans(x0, x)
    ly_ref, lx_ref = THESIS_100[ncell]
    print(f"scene 2, linear, {ncell}x{ncell} cells, 100x100 points: l_y = {ly:.4f} "
          f"({ly / ly_ref - 1:+.1%} vs thesis {ly_ref}), l_x = {lx:.4f} "
          f"({lx / lx_ref - 1:+.1%} vs {lx_ref})")
    assert abs(ly / ly_ref - 1) < 0.07
    assert abs(lx / lx_ref - 1) < 0.12


@pytest.mark.parametrize("ncell", [7, 8])
def test_cpdi_runs_stably_where_linear_hats_fail(ncell):
    sim = truss(ncell, 20, "cpdi", end=0.3)
    x0 = by_gid(sim, "x").copy()
    n0 = sim.particles.n_owned
    sim.run()
    x = by_gid(sim, "x")
    assert sim.particles.n_owned == n0 and np.all(np.isfinite(x))
    ly, lx = spans(x0, x)
    print(f"scene 2, CPDI, {ncell}x{ncell} cells, 20x20 points, t = {sim.time:.2f}: "
          f"l_y = {ly:.4f}, l_x = {lx:.4f}")
    assert 0.100 < ly < 0.130
    assert 0.024 < lx < 0.040
