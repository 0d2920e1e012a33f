"""A run stopped by SIGTERM leaves readable output and a checkpoint; restarted on another
rank count it reaches the state of an uninterrupted run (DESIGN.md §6, §7).

Runs from the serial session and starts its own `scripts/mpirun -n 2` (a test under mpirun
cannot start another mpirun). The SIGTERM goes to the rank processes themselves: Open MPI's
mpirun answers a SIGTERM of its own by killing the ranks a second later (see docs/output.md).
"""
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from pmpmsph.config import load_case_file, parse_set
from pmpmsph.io import list_snapshots, read_diagnostics, read_snapshot
from pmpmsph.io.checkpoint import read_header

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = os.path.join(ROOT, "cases", "two_disks_contact.toml")
# double-precision snapshots: their positions are compared with the state to 1e-10
SETS = ["time.end=0.4", "output.every=0.1", "output.precision=double"]

pytestmark = pytest.mark.timeout(300)


def _env():
    return dict(os.environ, PYTHONPATH=ROOT)


def _children(pid):
    """Pids of the processes whose parent is `pid` (the ranks mpirun started)."""
    out = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as fh:
                stat = fh.read()
        except OSError:
            continue
        if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
            out.append(int(entry))
    return out


def _rows(path):
    try:
        with open(path) as fh:
            return sum(1 for _ in fh) - 1
    except OSError:
        return -1


def test_sigterm_leaves_checkpoint_and_restart_on_one_rank_matches(tmp_path):
    out = tmp_path / "run"
    sets = [a for s in SETS for a in ("--set", s)]
    cmd = [os.path.join(ROOT, "scripts", "mpirun"), "-n", "2", sys.executable, "-m", "pmpmsph",
           CASE, "--out", str(out), "--progress", "1000000", *sets]
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=_env(), cwd=ROOT)
    try:
        deadline = time.time() + 200  # the first run may compile the kernels
        while time.time() < deadline and proc.poll() is None:
            if _rows(out / "diagnostics.csv") > 300:  # in the time loop, handlers installed
                break
            time.sleep(0.02)
        assert proc.poll() is None, "the run ended before it could be stopped"
        ranks = _children(proc.pid)
        assert len(ranks) == 2
        for pid in ranks:
            os.kill(pid, signal.SIGTERM)
        _, stderr = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 3, stderr
    assert stderr.count("stopped by SIGTERM") == 1, stderr

    # Output left readable: the snapshots up to the stop, the last one at the stop step.
    h5 = out / "particles.h5"
    head = read_header(out / "checkpoint.h5")
    stop = head["step"]
    assert 300 <= stop < 4000 and head["n_ranks"] == 2 and head["n_total"] == 632
    infos = list_snapshots(h5)
    assert infos[-1].step == stop and infos[0].step == 0
    _, _, data = read_snapshot(h5, -1)
    assert data["x"].shape == (632, 3)
    assert read_diagnostics(out / "diagnostics.csv")["step"][-1] == stop

    # Restart on one rank from the stored case (with the stored --set overrides).
    r = subprocess.run([sys.executable, "-m", "pmpmsph", "--restart",
                        str(out / "checkpoint.h5")], capture_output=True, text=True,
                       env=_env(), cwd=ROOT, timeout=200)
    assert r.returncode == 0, r.stderr
    infos = list_snapshots(h5)
    steps = [i.step for i in infos]
    assert steps == sorted(set(steps)) and steps[-1] == 4000
    assert [i.time for i in infos if i.step > stop][-1] == pytest.approx(0.4, abs=1e-12)
    diag = read_diagnostics(out / "diagnostics.csv")["step"]
    np.testing.assert_array_equal(diag, np.arange(4001))  # continued, nothing repeated

    # The uninterrupted run, here on one rank.
    from pmpmsph.simulation import Simulation

    ref = Simulation(load_case_file(CASE, overrides=parse_set(SETS)))
    ref.run()
    _, step, data = read_snapshot(h5, -1)
    assert step == ref.step_count == 4000
    order = np.argsort(data["gid"])
    p = ref.particles
    ref_order = np.argsort(p["gid"])
    np.testing.assert_array_equal(data["gid"][order], p["gid"][ref_order])
    for name in ("x", "v"):
        a = data[name][order][:, :2]
        b = p[name][ref_order]
        assert np.max(np.abs(a - b)) <= 1e-10 * np.max(np.abs(b)), name
    assert time.perf_counter() - t0 < 120


def test_restart_with_bad_checkpoint_is_exit_2(tmp_path, capsys):
    from pmpmsph.cli import main

    bad = tmp_path / "checkpoint.h5"
    bad.write_text("not hdf5")
    assert main(["--restart", str(bad), "--no-output"]) == 2
    err = capsys.readouterr().err
    assert "--restart" in err and "Traceback" not in err
    assert main(["--no-output"]) == 2  # neither a case nor a checkpoint
