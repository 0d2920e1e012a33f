"""Bad input found on one rank only stops every rank (issue 17, item 2).

Before step 1 the ranks agree on bad input at a few places (`Distributor.agree`,
`AGREEMENT_PLACES`): each place runs its local work, then one collective tells every rank
whether any failed. Here an error is injected on rank 1 only at each place
(PMPMSPH_INJECT_CONFIG_ERROR=1:place) under `mpirun -n 2`: every rank must exit 2 within the
time limit (a rank left waiting in a collective would hang: the test kills it and fails), and
the message appears once. Runs from the serial session and starts its own mpirun.
"""
import os
import re
import sys
from pathlib import Path

import pytest

from bounded_run import run_bounded
from pmpmsph.parallel.distributor import AGREEMENT_PLACES

ROOT = Path(__file__).resolve().parents[2]
CASE = ROOT / "cases" / "two_disks_contact.toml"
TIMEOUT = 180
_RANK_MAIN = """import os, sys
from pmpmsph.cli import main
rc = main(sys.argv[1:])
with open(os.path.join(os.environ["RC_DIR"], "rc." + os.environ["OMPI_COMM_WORLD_RANK"]),
          "w") as fh:
    fh.write(str(rc))
sys.exit(rc)
"""


def test_every_agreement_place_is_used_and_tested():
    """The places the code agrees at are exactly AGREEMENT_PLACES (a new one is tested)."""
    used = set()
    for path in (ROOT / "pmpmsph").rglob("*.py"):
        used |= set(re.findall(r"\.agree\(\s*\"([^\"]+)\"", path.read_text()))
    assert used == set(AGREEMENT_PLACES)


@pytest.mark.parametrize("place", AGREEMENT_PLACES)
def test_error_on_rank_one_only_stops_both_ranks(place, tmp_path):
    rcdir = tmp_path / "rc"
    rcdir.mkdir()
    args = [str(CASE), "--out", str(tmp_path / "out"), "--max-steps", "2"]
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    if place == "restart":  # a good checkpoint, read on rank 0 before the case
        first = run_bounded([sys.executable, "-m", "pmpmsph", *args, "--set",
                             "output.checkpoint_every=1"], TIMEOUT, cwd=tmp_path, env=env)
        assert first.returncode == 0, first.stderr
        args = ["--restart", str(tmp_path / "out" / "checkpoint.h5"), "--max-steps", "2"]
    env.update(RC_DIR=str(rcdir),
               PMPMSPH_INJECT_CONFIG_ERROR=f"1:{place}",
               OMPI_MCA_orte_abort_on_non_zero_status="0")
    r = run_bounded([str(ROOT / "scripts" / "mpirun"), "-n", "2", "--quiet", sys.executable,
                     "-c", _RANK_MAIN, *args], TIMEOUT, cwd=tmp_path, env=env)
    codes = {f.name: f.read_text() for f in rcdir.iterdir()}
    assert codes == {"rc.0": "2", "rc.1": "2"}, f"{place}: {codes}\n{r.stdout}\n{r.stderr}"
    assert "Traceback" not in r.stderr
    lines = [ln for ln in r.stderr.splitlines() if ln.startswith("error:")]
    assert lines == [f"error: invalid input at '<{place}>': fault injected on rank 1 at "
                     f"{place}"], r.stderr
