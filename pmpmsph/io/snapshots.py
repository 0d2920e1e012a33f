"""Particle snapshots in one HDF5 file per run (DESIGN.md section 6).

Layout of ``RUN.h5`` (the same whichever way it was written)::

    /                          attrs: format, layout, case (TOML text), code_version,
                                      n_ranks, plus the caller's extra attrs
    /snapshots/000000          attrs: index, time, step, counts (owned particles per rank),
                                      n_total, n_ranks, layout (of this snapshot: a restarted
                                      run may append with another rank count or layout)
    /snapshots/000000/<field>  dataset of global shape (n_total, ...), rank r's slice at
                                      offset sum(counts[:r]); fields in the order written
    /xdmf/polyvertex/<N>       0, 1, ..., N-1 (int32, int64 from 2**31 particles): the
                                      Polyvertex connectivity the XDMF sidecar points to,
                                      written once per distinct particle count N and shared
                                      by every snapshot with that count

Tensors such as ``F`` keep their natural shape (n_total, 3, 3), row-major, so ``F[i]`` is
the 3x3 matrix of particle i (the XDMF sidecar declares them as ``Tensor`` with dimensions
``N 3 3``, which ParaView/VTK read as 9-component arrays). Fields named in ``symmetric`` are
stored as their 6 independent components (n_total, 6) in the XDMF ``Tensor6`` order xx, xy,
xz, yy, yz, zz, with the dataset attribute ``symmetric`` naming that order;
:func:`pmpmsph.io.snapshot_read.read_snapshot` expands them to (n, 3, 3), and so does VTK's
XDMF2 reader, but ParaView's XDMF3 reader shows the 6 raw components under VTK's labels (xx,
yy, zz, xy, yz, xz), so a run stores its stress in full. Boolean fields are stored as uint8.

``precision``: ``"single"`` stores every float field as float32 (half the bytes: what a
viewer needs, and the disk is the cost of a snapshot), ``"double"`` as float64, None (the
default of this class) as given. Ids and integer fields keep their dtype. A run takes
``[output] precision`` (default single); checkpoints (io/checkpoint.py) are always the full
float64 state, for an exact restart.

Three ways of writing, chosen automatically (``mode="auto"``):

- ``"serial"``   one rank: a plain HDF5 file.
- ``"mpio"``     several ranks and h5py built with MPI: the file is opened by every rank with
                 ``driver="mpio"``; groups and datasets are created collectively and every rank
                 writes its slice with one collective H5Dwrite, an empty selection on ranks
                 that own no particles.
- ``"per-rank"`` several ranks, serial h5py: rank r writes its slice to ``RUN.r{r}.h5``
                 (same group/dataset names, local shape (n_r, ...)); rank 0 writes ``RUN.h5``
                 whose datasets are HDF5 virtual datasets joining the per-rank files (found
                 next to ``RUN.h5``; move them together).

A restarted run continues the file (``append=True``): snapshots after the restart step are
dropped, the numbering goes on, and the root ``layout`` becomes ``mixed`` if the new run
writes differently (per-rank parts of earlier snapshots are kept and still referenced).

The file is opened for each snapshot and closed again, so between writes it is complete on
disk: a reader (ParaView, ``io.snapshot_read.read_snapshot``) can open it while the run
goes on or after a crash. HDF5 file locking is switched off for the same reason (a viewer
holding the file must not stop the run). After each snapshot rank 0 rewrites the XDMF sidecar
``RUN.xdmf``.
"""
import logging
import os

import h5py
import numpy as np

from .h5files import (GROUP, LIBVER, TOPOLOGY, code_version, complete_snapshots,
                      connectivity_dtype, open_h5,
                      rank_file, rank_files_present, snapshot_name, write_slice,
                      xdmf_path_for)
from .xdmf import write_xdmf

log = logging.getLogger("pmpmsph")

FORMAT = "pmpmsph-snapshots-1"
MODES = ("auto", "serial", "mpio", "per-rank")
PRECISIONS = {"single": np.float32, "double": np.float64}
#: components of a symmetric tensor as stored (the XDMF Tensor6 order), as (row, column)
SYM_ORDER = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
SYM_ATTR = "xx xy xz yy yz zz"



