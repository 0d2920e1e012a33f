"""Checkpoints: the whole state of a run in one HDF5 file, restartable on any rank count.

Layout of ``RUN/checkpoint.h5`` (the same whichever way it was written)::

    /            attrs: format ("pmpmsph-checkpoint-1"), layout (serial | mpio | per-rank),
                        case (TOML text), case_name, case_overrides (JSON list of the
                        [key, value] pairs given with --set), case_dir (folder of relative
                        paths in the case, e.g. mesh files), code_version, n_ranks, counts
                        (owned particles per rank), n_total, dim, time, step, dt,
                        next_snapshot_time, axis (slab axis, -1 without slabs), faces (slab
                        faces in cells, empty without slabs), fields (names in order),
                        written (UTC time), failed (the cause; only in checkpoint_failed.h5)
    /particles/<field>  (n_total, ...) every field the ParticleSet declares as migrating
                        (``particles.fields(migrate=True)``), natural shape and dtype, owned
                        rows only; rank r's rows at offset sum(counts[:r])

Written like the snapshots (``io.snapshots``): one file opened by every rank with
``driver="mpio"`` and collective writes (an empty selection on ranks that own nothing) when
h5py has MPI, else per-rank part files ``checkpoint.<token>.r<r>.h5`` joined by HDF5
virtual datasets in the main file, one plain file on one rank. Atomically: everything goes
to ``checkpoint.h5.tmp`` (and parts with a fresh token); when every rank is done, rank 0
renames it over ``checkpoint.h5`` (``os.replace``) and only then deletes the parts of the
previous checkpoint. A crash while writing leaves the previous checkpoint intact.

Restart (``Simulation.restore_checkpoint``): every rank reads the particle rows in chunks
and keeps those it owns under the new decomposition, so any rank count can continue.
"""
import datetime
import glob
import json
import os
import re
import signal
import threading
import uuid

import h5py
import numpy as np

from .h5files import LIBVER, code_version, open_h5, write_slice

FORMAT = "pmpmsph-checkpoint-1"
GROUP = "particles"
MODES = ("auto", "serial", "mpio", "per-rank")
#: rows read at once on restart (bounded memory however large the checkpoint)
READ_CHUNK = 1 << 20


class CheckpointError(Exception):
    """A checkpoint that cannot be written or does not fit the case (message for the user)."""


# -- collective helpers ---------------------------------------------------------------------------
def _everywhere(dist, fn, what):
    """Run fn on every rank; if it fails on any rank, raise on every rank."""
    err = None
    try:
        fn()
    except Exception as exc:  # noqa: BLE001 - re-raised below, on every rank
        err = exc
    if dist.any(err is not None):
        if err is not None:
            raise err
        raise CheckpointError(f"checkpoint failed on another rank while {what}")


def _on_root(dist, fn, what):
    """Run fn on rank 0 only; if it fails, raise on every rank. Returns fn's result (bcast)."""
    out, err = None, None
    if dist.is_root:
        try:
            out = fn()
        except Exception as exc:  # noqa: BLE001 - re-raised below
            err = exc
    msg = dist.bcast(None if err is None else f"{type(err).__name__}: {err}")
    if err is not None:
        raise err
    if msg is not None:
        raise CheckpointError(f"checkpoint failed on rank 0 while {what}: {msg}")
    return dist.bcast(out)


def _choose_mode(dist, mode):
    if mode not in MODES:
        raise ValueError(f"unknown checkpoint mode {mode!r}, expected one of {MODES}")
    if dist.size == 1:
        return "serial"
    if mode == "auto":
        return "mpio" if h5py.get_config().mpi else "per-rank"
    if mode == "serial":
        raise ValueError("checkpoint mode 'serial' needs a single rank")
    return mode


def part_file(path, token, rank):
    stem = os.path.splitext(os.path.basename(os.fspath(path)))[0]
    return os.path.join(os.path.dirname(os.fspath(path)), f"{stem}.{token}.r{rank}.h5")


def _stale_parts(path, keep_token):
    stem = os.path.splitext(os.path.basename(path))[0]
    folder = os.path.dirname(path) or "."
    pattern = re.compile(re.escape(stem) + r"\.([0-9a-f]+)\.r\d+\.h5$")
    out = []
    for p in glob.glob(os.path.join(glob.escape(folder), glob.escape(stem) + ".*.r*.h5")):
        m = pattern.search(os.path.basename(p))
        if m and m.group(1) != keep_token:
            out.append(p)
    return out


