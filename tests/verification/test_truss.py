"""Scene 2 (BENCHMARKS.md): square truss hanging under its own weight, large strain (seed 003,
thesis §8.2, tables 6-9), neo-Hookean, E = 1e5, nu = 0.3, rho = 1500, g = 1400, alpha_d = 25.

Grid: the thesis' "grid with N x N cells" is read as N x N cells over a square of side 3 l in
which the block hangs (h = 0.18/N), top edge on the top face (slip: "fixed vertically"),
because with linear hats that reading reproduces the thesis' tables and failures and
"N cells across the block" (h = l/N) does not; the evidence is in cases/truss_2d.toml.

With linear hats the thesis hits "extension instability" at 7 x 7 and 8 x 8 cells with 5 x 5
and 20 x 20 points; BENCHMARKS.md asks that GIMP-family or B-spline shape functions run
stably there. CPDI (convected particle domains, Sadeghirad et al. 2011, the GIMP family) does
at all four; quadratic B-splines do with 20 x 20 points. Uniform GIMP does not (not asserted,
see the case header): with 20 x 20 points its particle half-width is 0.06 cell, so it is
nearly the linear hat, and it tears the same way.

End time of the stability runs: t = 0.5. The first swing peaks at t ~ 0.022 (the block falls
freely until the tension wave from the top reaches its bottom, ~7 ms, then stretches to
l_y ~ 0.17); the linear hats' failures all come by t = 0.14; by t = 0.5 the damping
alpha_d = 25 has shrunk the swing by e^(-alpha_d t / 2) = e^-6.25 ~ 0.2 %, and it is the time
of the REFERENCE. At t = 0.3 (e^-3.75 ~ 2.4 %) the state has not settled enough to compare:
CPDI's l_x with 5 x 5 points on 7 x 7 cells is 0.0255 there and 0.0268 at t = 0.5 (measured).
Each stability run takes 1-3 s. The thesis ran to T = 2.

References for coarse point counts: l_y and l_x are measured between the first and last
points, which sit half a point spacing inside the block's edges, so n x n points span less
than the converged field does. Sampling the linear-hat 100 x 100 field (same grid, dt = 5e-5,
t = 0.5) at the seeds of the 20 x 20 and 5 x 5 points gives the REFERENCE below.
"""
from pathlib import Path

import numpy as np
import pytest

from pmpmsph import load_case_file
from pmpmsph.errors import RunError
from pmpmsph.simulation import Simulation

CASE = Path(__file__).resolve().parents[2] / "cases" / "truss_2d.toml"
L = 0.06
SIDE = 3 * L  # the square the block hangs in (cases/truss_2d.toml)
END = 0.5  # end time of the runs that must stay stable (module docstring)
#: thesis tables 8 and 9, 100 x 100 points, T = 2: (l_y, l_x)
THESIS_100 = {7: (0.1202, 0.0314), 8: (0.1213, 0.0312)}
#: (cells, points) -> (l_y, l_x) of the 100 x 100 linear-hat field sampled at the seeds of
#: the coarse points (see the module docstring)
REFERENCE = {(7, 20): (0.1161, 0.0304), (8, 20): (0.1170, 0.0302),
             (7, 5): (0.0962, 0.0269), (8, 5): (0.0971, 0.0264)}


def by_gid(sim, name):
    """A particle field in gid (seeding) order: the solver re-sorts its rows by grid cell."""
    p = sim.particles
    return p[name][np.argsort(p["gid"])]


def truss(ncell, npts, shape, end, dt=5e-5):
    h = SIDE / ncell
    overrides = [("mpm.shape", shape), ("grid.cell_size", h),
                 ("grid.origin", [L / 2 - SIDE / 2, -SIDE]), ("grid.cells", [ncell, ncell]),
                 ("bodies[0].count", [npts, npts]), ("time.dt", dt), ("time.end", end)]
    return Simulation(load_case_file(CASE, overrides=overrides), write_output=False)


def spans(x0, x):
    """l_y: first-to-last point of the centre column(s); l_x: of the top row."""
    d = np.abs(x0[:, 0] - L / 2)
    centre = d <= d.min() + 1e-12
    cols = np.unique(x0[centre, 0])
    ly = np.mean([np.ptp(x[centre & (x0[:, 0] == c), 1]) for c in cols])
    top = x0[:, 1] >= x0[:, 1].max() - 1e-12
    return ly, np.ptp(x[top, 0])