def _storage_array(name, arr, float_dtype=None, symmetric=False):
    """The array as it is stored: numpy, bool -> uint8, object/str dtypes refused; floats in
    `float_dtype` (None: as given); a symmetric (n, 3, 3) field as its (n, 6) components."""
    arr = np.asarray(arr)
    if arr.ndim == 0:
        raise ValueError(f"snapshot field '{name}' must have a particle axis, got a scalar")
    if arr.dtype == np.bool_:
        arr = arr.astype(np.uint8)
    if arr.dtype.kind not in "iuf":
        raise ValueError(f"snapshot field '{name}' has unsupported dtype {arr.dtype}")
    dtype = float_dtype if float_dtype is not None and arr.dtype.kind == "f" else arr.dtype
    if symmetric:
        if arr.shape[1:] != (3, 3):
            raise ValueError(f"symmetric snapshot field '{name}' must have shape (n, 3, 3), "
                             f"got {arr.shape}")
        packed = np.empty((arr.shape[0], 6), dtype=dtype)
        for k, (i, j) in enumerate(SYM_ORDER):  # the upper triangle; sigma is symmetric
            packed[:, k] = arr[:, i, j]
        return packed
    return arr.astype(dtype, copy=False)


class SnapshotWriter:
    """Writes particle snapshots of a run into one HDF5 file; every method is collective.

    ``fields`` given to :meth:`write` map a name to an array whose first axis is this rank's
    owned particle count; all ranks must pass the same names, dtypes and trailing shapes in
    the same order (checked). ``x`` (n, 3) is required when the XDMF sidecar is written.
    ``precision`` ("single", "double" or None: as given) sets the stored float type and
    ``symmetric`` names the (n, 3, 3) fields stored as 6 components (see the module doc).
    """

    def __init__(self, dist, path, *, case_text="", attrs=None, overwrite=False, mode="auto",
                 xdmf=True, append=False, after_step=None, precision=None, symmetric=()):
        if mode not in MODES:
            raise ValueError(f"unknown snapshot mode {mode!r}, expected one of {MODES}")
        if precision is not None and precision not in PRECISIONS:
            raise ValueError(f"unknown snapshot precision {precision!r}, expected one of "
                             f"{tuple(PRECISIONS)} or None")
        self.float_dtype = PRECISIONS.get(precision)
        self.symmetric = frozenset(symmetric)
        self.dist = dist
        self.path = os.path.abspath(os.fspath(dist.bcast(os.fspath(path))))
        self.xdmf = xdmf
        self.xdmf_path = xdmf_path_for(self.path)
        self.mode = self._choose_mode(mode)
        self.index = 0
        self._closed = False
        self._xdmf_cache = {}  # snapshot name -> its XDMF Grid element (rank 0)

        # Existing output: decided on rank 0, the same answer on every rank.
        exists = None
        if dist.is_root:
            exists = os.path.exists(self.path) or bool(rank_files_present(self.path))
        exists = dist.bcast(exists)
        self.appending = bool(append and exists and dist.bcast(os.path.exists(self.path)))
        #: step of the last snapshot kept when appending (None: none kept / a new file)
        self.last_step = None
        if exists and not overwrite and not self.appending:
            raise FileExistsError(
                f"output file {self.path} already exists (allow overwriting to replace it)")

        case_text = dist.bcast(case_text or "")
        attrs = dist.bcast(dict(attrs or {}))
        if self.appending:
            self._on_root(lambda: self._open_append(after_step))
            self.index, self.last_step = dist.bcast((self.index, self.last_step))
        else:
            self._on_root(lambda: self._create_main(exists, case_text, attrs))
        if self.mode == "per-rank":
            self._collective(lambda: self._create_rank_file(), "creating the per-rank file")
        if self.mode == "per-rank" and dist.size > 1 and mode == "auto" and dist.is_root:
            log.warning(
                "h5py is built without MPI: each rank writes %s and %s joins them with "
                "HDF5 virtual datasets (keep these files together)",
                os.path.basename(rank_file(self.path, "N")), os.path.basename(self.path))

    # -- set-up -----------------------------------------------------------------------------
    def _choose_mode(self, mode):
        mpi = bool(h5py.get_config().mpi)
        if mode == "auto":
            if self.dist.size == 1:
                return "serial"
            return "mpio" if mpi else "per-rank"
        if mode == "mpio" and not mpi:
            raise ValueError("snapshot mode 'mpio' needs h5py built with MPI")
        if mode == "serial" and self.dist.size > 1:
            raise ValueError("snapshot mode 'serial' needs a single rank")
        if mode == "mpio" and self.dist.size == 1:
            return "serial"
        return mode

    def _create_main(self, exists, case_text, attrs):
        if exists:
            for p in [self.path, self.xdmf_path] + rank_files_present(self.path):
                if os.path.exists(p):
                    os.remove(p)
        os.makedirs(os.path.dirname(self.path), exist_ok=True)
        with open_h5(self.path, "w", libver=LIBVER) as f:
            f.attrs["format"] = FORMAT
            f.attrs["layout"] = self.mode
            f.attrs["case"] = case_text
            f.attrs["code_version"] = code_version()
            f.attrs["n_ranks"] = self.dist.size
            for key, value in attrs.items():
                f.attrs[key] = value
            f.create_group(GROUP, track_order=True)
            f.create_group(TOPOLOGY)

    def _open_append(self, after_step):
        """Continue an existing file: keep its complete snapshots up to `after_step`, carry on
        numbering. Snapshots to drop (those after `after_step`, and a group a kill cut short)
        are not unlinked in place: unlinking from a file a kill left half-written crashed
        HDF5 itself (a segfault in H5Gunlink, seen in tests/parallel/test_faults.py), and
        once a "Couldn't delete link" error. The snapshots kept are copied into a fresh file
        that then replaces the old one. If the old file cannot even be read, it is kept
        beside the new one (`particles.h5.damaged`), so nothing written before the kill is
        lost."""
        try:
            rewrite = self._has_snapshots_to_drop(after_step)
        except (KeyError, OSError) as err:
            damaged = self.path + ".damaged"
            log.warning("%s: %s; its complete snapshots go to a new file, the old one is kept "
                        "as %s", self.path, err, os.path.basename(damaged))
            os.replace(self.path, damaged)
            self._copy_complete(damaged, self.path, after_step)
        else:
            if rewrite:
                fresh = self.path + ".tmp"
                self._copy_complete(self.path, fresh, after_step)
                os.replace(fresh, self.path)
        with open_h5(self.path, "r+", libver=LIBVER) as f:
            done = complete_snapshots(f[GROUP])
            self.index = done[-1].index + 1 if done else 0
            self.last_step = done[-1].step if done else None
            layout = f.attrs.get("layout")
            layout = layout.decode() if isinstance(layout, bytes) else layout
            if layout != self.mode:
                f.attrs["layout"] = "mixed"
            if TOPOLOGY not in f:
                f.create_group(TOPOLOGY)
        if self.xdmf:
            write_xdmf(self.path, self.xdmf_path, cache=self._xdmf_cache)

    def _keep(self, grp, after_step):
        """The names of the complete snapshots of `grp` up to `after_step`."""
        return [i.name for i in complete_snapshots(grp)
                if after_step is None or i.step <= after_step]

    def _has_snapshots_to_drop(self, after_step):
        """Whether the file holds groups after `after_step` or cut short (read only)."""
        with open_h5(self.path, "r", libver=LIBVER) as f:
            if f.attrs.get("format") != FORMAT or GROUP not in f:
                raise ValueError(f"cannot append to {self.path}: not a pmpmsph snapshot file")
            grp = f[GROUP]
            return len(self._keep(grp, after_step)) != len(grp)

    def _copy_complete(self, source, target, after_step):
        """Write `target` with the attributes, the topology and the complete snapshots up to
        `after_step` of `source`."""
        with open_h5(source, "r") as src, open_h5(target, "w", libver=LIBVER) as dst:
            for key, value in src.attrs.items():
                dst.attrs[key] = value
            dst.create_group(GROUP, track_order=True)
            if TOPOLOGY in src:
                src.copy(src[TOPOLOGY], dst, name=TOPOLOGY)
            for name in self._keep(src[GROUP], after_step):
                src.copy(src[GROUP][name], dst[GROUP], name=name)

    def _create_rank_file(self):
        path = rank_file(self.path, self.dist.rank)
        if self.appending and os.path.exists(path):  # earlier snapshots live in it: keep them
            return
        with open_h5(path, "w", libver=LIBVER) as f:
            f.attrs["format"] = FORMAT
            f.attrs["layout"] = "per-rank part"
            f.attrs["rank"] = self.dist.rank
            f.attrs["n_ranks"] = self.dist.size
            f.attrs["main_file"] = os.path.basename(self.path)
            f.create_group(GROUP, track_order=True)

    # -- collective error handling ------------------------------------------------------------
    def _on_root(self, fn):
        """Run fn on rank 0; if it fails, raise on every rank (no rank left waiting)."""
        err = None
        if self.dist.is_root:
            try:
                fn()
            except Exception as exc:  # noqa: BLE001 - re-raised below, on every rank
                err = exc
        msg = self.dist.bcast(None if err is None else f"{type(err).__name__}: {err}")
        if err is not None:
            raise err
        if msg is not None:
            raise RuntimeError(f"snapshot output failed on rank 0: {msg}")

    def _collective(self, fn, what):
        """Run fn on every rank; if it fails anywhere, raise everywhere."""
        err = None
        try:
            fn()
        except Exception as exc:  # noqa: BLE001 - re-raised below
            err = exc
        if self.dist.any(err is not None):
            if err is not None:
                raise err
            raise RuntimeError(f"snapshot output failed on another rank while {what}")

    # -- writing ------------------------------------------------------------------------------
    def _check_fields(self, fields):
        """Validate locally, then agree on every rank; returns (arrays, n_local)."""
        arrays, n, err = {}, None, None
        try:
            if not fields:
                raise ValueError("a snapshot needs at least one field")
            for name, value in fields.items():
                if "/" in name or not name:
                    raise ValueError(f"invalid snapshot field name {name!r}")
                arr = _storage_array(name, value, self.float_dtype, name in self.symmetric)
                if n is None:
                    n = arr.shape[0]
                elif arr.shape[0] != n:
                    raise ValueError(
                        f"snapshot field '{name}' has {arr.shape[0]} rows, expected {n}")
                arrays[name] = arr
            if self.xdmf and ("x" not in arrays or arrays["x"].shape[1:] != (3,)):
                raise ValueError("snapshot field 'x' of shape (n, 3) is needed for the XDMF "
                                 "sidecar (positions are always stored with 3 components)")
        except ValueError as exc:
            err = exc
        if self.dist.any(err is not None):
            raise err or ValueError("invalid snapshot fields on another rank")
        signature = [(k, a.dtype.str, a.shape[1:]) for k, a in arrays.items()]
        root_sig = self.dist.bcast(signature)
        if self.dist.any(signature != root_sig):
            raise ValueError("snapshot fields differ between ranks (names, order, dtypes or "
                             f"trailing shapes); rank 0 has {root_sig}, rank "
                             f"{self.dist.rank} has {signature}")
        return arrays, n

    def write(self, step, time, fields):
        """Write one snapshot (collective). Returns its index."""
        if self._closed:
            raise ValueError("write() on a closed SnapshotWriter")
        arrays, n = self._check_fields(fields)
        counts = self.dist.gather_counts(n)
        offset = int(counts[: self.dist.rank].sum())
        n_total = int(counts.sum())
        name = snapshot_name(self.index)
        meta = {"index": self.index, "time": float(time), "step": int(step),
                "counts": counts, "n_total": n_total, "n_ranks": self.dist.size,
                "layout": self.mode}

        if self.mode == "mpio":
            self._collective(lambda: self._write_mpio(name, meta, arrays, offset, n_total),
                             f"writing snapshot {name}")
        elif self.mode == "serial":
            self._on_root(lambda: self._write_plain(self.path, name, meta, arrays))
        else:
            self._collective(
                lambda: self._write_plain(rank_file(self.path, self.dist.rank), name,
                                          dict(meta, offset=offset), arrays),
                f"writing snapshot {name} to the per-rank file")
            self._on_root(lambda: self._write_virtual(name, meta, arrays))
        self.dist.barrier()
        if self.xdmf:
            self._on_root(lambda: write_xdmf(self.path, self.xdmf_path, cache=self._xdmf_cache))
        self.index += 1
        return self.index - 1

    def _write_mpio(self, name, meta, arrays, offset, n_total):
        with open_h5(self.path, "r+", driver="mpio", comm=self.dist.comm, libver=LIBVER) as f:
            grp = _new_group(f, name)
            for key, value in meta.items():
                grp.attrs[key] = value
            for key, arr in arrays.items():
                dset = grp.create_dataset(key, shape=(n_total,) + arr.shape[1:], dtype=arr.dtype)
                self._mark(dset, key)
                if n_total > 0:  # a dataset of size 0 has no storage to write to (all agree)
                    write_slice(dset, offset, arr, collective=True)
            key = str(n_total)
            if self.xdmf and n_total > 0 and key not in f[TOPOLOGY]:  # same answer on all ranks
                dtype = connectivity_dtype(n_total)
                dset = f[TOPOLOGY].create_dataset(key, shape=(n_total,), dtype=dtype)
                n = len(next(iter(arrays.values())))
                write_slice(dset, offset, np.arange(offset, offset + n, dtype=dtype),
                             collective=True)
            # No f.flush(): with the mpio driver it is an MPI_File_sync, an fsync that waits
            # for the disk (0.03-0.4 s per snapshot measured here); closing writes the
            # metadata without one, so the file is as complete for readers as in the other
            # layouts, whose flush never fsyncs either (nor does a checkpoint).

    def _write_plain(self, path, name, meta, arrays):
        with open_h5(path, "r+", libver=LIBVER) as f:
            grp = _new_group(f, name)
            for key, value in meta.items():
                grp.attrs[key] = value
            for key, arr in arrays.items():
                self._mark(grp.create_dataset(key, data=np.ascontiguousarray(arr)), key)
            if path == self.path:  # the main file of a one-rank run (not a per-rank part)
                self._write_topology(f, meta["n_total"])
            f.flush()

    def _mark(self, dset, key):
        """Name the stored component order of a symmetric tensor (collective in mpio mode:
        every rank marks the same datasets)."""
        if key in self.symmetric:
            dset.attrs["symmetric"] = SYM_ATTR

    def _write_topology(self, f, n_total):
        """Serial writer of the shared Polyvertex connectivity (rank 0 / one rank)."""
        if self.xdmf and n_total > 0 and str(n_total) not in f[TOPOLOGY]:
            f[TOPOLOGY].create_dataset(
                str(n_total), data=np.arange(n_total, dtype=connectivity_dtype(n_total)))

    def _write_virtual(self, name, meta, arrays):
        counts = meta["counts"]
        starts = np.concatenate([[0], np.cumsum(counts)])
        with open_h5(self.path, "r+", libver=LIBVER) as f:
            grp = _new_group(f, name)
            for key, value in meta.items():
                grp.attrs[key] = value
            for key, arr in arrays.items():
                trailing = arr.shape[1:]
                layout = h5py.VirtualLayout(shape=(meta["n_total"],) + trailing, dtype=arr.dtype)
                for r, c in enumerate(counts):
                    if c == 0:
                        continue
                    src = h5py.VirtualSource(
                        os.path.basename(rank_file(self.path, r)), f"/{GROUP}/{name}/{key}",
                        shape=(int(c),) + trailing, dtype=arr.dtype)
                    layout[int(starts[r]):int(starts[r + 1])] = src
                self._mark(grp.create_virtual_dataset(key, layout, fillvalue=0), key)
            self._write_topology(f, meta["n_total"])
            f.flush()

    def flush(self):
        """Nothing is buffered between snapshots (each write closes the file); kept for API."""

    def close(self):
        self._closed = True

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _new_group(f, name):
    """The group of a new snapshot; a leftover of a write that failed half-way is replaced
    (collective in mpio mode: every rank sees the same file)."""
    if name in f[GROUP]:
        del f[GROUP][name]
    return f[GROUP].create_group(name, track_order=True)
