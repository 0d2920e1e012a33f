"""Checkpoints on one rank: periodic (output.checkpoint_every), at a failure, restart into a
new folder with a later end time (DESIGN.md §6, §7)."""
import os

import numpy as np
import pytest

from pmpmsph import ConfigError, load_case_text
from pmpmsph.cli import main
from pmpmsph.io import list_snapshots, read_diagnostics, read_snapshot
from pmpmsph.io.checkpoint import read_checkpoint, read_header

CASE = """
dimension = 2
[grid]
length = [1.0, 1.0]
cells = [10, 10]
[materials.m]
model = "neo_hookean"
E = 1000.0
nu = 0.3
rho = 1000.0
[[bodies]]
name = "block"
material = "m"
shape = "box"
min = [0.3, 0.3]
max = [0.6, 0.6]
ppc = 2
velocity = [0.05, 0.02]
[time]
end = 0.05
dt = 1e-3
[output]
every_steps = 20
checkpoint_every = 15
# the restart is compared with an uninterrupted run to 1e-10 through the snapshots
precision = "double"
fields = ["gid", "x", "v", "F", "sigma"]
"""

BULLET = """
[[bodies]]
name = "bullet"
material = "m"
shape = "box"
min = [0.92, 0.5]
max = [0.95, 0.53]
count = [1, 1]
velocity = [3.0, 0.0]
"""


def test_checkpoint_every_key_is_validated():
    assert load_case_text(CASE).output.checkpoint_every == 15
    assert load_case_text(CASE.replace("checkpoint_every = 15", "")).output.checkpoint_every == 0
    with pytest.raises(ConfigError) as err:
        load_case_text(CASE.replace("checkpoint_every = 15", "checkpoint_every = -1"))
    assert err.value.key == "output.checkpoint_every"


def test_periodic_checkpoints_then_restart_in_new_folder_with_later_end(tmp_path):
    case = tmp_path / "c.toml"
    case.write_text(CASE)
    run, again = str(tmp_path / "run"), str(tmp_path / "again")
    assert main([str(case), "--out", run]) == 0
    head = read_header(os.path.join(run, "checkpoint.h5"))
    assert head["step"] == 50 and head["time"] == pytest.approx(0.05)  # the run's end
    assert head["case_overrides"] == [] and head["case_dir"] == str(tmp_path)
    assert head["case"] == CASE and head["counts"] == [36] and head["faces"] == [0, 10]
    assert not os.path.exists(os.path.join(run, "checkpoint.h5.tmp"))
    # continue to t = 0.08 in another folder, from the stored case text
    assert main(["--restart", os.path.join(run, "checkpoint.h5"), "--out", again,
                 "--set", "time.end=0.08"]) == 0
    steps = [i.step for i in list_snapshots(os.path.join(again, "particles.h5"))]
    assert steps == [50, 60, 80]
    assert read_diagnostics(os.path.join(again, "diagnostics.csv"))["step"].tolist() == \
        list(range(50, 81))
    assert read_header(os.path.join(again, "checkpoint.h5"))["case_overrides"] == \
        [("time.end", 0.08)]
    # ... the same as one run to t = 0.08, to round-off (the first run's last step was cut
    # to end exactly at t = 0.05)
    ref = str(tmp_path / "ref")
    assert main([str(case), "--out", ref, "--set", "time.end=0.08"]) == 0
    _, sa, a = read_snapshot(os.path.join(again, "particles.h5"), -1)
    _, sb, b = read_snapshot(os.path.join(ref, "particles.h5"), -1)
    assert sa == sb == 80
    for k in ("x", "v", "F", "sigma"):
        ka, kb = a[k][np.argsort(a["gid"])], b[k][np.argsort(b["gid"])]
        assert np.max(np.abs(ka - kb)) <= 1e-10 * np.max(np.abs(kb)), k


def test_failure_writes_checkpoint_failed_and_keeps_the_last_good_one(tmp_path, capsys):
    case = tmp_path / "c.toml"
    case.write_text(CASE.replace("end = 0.05", "end = 1.0") + BULLET)
    run = str(tmp_path / "run")
    assert main([str(case), "--out", run]) == 3
    err = capsys.readouterr()
    assert "left the grid" in err.err
    good = read_header(os.path.join(run, "checkpoint.h5"))
    head, rows = read_checkpoint(os.path.join(run, "checkpoint_failed.h5"))
    assert "left the grid" in head["failed"]
    assert good["step"] % 15 == 0 and good["step"] <= head["step"] < good["step"] + 15
    assert "failed" not in good
    assert len(rows["gid"]) == 37
    infos = list_snapshots(os.path.join(run, "particles.h5"))  # readable, last = failure
    assert infos[-1].step == head["step"]
    assert main(["--restart", os.path.join(run, "checkpoint.h5"), "--no-output",
                 "--max-steps", "2"]) == 0  # the good one restarts
    one_body = tmp_path / "one.toml"  # a case without the bullet: body 1 does not exist
    one_body.write_text(CASE)
    capsys.readouterr()
    assert main(["--restart", os.path.join(run, "checkpoint.h5"), str(one_body),
                 "--no-output"]) == 2
    assert "refer to body 1" in capsys.readouterr().err