def sampled_spans(x0, x, nfine, n):
    """(l_y, l_x) that n x n points would measure in the field of an nfine x nfine run (x0, x
    its seeds and end positions): the seed (i + 1/2) l/n of a coarse point lies at the
    fractional index (i + 1/2) nfine/n - 1/2 of the fine lattice, between whose points the
    end positions are interpolated bilinearly."""
    s = L / nfine
    i = np.rint(x0[:, 0] / s - 0.5).astype(int)
    j = np.rint(-x0[:, 1] / s - 0.5).astype(int)  # row 0 on top
    X = np.zeros((nfine, nfine, 2))
    X[i, j] = x[:, :2]

    def at(fi, fj):
        a, b = int(fi), int(fj)
        u, v = fi - a, fj - b
        a1, b1 = min(a + 1, nfine - 1), min(b + 1, nfine - 1)
        return ((1 - u) * (1 - v) * X[a, b] + u * (1 - v) * X[a1, b]
                + (1 - u) * v * X[a, b1] + u * v * X[a1, b1])

    k = lambda c: (c + 0.5) * nfine / n - 0.5  # noqa: E731 - coarse index -> fine index
    cols = [n // 2] if n % 2 else [n // 2 - 1, n // 2]  # the centre column(s), as `spans`
    ly = np.mean([at(k(c), k(0))[1] - at(k(c), k(n - 1))[1] for c in cols])
    return ly, at(k(n - 1), k(0))[0] - at(k(0), k(0))[0]


def check_spans(label, got, ref, tol_y, tol_x):
    """Print l_y, l_x against their reference and assert the relative tolerances."""
    (ly, lx), (ly_ref, lx_ref) = got, ref
    print(f"scene 2, {label}: l_y = {ly:.4f} ({ly / ly_ref - 1:+.1%} vs {ly_ref}), "
          f"l_x = {lx:.4f} ({lx / lx_ref - 1:+.1%} vs {lx_ref})")
    assert abs(ly / ly_ref - 1) < tol_y
    assert abs(lx / lx_ref - 1) < tol_x


def run_stably(ncell, npts, shape, end, field=None):
    """Run to `end`, asserting no failure, no particle lost, finite state and det F > 0;
    returns (l_y, l_x). `field`, if a dict, receives the seeds and end positions."""
    sim = truss(ncell, npts, shape, end)
    x0 = by_gid(sim, "x").copy()
    n0 = sim.particles.n_owned
    sim.run()  # a RunError (det F <= 0, NaN, left the grid) fails the test
    assert sim.time == pytest.approx(end)
    x, F = by_gid(sim, "x"), by_gid(sim, "F")
    assert sim.particles.n_owned == n0
    assert np.all(np.isfinite(x)) and np.all(np.isfinite(F))
    assert np.all(np.linalg.det(F[:, :2, :2]) > 0.0)
    if field is not None:
        field.update(x0=x0, x=x.copy())
    return spans(x0, x)


@pytest.mark.parametrize("dt", [1e-5, 5e-5])
@pytest.mark.parametrize("ncell", [7, 8])
@pytest.mark.parametrize("npts", [5, 20])
def test_linear_hats_fail_like_the_thesis(ncell, npts, dt):
    """Thesis tables 8 and 9: "extension instability" at 7 x 7 and 8 x 8 cells with 5 x 5
    and 20 x 20 points, at the thesis' dt = 1e-5 and at the 5e-5 of the runs below.
    Measured: points leave the grid at t = 0.019 / 0.096 (7 x 7, 5 / 20 points) and
    0.019 / 0.089 (8 x 8) with dt = 1e-5; 0.019 / 0.139 and 0.018 / 0.066 with dt = 5e-5;
    before that neighbouring points of the centre column separate by more than a cell (the
    material tears; largest gaps 1.4-7 cells, measured with dt = 5e-5)."""
    sim = truss(ncell, npts, "linear", end=0.3, dt=dt)
    with pytest.raises(RunError) as info:
        sim.run()
    print(f"scene 2, linear, {ncell}x{ncell} cells, {npts}x{npts} points, dt = {dt}: fails "
          f"at t = {sim.time:.4f}: {info.value.cause}")
    assert sim.time < 0.15


@pytest.mark.parametrize("ncell", [7, 8])
def test_linear_hats_with_100x100_points_match_the_thesis(ncell):
    """Where the thesis' linear hats run at 7 x 7 and 8 x 8 cells (100 x 100 points), ours
    run too and give its l_y and l_x within 2 % and 3 % (t = 0.5, when alpha_d = 25 has
    shrunk the swing to e^-6.25 ~ 0.2 %; the thesis ran to T = 2).
    Measured, dt = 5e-5: 7 x 7: l_y = 0.1214 (+1.0 %), l_x = 0.0310 (-1.3 %); 8 x 8:
    l_y = 0.1224 (+0.9 %), l_x = 0.0309 (-1.0 %). With the thesis' dt = 1e-5 (82-110 s a
    run): 0.1205 / 0.0313 and 0.1213 / 0.0313, within 0.3 % of the thesis.
    The same field, sampled at the seeds of 20 x 20 and 5 x 5 points (`sampled_spans`),
    gives the REFERENCE of the coarse runs; checked here to its 4 digits."""
    field = {}
    ly, lx = run_stably(ncell, 100, "linear", END, field)
    # the coarse-point REFERENCE comes from this field (and must still come from it)
    for npts in (20, 5):
        ref = sampled_spans(field["x0"], field["x"], 100, npts)
        print(f"  sampled at the {npts}x{npts} seeds: l_y = {ref[0]:.4f}, l_x = {ref[1]:.4f}")
        np.testing.assert_allclose(ref, REFERENCE[(ncell, npts)], atol=1e-4)
    check_spans(f"linear, {ncell}x{ncell} cells, 100x100 points", (ly, lx), THESIS_100[ncell],
                0.02, 0.03)


@pytest.mark.parametrize("ncell", [7, 8])
@pytest.mark.parametrize("npts", [5, 20])
def test_cpdi_runs_stably_where_linear_hats_fail(ncell, npts):
    """CPDI at the thesis' failing resolutions: runs to t = END (module docstring) without
    failure, with every det F > 0, and gives l_y within 4 % and l_x within 6 % of the
    coarse-point REFERENCE. Measured (dt = 5e-5, t = 0.5): 7 x 7 cells: 20 points
    l_y = 0.1137 (-2.1 %), l_x = 0.0310 (+2.1 %), 5 points 0.0966 (+0.4 %), 0.0268 (-0.3 %);
    8 x 8: 20 points 0.1146 (-2.1 %), 0.0311 (+3.0 %), 5 points 0.0953 (-1.9 %), 0.0267
    (+1.0 %). The l_y of 20 points sits 2 % under the reference, about the spread between
    the linear hats' and CPDI's 100 x 100 fields (0.1224 and 0.1197 at 8 x 8 cells, side
    0.3: 0.1201 and 0.1197)."""
    check_spans(f"CPDI, {ncell}x{ncell} cells, {npts}x{npts} points, t = {END}",
                run_stably(ncell, npts, "cpdi", END), REFERENCE[(ncell, npts)], 0.04, 0.06)


@pytest.mark.parametrize("ncell", [7, 8])
def test_quadratic_bsplines_run_stably_with_20x20_points(ncell):
    """Quadratic B-splines at the thesis' failing 7 x 7 and 8 x 8 cells with 20 x 20 points:
    stable to t = END and l_y within 4 % of the REFERENCE. Their top row stays narrower:
    measured l_y = 0.1167 (+0.5 %) / 0.1173 (+0.3 %), l_x = 0.0268 (-11.9 %) / 0.0288
    (-4.5 %) on 7 x 7 / 8 x 8 cells, so l_x is held to 15 % (the support, 3 cells = 0.077
    on 7 x 7 cells, is wider than the block, 0.06, and smooths its lateral contraction).
    With 5 x 5 points they tear at t = 0.02 like the linear hats (not asserted)."""
    check_spans(f"quadratic B-splines, {ncell}x{ncell} cells, 20x20 points, t = {END}",
                run_stably(ncell, 20, "quadratic", END), REFERENCE[(ncell, 20)], 0.04, 0.15)