# -- writing ---------------------------------------------------------------------------------------
def write_checkpoint(dist, path, fields, attrs, mode="auto"):
    """Write owned rows `fields` ({name: array}, same names/dtypes/trailing shapes on every
    rank) and root attributes `attrs` (rank 0's are used) to `path`; collective.

    Returns the path. Adds format, layout, code_version, n_ranks, counts, n_total, fields and
    written to the attributes.
    """
    path = os.path.abspath(os.fspath(dist.bcast(os.fspath(path))))
    mode = _choose_mode(dist, mode)
    arrays = {k: np.ascontiguousarray(v) for k, v in fields.items()}
    n = len(next(iter(arrays.values()))) if arrays else 0
    if any(len(a) != n for a in arrays.values()):
        raise ValueError("checkpoint fields have different row counts")
    signature = [(k, a.dtype.str, a.shape[1:]) for k, a in arrays.items()]
    root_sig = dist.bcast(signature)
    if dist.any(signature != root_sig):
        raise ValueError("checkpoint fields differ between ranks")
    counts = dist.gather_counts(n)
    offset = int(counts[: dist.rank].sum())
    n_total = int(counts.sum())
    meta = dict(attrs)
    meta.update(format=FORMAT, layout=mode, code_version=code_version(), n_ranks=dist.size,
                counts=counts, n_total=n_total, fields=json.dumps(list(arrays)),
                written=datetime.datetime.now(datetime.timezone.utc).isoformat(
                    timespec="seconds"))
    meta = dist.bcast(meta)  # identical metadata on every rank (collective attribute writes)
    tmp = path + ".tmp"
    token = dist.bcast(uuid.uuid4().hex[:12]) if mode == "per-rank" else None

    def prepare():
        os.makedirs(os.path.dirname(path), exist_ok=True)
        if os.path.exists(tmp):
            os.remove(tmp)

    _on_root(dist, prepare, "preparing the folder")
    if mode == "mpio":
        def write_mpio():
            with open_h5(tmp, "w", driver="mpio", comm=dist.comm, libver=LIBVER) as f:
                _set_attrs(f, meta)
                grp = f.create_group(GROUP, track_order=True)
                for name, arr in arrays.items():
                    dset = grp.create_dataset(name, shape=(n_total,) + arr.shape[1:],
                                              dtype=arr.dtype)
                    if n_total > 0:
                        write_slice(dset, offset, arr, collective=True)

        _everywhere(dist, write_mpio, "writing collectively")
    elif mode == "serial":
        def write_serial():
            with open_h5(tmp, "w", libver=LIBVER) as f:
                _set_attrs(f, meta)
                grp = f.create_group(GROUP, track_order=True)
                for name, arr in arrays.items():
                    grp.create_dataset(name, data=arr)

        write_serial()
    else:
        def write_part():
            with open_h5(part_file(path, token, dist.rank), "w", libver=LIBVER) as f:
                f.attrs["format"] = FORMAT
                f.attrs["layout"] = "per-rank part"
                f.attrs["rank"] = dist.rank
                f.attrs["offset"] = offset
                grp = f.create_group(GROUP, track_order=True)
                for name, arr in arrays.items():
                    grp.create_dataset(name, data=arr)

        _everywhere(dist, write_part, "writing the per-rank part")
        _on_root(dist, lambda: _write_virtual(tmp, path, token, meta, root_sig, counts),
                 "joining the parts")
    dist.barrier()  # every rank's data is in place: publish the new checkpoint atomically

    def publish():
        os.replace(tmp, path)
        for stale in _stale_parts(path, token):
            os.remove(stale)

    _on_root(dist, publish, "renaming the file")
    return path


def _set_attrs(f, meta):
    for key, value in meta.items():
        if value is None:
            continue
        f.attrs[key] = value


def _write_virtual(tmp, path, token, meta, signature, counts):
    starts = np.concatenate([[0], np.cumsum(counts)])
    n_total = int(counts.sum())
    with open_h5(tmp, "w", libver=LIBVER) as f:
        _set_attrs(f, meta)
        grp = f.create_group(GROUP, track_order=True)
        for name, dtype, trailing in signature:
            dtype = np.dtype(dtype)
            layout = h5py.VirtualLayout(shape=(n_total,) + tuple(trailing), dtype=dtype)
            for r, c in enumerate(counts):
                if c == 0:
                    continue
                src = h5py.VirtualSource(os.path.basename(part_file(path, token, r)),
                                         f"/{GROUP}/{name}", shape=(int(c),) + tuple(trailing),
                                         dtype=dtype)
                layout[int(starts[r]):int(starts[r + 1])] = src
            grp.create_virtual_dataset(name, layout, fillvalue=0)


