"""Reading particle snapshots back (serial, any layout of io/snapshots.py: plain, collective
MPI-IO or per-rank files joined by virtual datasets, which HDF5 resolves)."""
import os

import numpy as np

from .h5files import GROUP, complete_snapshots, open_h5
from .snapshots import SYM_ATTR, SYM_ORDER


def unpack_symmetric(arr):
    """(n, 6) components in the stored order -> (n, 3, 3) symmetric tensors (same dtype)."""
    arr = np.asarray(arr)
    full = np.empty((arr.shape[0], 3, 3), dtype=arr.dtype)
    for k, (i, j) in enumerate(SYM_ORDER):
        full[:, i, j] = arr[:, k]
        full[:, j, i] = arr[:, k]
    return full


def list_snapshots(path):
    """The snapshots of a run file, in order, as SnapshotInfo(index, name, step, time, n_total)
    (a last snapshot a killed run left half-written is not among them)."""
    with open_h5(os.fspath(path), "r") as f:
        grp = f.get(GROUP)
        if grp is None:
            raise ValueError(f"{path} is not a pmpmsph snapshot file (no /{GROUP} group)")
        return complete_snapshots(grp)


def read_snapshot(path, index=-1, fields=None, packed=False):
    """Read one snapshot: returns (time, step, {field: array}) with fields in written order.

    ``index`` counts snapshots like a Python list (-1 is the last). ``fields`` restricts the
    names read. Works for every layout (virtual datasets are resolved by HDF5). Symmetric
    tensors come back as (n, 3, 3), or as stored, (n, 6), with ``packed=True``. Arrays keep
    their stored dtype (float32 for a single-precision run).
    """
    infos = list_snapshots(path)
    if not infos:
        raise IndexError(f"{path} holds no snapshots yet")
    info = infos[index]
    with open_h5(os.fspath(path), "r") as f:
        grp = f[GROUP][info.name]
        names = list(grp.keys())
        if fields is not None:
            missing = [k for k in fields if k not in grp]
            if missing:
                raise KeyError(f"snapshot {info.name} of {path} has no field(s) {missing}")
            names = list(fields)
        data = {}
        for k in names:
            dset = grp[k]
            data[k] = dset[()]
            if not packed and _attr_str(dset.attrs.get("symmetric")) == SYM_ATTR:
                data[k] = unpack_symmetric(data[k])
    return info.time, info.step, data


def _attr_str(value):
    return value.decode() if isinstance(value, bytes) else value


def read_attrs(path):
    """Root attributes of a run file (case text, code version, n_ranks, layout, user attrs)."""
    with open_h5(os.fspath(path), "r") as f:
        return {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
