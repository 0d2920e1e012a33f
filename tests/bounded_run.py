"""A subprocess with a hang detector: past `timeout` the whole process group (mpirun and
every rank it started) is killed and the test fails, so a hung rank fails one test instead of
spinning until CI's own limit."""
import os
import signal
import subprocess

import pytest


def run_bounded(cmd, timeout, **kw):
    """subprocess.run(cmd, capture_output=True, text=True, **kw) in its own session; on
    timeout kill the session and fail the test with what it printed."""
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, **kw)
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, err = proc.communicate()
        pytest.fail(f"hung: no exit within {timeout} s: {' '.join(map(str, cmd))}\n"
                    f"{out}\n{err}")
    return subprocess.CompletedProcess(cmd, proc.returncode, out, err)
