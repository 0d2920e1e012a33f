"""`python -m pmpmsph.bench accuracy --quick` on scene 14 (the vibrating bar), end to end:
the CSV, the observed orders, the plot and the generated summary; and the report's helpers
on made-up rows.

Measured (this build, --quick: one period, levels h = 1, 1/2, 1/4): MPM GIMP USL errors
6.61e-3, 2.54e-3, 1.09e-3 (fitted order 1.30); SPH UL Verlet with h = 2 spacings 3.30e-3,
8.55e-4, 2.62e-4 (1.83); SPH with h = 1.3 spacings does not converge (0.106, 0.108, 0.52).
"""
import csv
import math

import numpy as np
import pytest

from pmpmsph.bench.__main__ import main
from pmpmsph.bench.accuracy_core import COLUMNS
from pmpmsph.bench.accuracy_report import converges, fastest, order_of


def _row(method, knob, error, wall, note=""):
    return {"method": method, "family": "MPM", "knob": knob, "error": error, "wall": wall,
            "particle_steps": 1.0, "note": note}


def test_order_of_a_second_order_sequence():
    rows = [_row("a", h, 0.3 * h**2, 1 / h) for h in (1.0, 0.5, 0.25)]
    fit, last = order_of(rows)
    assert fit == pytest.approx(2.0, abs=1e-12) and last == pytest.approx(2.0, abs=1e-12)
    assert converges(rows, fit)
    flat = [_row("b", h, 1e-5, 1 / h) for h in (1.0, 0.5)]
    assert not converges(flat, order_of(flat)[0])  # at a floor: not converging


def test_fastest_picks_the_cheapest_point_under_the_target():
    rows = [_row("a", 1.0, 2e-2, 1.0), _row("a", 0.5, 5e-3, 4.0), _row("b", 1.0, 8e-3, 2.0),
            _row("c", 1.0, math.nan, 0.1, note="failed")]
    assert fastest(rows, 1e-2)["method"] == "b"
    assert fastest(rows, 1e-3) is None


@pytest.fixture(scope="module")
def quick_bar(tmp_path_factory):
    out = tmp_path_factory.mktemp("accuracy")
    assert main(["accuracy", "--quick", "--scenes", "vibrating_bar", "--out", str(out)]) == 0
    with open(out / "vibrating_bar.csv") as fh:
        rows = list(csv.DictReader(fh))
    return out, rows


def _errors(rows, method):
    return np.array([float(r["error"]) for r in rows if r["method"] == method])


def test_quick_csv_has_every_column_and_finite_costs(quick_bar):
    out, rows = quick_bar
    assert list(rows[0]) == COLUMNS
    gimp = [r for r in rows if r["method"] == "MPM gimp usl"]
    assert [int(r["level"]) for r in gimp] == [1, 2, 4]
    for r in gimp:
        assert float(r["wall"]) > 0 and int(r["particles"]) == 50 * int(r["level"])
        assert int(r["steps"]) == 1000 * int(r["level"])  # T = 10, dt = 0.01 h
        assert int(r["particle_steps"]) == int(r["particles"]) * int(r["steps"])
        assert int(r["particle_bytes"]) > 0


def test_quick_orders_of_gimp_and_sph(quick_bar):
    _, rows = quick_bar
    e = _errors(rows, "MPM gimp usl")
    assert np.all(np.isfinite(e)) and np.all(np.diff(e) < 0)
    assert e[0] < 1e-2
    assert 1.1 < np.polyfit(np.log([1, 0.5, 0.25]), np.log(e), 1)[0] < 1.6
    s = _errors(rows, "SPH UL verlet h=2.0s")
    assert np.all(np.diff(s) < 0)
    assert 1.5 < np.polyfit(np.log([1, 0.5, 0.25]), np.log(s), 1)[0] < 2.2


def test_quick_report_names_the_non_converging_methods(quick_bar):
    out, _ = quick_bar
    text = (out / "summary.md").read_text()
    assert "fastest to 1 %" in text and "fastest to 0.1 %" in text
    assert "SPH UL verlet h=1.3s (" in text  # listed with its cause
    assert "1.9 % fast" in text
    assert (out / "vibrating_bar.png").stat().st_size > 10_000
