"""Scene 16 (BENCHMARKS.md): speed of a stress front in an elastic bar (1D) and in a strip in
plane strain between slip walls (2D, uniaxial strain), GIMP.

A traction of 1, ramped linearly over 0.05, pushes the left end of a free bar [0, 10]. The front
carries the particle velocity v = sigma/(rho c) at the speed c = sqrt(E/rho) (1D bar) or
c_p = sqrt((lambda + 2 mu)/rho) (plane strain, lateral motion blocked by the walls). We time
the instant a station's particle velocity first reaches v/2 (the middle of the ramp) at
x = 2.5 and x = 7.5: the front speed is 5 / (t_7.5 - t_2.5). At the free right end the front
reflects and the end moves at 2v; it reaches v at L/c + ramp/2.
Measured (this build): 1D speed -0.79 % (h = 0.1), -0.60 % (h = 0.05); end arrival +1.37 %,
+0.68 %; 2D speed -0.70 %, end arrival +1.37 % (h = 0.1).
"""
from pathlib import Path

import numpy as np
import pytest

from pmpmsph import load_case_file
from pmpmsph.simulation import Simulation

CASES = Path(__file__).resolve().parents[2] / "cases"
E, NU, RHO, LENGTH, RAMP, TRACTION = 100.0, 0.3, 1.0, 10.0, 0.05, 1.0


def by_gid(sim, name):
    """A particle field in gid (seeding) order: the solver re-sorts its rows by grid cell."""
    p = sim.particles
    return p[name][np.argsort(p["gid"])]


def wave_speed(dim):
    if dim == 1:
        return np.sqrt(E / RHO)
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    return np.sqrt((lam + 2 * mu) / RHO)


def arrival_times(dim, refine=1):
    h = 0.1 / refine
    box = {"min": [-1.0] * dim, "max": [0.04 / refine] + ([2.0] if dim == 2 else [])}
    overrides = [("grid.cell_size", h), ("time.dt", 0.001 / refine), ("loads[0].box", box),
                 ("grid.cells", [110 * refine] + ([10 * refine] if dim == 2 else []))]
    sim = Simulation(load_case_file(CASES / f"wave_speed_{dim}d.toml", overrides=overrides))
    c = wave_speed(dim)
    v = TRACTION / (RHO * c)
    X = by_gid(sim, "x")[:, 0].copy()
    # one loaded particle layer: the applied force is traction x loaded face area (the bar's
    # section is 1 in 1D, the strip is 1 high in 2D)
    assert sim.particles["fext0"][:, 0].sum() == pytest.approx(TRACTION, rel=1e-12)

    def column(xs):
        d = np.abs(X - xs)
        return d <= d.min() + 1e-9

    stations = {2.5: (column(2.5), v / 2), 7.5: (column(7.5), v / 2),
                "end": (X >= X.max() - 1e-9, v)}
    times = {}

    def watch(s):
        vx = by_gid(s, "v")[:, 0]
        for key, (sel, threshold) in stations.items():
            if key not in times and vx[sel].mean() >= threshold:
                times[key] = s.time

    sim.run(on_step=watch)
    assert set(times) == set(stations), f"front did not reach every station: {times}"
    return times, c


@pytest.mark.parametrize("dim,refine,tol_speed,tol_end", [(1, 1, 0.015, 0.025),
                                                          (1, 2, 0.010, 0.015),
                                                          (2, 1, 0.015, 0.025)])
def test_front_speed_and_arrival(dim, refine, tol_speed, tol_end):
    times, c = arrival_times(dim, refine)
    speed = 5.0 / (times[7.5] - times[2.5])
    expected_end = LENGTH / c + RAMP / 2
    err_speed = speed / c - 1
    err_end = times["end"] / expected_end - 1
    print(f"scene 16, {dim}D, h = {0.1 / refine:g}: front speed {speed:.4f} vs c = {c:.4f} "
          f"({err_speed:+.2%}); free end reached v at t = {times['end']:.4f} vs L/c + ramp/2 = "
          f"{expected_end:.4f} ({err_end:+.2%})")
    assert abs(err_speed) < tol_speed
    assert abs(err_end) < tol_end
