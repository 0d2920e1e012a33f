"""An exception on one rank ends the whole mpirun within seconds, with the message once.

Runs from the serial test session and starts its own `mpirun -n 2` (a test under mpirun
cannot start another mpirun)."""
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = """
dimension = 2
[grid]
length = [1.0, 1.0]
cells = [20, 20]
[materials.m]
model = "neo_hookean"
E = 1000.0
nu = 0.3
rho = 1000.0
[[bodies]]
material = "m"
shape = "box"
min = [0.1, 0.1]
max = [0.9, 0.9]
ppc = 2
velocity = [0.01, 0.0]
[time]
end = 100.0
dt = 1e-3
"""


def _mpirun(args, env_extra, timeout):
    env = dict(os.environ, PYTHONPATH=ROOT, **env_extra)
    cmd = [os.path.join(ROOT, "scripts", "mpirun"), "-n", "2", sys.executable, "-m", "pmpmsph",
           *args]
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env, cwd=ROOT)
    return r, time.perf_counter() - t0


def test_exception_on_one_rank_ends_all_ranks(tmp_path):
    case = tmp_path / "fault.toml"
    case.write_text(CASE)
    # warm the JIT cache first so the timing below measures the shutdown, not compilation
    warm, _ = _mpirun([str(case), "--no-output", "--max-steps", "3"], {}, 600)
    assert warm.returncode == 0, warm.stderr
    r, seconds = _mpirun([str(case), "--no-output"], {"PMPMSPH_INJECT_FAULT": "1:20"}, 120)
    assert r.returncode != 0
    assert seconds < 30  # the other rank would otherwise wait forever in the next collective
    assert r.stderr.count("fault injected on rank 1 at step 20") == 1


def test_runtime_error_on_one_rank_is_reported_once_with_exit_3(tmp_path):
    # a particle thrown out of the grid on one side only: the check is collective
    case = tmp_path / "throw.toml"
    case.write_text(CASE.replace("velocity = [0.01, 0.0]", "velocity = [0.01, 0.0]") + """
[[bodies]]
name = "bullet"
material = "m"
shape = "box"
min = [0.92, 0.5]
max = [0.95, 0.53]
count = [1, 1]
velocity = [30.0, 0.0]
""")
    r, seconds = _mpirun([str(case), "--no-output"], {}, 300)
    assert r.returncode == 3, r.stderr
    lines = [ln for ln in r.stderr.splitlines() if ln.startswith("error:")]
    assert len(lines) == 1 and "left the grid" in lines[0] and "gid" in lines[0]


def test_nan_mid_run_stops_all_ranks_and_the_last_checkpoint_restarts(tmp_path):
    """A NaN velocity injected on rank 1 at step 25 (of 40): every rank stops with exit 3
    and one message naming the step, the particle and the NaN; the snapshots stay readable;
    the last checkpoint (step 20) restarted without the fault reaches the uninterrupted
    run's final state to 1e-10."""
    import numpy as np

    from pmpmsph.io.snapshots import read_snapshot

    case = tmp_path / "nan.toml"
    case.write_text(CASE.replace("end = 100.0", "end = 0.04") + """
[output]
every_steps = 10
checkpoint_every = 10
""")
    run, clean = tmp_path / "run", tmp_path / "clean"
    r, seconds = _mpirun([str(case), "--out", str(run)], {"PMPMSPH_INJECT_NAN": "1:25"}, 300)
    assert r.returncode == 3, r.stderr
    lines = [ln for ln in r.stderr.splitlines() if ln.startswith("error:")]
    assert len(lines) == 1 and "NaN" in lines[0] and "step 26" in lines[0], r.stderr
    assert "Traceback" not in r.stderr
    t, step, fields = read_snapshot(str(run / "particles.h5"), -1)
    assert len(fields["gid"]) == 1024
    r2, _ = _mpirun(["--restart", str(run / "checkpoint.h5"), "--out", str(tmp_path / "rs")],
                    {}, 300)
    assert r2.returncode == 0, r2.stderr
    r3, _ = _mpirun([str(case), "--out", str(clean)], {}, 300)
    assert r3.returncode == 0, r3.stderr
    _, s_a, a = read_snapshot(str(tmp_path / "rs" / "particles.h5"), -1)
    _, s_b, b = read_snapshot(str(clean / "particles.h5"), -1)
    assert s_a == s_b == 40
    ia, ib = np.argsort(a["gid"]), np.argsort(b["gid"])
    assert np.abs(a["x"][ia] - b["x"][ib]).max() < 1e-10


def test_check_command_on_two_ranks_does_not_hang(tmp_path):
    """`check` computes the stable time step (a collective) on every rank, not on rank 0
    only (it used to wait forever for the other rank)."""
    for case in ("two_disks.toml", "sph_dam_break.toml"):
        r, seconds = _mpirun(["check", os.path.join(ROOT, "cases", case)], {}, 120)
        assert r.returncode == 0, r.stderr
        assert r.stdout.count("stable limit") == 1
