#!/usr/bin/env bash
# The whole test suite: set-up if needed, then the serial tests, then the MPI tests under
# mpirun on 2 and 3 ranks (DESIGN.md section 8). Exit status non-zero if anything fails.
# Tiers: `bash scripts/test.sh` runs everything (CI); `bash scripts/test.sh quick` leaves out
# the tests marked `slow` (pyproject.toml's markers). The serial pass runs its test files on
# PMPMSPH_TEST_WORKERS processes (default 2, the cores of the reference machine; pytest-xdist,
# one file per worker at a time) and reports its 25 slowest tests.
set -euo pipefail
select=()
if [ "${1:-}" = "quick" ]; then select=(-m "not slow"); fi
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
bash scripts/setup.sh
py=.venv/bin/python
status=0
echo "== serial tests"
$py -m pytest -q -p no:cacheprovider --durations=25 -n "${PMPMSPH_TEST_WORKERS:-2}" \
  --dist loadfile "${select[@]}" tests || status=$?
echo "== MPI tests on 2 ranks"
scripts/mpirun -n 2 $py -m pytest -q -p no:cacheprovider -m "mpi${select:+ and not slow}" tests/parallel || status=$?
echo "== MPI tests on 3 ranks (oversubscribed)"
scripts/mpirun -n 3 $py -m pytest -q -p no:cacheprovider -m "mpi${select:+ and not slow}" tests/parallel || status=$?
exit $status
