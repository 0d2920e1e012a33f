"""Every case in cases/ passes `check` and runs 5 steps with finite energies.

`check` goes through the command line entry point (in-process, so the Numba cache of this
process is reused); the 5 steps go through the Python API without output files. Each case
must also carry the header comment every case has (source, what to look at, expected result,
runtime).
"""
import math
from pathlib import Path

import numpy as np
import pytest

from pmpmsph import load_case_file
from pmpmsph.cli import main
from pmpmsph.simulation import Simulation

CASES = sorted((Path(__file__).resolve().parents[2] / "cases").glob("*.toml"))


def test_there_are_cases():
    assert len(CASES) >= 13


@pytest.mark.parametrize("path", CASES, ids=[p.stem for p in CASES])
def test_header_comment(path):
    head = []
    for line in path.read_text(encoding="utf-8").splitlines():
        if not line.startswith("#"):
            break
        head.append(line.lower())
    text = "\n".join(head)
    for word in ("source", "look at", "expected", "runtime"):
        assert word in text, f"{path.name}: header comment lacks '{word}'"


@pytest.mark.parametrize("path", CASES, ids=[p.stem for p in CASES])
def test_check_and_five_steps(path, capsys):
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "particles" in out and "dt" in out

    sim = Simulation(load_case_file(path), out_dir=None)
    before = sim.diagnostics()
    summary = sim.run(max_steps=5)
    after = sim.diagnostics()
    assert summary["steps"] == 5
    assert sim.step_count == 5
    for d in (before, after):
        for key in ("kinetic", "strain", "potential", "total", "px", "py", "pz", "mass"):
            assert math.isfinite(d[key]), f"{path.name}: {key} = {d[key]}"
    assert after["mass"] == pytest.approx(before["mass"], rel=1e-12)
    assert np.all(np.isfinite(sim.particles["x"]))
    assert np.all(np.isfinite(sim.particles["sigma"]))
