"""Config validation: every bad input names its TOML key; the CLI exits 2 without a traceback."""
import os
import subprocess
import sys

import pytest

from pmpmsph import ConfigError, load_case_text

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GOOD = """
dimension = 2
gravity = [0.0, -9.81]
[grid]
origin = [0.0, 0.0]
length = [1.0, 1.0]
cells = [10, 10]
[materials.rubber]
model = "neo_hookean"
E = 1.0e4
nu = 0.3
rho = 1000.0
[[bodies]]
name = "block"
material = "rubber"
shape = "box"
min = [0.2, 0.2]
max = [0.4, 0.4]
ppc = 2
[[boundaries]]
face = "y-"
type = "slip"
[time]
end = 0.1
cfl = 0.5
"""


def test_good_case_loads():
    case = load_case_text(GOOD)
    assert case.dim == 2 and case.grid.cell_size == (0.1, 0.1)
    assert case.bodies[0].ppc == 2 and case.boundaries[0].normal == (0.0, -1.0)


@pytest.mark.parametrize("old,new,key", [
    ("nu = 0.3", "nu = 0.5", "materials.rubber.nu"),
    ("rho = 1000.0", "rho = -1.0", "materials.rubber.rho"),
    ('model = "neo_hookean"', 'model = "jelly"', "materials.rubber.model"),
    ('material = "rubber"', 'material = "steel"', "bodies[0].material"),
    ("ppc = 2", "ppc = 2.5", "bodies[0].ppc"),
    ("cells = [10, 10]", "cells = [10, 0]", "grid.cells[1]"),
    ("cfl = 0.5", "cfl = 0.5\ndt = 1e-3", "time.dt"),
    ("end = 0.1", "end = nan", "time.end"),
    ('type = "slip"', 'type = "sticky"', "boundaries[0].type"),
    ("dimension = 2", "dimension = 4", "dimension"),
    ("ppc = 2", "ppc = 2\ncolour = 3", "bodies[0].colour"),
    ('face = "y-"', 'face = "z-"', "boundaries[0].face"),
])
def test_bad_values_name_their_key(old, new, key):
    assert old in GOOD
    with pytest.raises(ConfigError) as err:
        load_case_text(GOOD.replace(old, new))
    assert err.value.key == key


def test_the_retired_contact_gap_says_why():
    text = GOOD.replace("[time]", '[mpm]\ncontact = "multi"\ncontact_gap = 1.5\n[time]')
    with pytest.raises(ConfigError) as err:
        load_case_text(text)
    assert err.value.key == "mpm.contact_gap" and "particle surfaces" in str(err.value)


def test_toml_syntax_error():
    with pytest.raises(ConfigError) as err:
        load_case_text(GOOD + "\n[grid\n")
    assert err.value.key == "<toml>"


def _cli(args, tmp_path):
    env = dict(os.environ, PYTHONPATH=ROOT)
    return subprocess.run([sys.executable, "-m", "pmpmsph", *args], capture_output=True,
                          text=True, cwd=tmp_path, env=env, timeout=300)


def test_cli_bad_input_exit_2_one_line(tmp_path):
    case = tmp_path / "bad.toml"
    case.write_text(GOOD.replace("nu = 0.3", "nu = 0.7"))
    r = _cli([str(case)], tmp_path)
    assert r.returncode == 2
    assert "Traceback" not in r.stderr
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and "materials.rubber.nu" in lines[0]
    assert not (tmp_path / "output").exists()


def test_cli_particles_outside_grid_and_dt_limit(tmp_path):
    case = tmp_path / "out.toml"
    case.write_text(GOOD.replace("max = [0.4, 0.4]", "max = [1.4, 0.4]"))
    r = _cli([str(case), "--no-output"], tmp_path)
    assert r.returncode == 2 and "bodies[0]" in r.stderr and "outside the grid" in r.stderr
    case.write_text(GOOD.replace("cfl = 0.5", "dt = 1.0"))
    r = _cli([str(case), "--no-output"], tmp_path)
    assert r.returncode == 2 and "time.dt" in r.stderr and "stable limit" in r.stderr
