"""HDF5 files of a run: their names, opening them, the version stamp, and the one collective
slice write that output and checkpoints share (io/snapshots.py, io/checkpoint.py)."""
import glob
import os
import re
from collections import namedtuple
from importlib.metadata import version

import h5py
import numpy as np

# Dense attribute storage (the 1.8 file format) so large attributes (a long case text, the
# counts of many ranks) do not hit the 64 KiB object-header limit.
LIBVER = ("v108", "latest")
#: the snapshot file's group of per-step groups, and of the XDMF polyvertex connectivities
GROUP = "snapshots"
TOPOLOGY = "xdmf/polyvertex"


def code_version():
    """Installed pmpmsph version (or 'unknown' when running from an uninstalled tree)."""
    try:
        return version("pmpmsph")
    except Exception:  # noqa: BLE001 - any failure just means "not installed"
        import pmpmsph  # noqa: PLC0415 - the package itself, a circle at import time

        return getattr(pmpmsph, "__version__", "unknown")


def snapshot_name(index):
    """The group name of snapshot `index` (000000, 000001, ...)."""
    return f"{int(index):06d}"


def rank_file(path, rank):
    """Per-rank file of ``path`` (``RUN.h5`` -> ``RUN.r3.h5``), in the same directory."""
    path = os.fspath(path)
    stem, _ = os.path.splitext(os.path.basename(path))
    return os.path.join(os.path.dirname(path), f"{stem}.r{rank}.h5")


def rank_files_present(path):
    """The per-rank files of ``path`` that exist (``RUN.r0.h5``, ...)."""
    path = os.fspath(path)
    stem, _ = os.path.splitext(os.path.basename(path))
    pattern = re.compile(re.escape(stem) + r"\.r\d+\.h5$")
    folder = os.path.dirname(path) or "."
    return [p for p in glob.glob(os.path.join(glob.escape(folder), f"{glob.escape(stem)}.r*.h5"))
            if pattern.search(os.path.basename(p))]


def xdmf_path_for(path):
    """The XDMF sidecar of ``RUN.h5``: ``RUN.xdmf``."""
    return os.path.splitext(os.fspath(path))[0] + ".xdmf"


def open_h5(path, mode, **kw):
    """h5py.File without HDF5 file locking (readers and the writer must not block each other)."""
    try:
        return h5py.File(path, mode, locking=False, **kw)
    except (TypeError, ValueError):  # h5py/HDF5 too old for the locking switch
        return h5py.File(path, mode, **kw)


def connectivity_dtype(n_total):
    return np.int32 if n_total < 2**31 else np.int64


def write_slice(dset, offset, arr, collective):
    """Write arr into rows [offset, offset + n) with one H5Dwrite, even when n == 0.

    h5py's ``dset[a:b] = ...`` skips the H5Dwrite call for an empty selection, which would
    leave the other ranks waiting in a collective write; here a rank that owns nothing
    takes part with an empty selection.
    """
    n = arr.shape[0]
    trailing = arr.shape[1:]
    fspace = dset.id.get_space()
    if n > 0:
        fspace.select_hyperslab((offset,) + (0,) * len(trailing), (n,) + trailing)
        buf = np.ascontiguousarray(arr, dtype=dset.dtype)
        mspace = h5py.h5s.create_simple(buf.shape)
    else:
        fspace.select_none()
        buf = np.zeros((1,) + trailing, dtype=dset.dtype)
        mspace = h5py.h5s.create_simple(buf.shape)
        mspace.select_none()
    dxpl = None
    if collective:
        dxpl = h5py.h5p.create(h5py.h5p.DATASET_XFER)
        dxpl.set_dxpl_mpio(h5py.h5fd.MPIO_COLLECTIVE)
    dset.id.write(mspace, fspace, buf, dxpl=dxpl)


#: one snapshot of a run file (`complete_snapshots`, `snapshot_read.list_snapshots`)
SnapshotInfo = namedtuple("SnapshotInfo", "index name step time n_total")


def complete_snapshots(grp):
    """SnapshotInfo of every complete snapshot in the open snapshot group `grp`, in order.
    The last group may be one that a killed run left half-written (no attributes yet, or an
    object header the kill cut short): it is no snapshot and is left out. An unreadable
    group before the last is an error (raised as is)."""
    names = sorted(grp.keys())
    out = []
    for k, name in enumerate(names):
        try:
            a = grp[name].attrs
            out.append(SnapshotInfo(int(name), name, int(a["step"]), float(a["time"]),
                                    int(a["n_total"])))
        except (KeyError, OSError):
            if k < len(names) - 1:
                raise
    return out