# -- reading ---------------------------------------------------------------------------------------
def _plain(value):
    if isinstance(value, bytes):
        return value.decode()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


def read_header(path):
    """Root attributes (plain Python values) plus ``field_specs`` {name: (trailing, dtype)}."""
    with open_h5(os.fspath(path), "r") as f:
        attrs = {k: _plain(v) for k, v in f.attrs.items()}
        if attrs.get("format") != FORMAT:
            raise CheckpointError(f"{path} is not a pmpmsph checkpoint (format "
                                  f"{attrs.get('format')!r})")
        grp = f[GROUP]
        attrs["field_specs"] = {k: (tuple(grp[k].shape[1:]), grp[k].dtype.str)
                                for k in json.loads(attrs["fields"])}
    attrs["fields"] = json.loads(attrs["fields"])
    attrs["case_overrides"] = [tuple(kv) for kv in json.loads(attrs.get("case_overrides", "[]"))]
    return attrs


def read_rows(path, names, keep=None, rows=None, chunk=READ_CHUNK):
    """The particle rows of `names` that `keep(x) -> mask` selects (all without it), read in
    chunks of `chunk` rows; `rows` = (lo, hi) restricts the rows looked at. Serial on each
    rank (the caller makes the ranks' selections disjoint)."""
    with open_h5(os.fspath(path), "r") as f:
        grp = f[GROUP]
        n_total = grp[names[0]].shape[0]
        lo, hi = rows if rows is not None else (0, n_total)
        parts = {k: [] for k in names}
        for a in range(lo, hi, chunk):
            b = min(a + chunk, hi)
            sel = None
            if keep is not None:
                sel = np.nonzero(keep(grp["x"][a:b]))[0]
                if len(sel) == 0:
                    continue
            for k in names:
                block = grp[k][a:b]
                parts[k].append(block if sel is None else block[sel])
        out = {}
        for k in names:
            dset = grp[k]
            out[k] = (np.concatenate(parts[k]) if parts[k]
                      else np.zeros((0,) + dset.shape[1:], dtype=dset.dtype))
    return out


def read_checkpoint(path):
    """(header, {field: all rows}) of a checkpoint, serially (tests, tools)."""
    head = read_header(path)
    return head, read_rows(path, head["fields"])


# -- graceful stop on signals -------------------------------------------------------------------
class StopRequest:
    """Signal handlers that only record the signal; `Simulation.run` polls `signum` at the end
    of every step (all ranks agree collectively) and then writes a checkpoint and stops.

    SIGTERM and SIGINT (Ctrl-C) are handled, and SIGUSR1, which Open MPI's mpirun forwards to
    the ranks as it is (it answers SIGTERM itself with SIGTERM to the ranks and SIGKILL one
    second later). A second SIGINT stops at once (KeyboardInterrupt), without a checkpoint.
    """

    SIGNALS = ("SIGTERM", "SIGINT", "SIGUSR1")

    def __init__(self):
        self.signum = 0
        self._old = {}

    @property
    def installed(self):
        return bool(self._old)

    def _handler(self, signum, frame):
        if self.signum and signum == signal.SIGINT:
            raise KeyboardInterrupt
        self.signum = signum

    def install(self):
        """Install the handlers (main thread only; elsewhere nothing happens)."""
        if self._old or threading.current_thread() is not threading.main_thread():
            return self
        self.signum = 0
        for name in self.SIGNALS:
            sig = getattr(signal, name, None)
            if sig is not None:
                self._old[sig] = signal.signal(sig, self._handler)
        return self

    def uninstall(self):
        for sig, old in self._old.items():
            signal.signal(sig, old)
        self._old = {}

    def __enter__(self):
        return self.install()

    def __exit__(self, *exc):
        self.uninstall()


#: the process's stop request (installed by the command line around `Simulation.run`)
STOP = StopRequest()


def signal_name(signum):
    try:
        return signal.Signals(signum).name
    except ValueError:
        return f"signal {signum}"
