"""Run the peer programs of ../shared/peers beside our own benchmark, in the same invocation.

Each peer prints "... X M particle-steps/s ..."; we parse that figure. A peer whose runtime is
missing is reported as such (with the command that installs it), never silently skipped.
"""
import os
import re
import subprocess
import sys

RATE = re.compile(r"([0-9.]+) M particle-steps/s")
PEERS_VENV = "/tmp/pmpmsph-peers-venv"


def peers_dir():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    return os.environ.get("PMPMSPH_PEERS", os.path.join(os.path.dirname(root), "shared", "peers"))


def _python_with(module):
    """A Python interpreter that can import `module` (ours, or the peers venv)."""
    candidates = [sys.executable, os.path.join(PEERS_VENV, "bin", "python")]
    for py in candidates:
        if os.path.exists(py):
            ok = subprocess.run([py, "-c", f"import {module}"], capture_output=True).returncode
            if ok == 0:
                return py
    return None


def install_peers():
    """Create the peers venv with Taichi (PySPH's script installs itself on first use)."""
    if not os.path.exists(os.path.join(PEERS_VENV, "bin", "python")):
        subprocess.run([sys.executable, "-m", "venv", PEERS_VENV], check=True)
    subprocess.run([os.path.join(PEERS_VENV, "bin", "pip"), "install", "-q", "taichi"],
                   check=True)


def run_peer(name, args=(), timeout=900):
    """Returns (rate in particle-steps/s or None, one-line note)."""
    script = os.path.join(peers_dir(), name)
    if not os.path.exists(script):
        return None, f"{script} not found"
    if name.endswith(".sh"):
        cmd = ["bash", script, *map(str, args)]
    else:
        module = "taichi" if "taichi" in name else "numba"
        py = _python_with(module)
        if py is None:
            return None, (f"{module} not installed for the peer (python -m pmpmsph.bench "
                          "throughput --install-peers)")
        cmd = [py, script, *map(str, args)]
    env = dict(os.environ, OMP_NUM_THREADS="1", NUMBA_NUM_THREADS="1")
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env,
                             cwd="/tmp")
    except subprocess.TimeoutExpired:
        return None, f"{name} timed out after {timeout} s"
    rates = RATE.findall(out.stdout)
    if not rates:
        tail = (out.stdout + out.stderr).strip().splitlines()[-1:] or ["no output"]
        return None, f"{name} gave no rate: {tail[0][:200]}"
    return float(rates[0]) * 1e6, out.stdout.strip().splitlines()[0]
