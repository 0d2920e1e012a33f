"""Reading a finished (or running) run back in Python: ``pmpmsph.read(RUN)``.

A run folder holds ``particles.h5`` (snapshots, io/snapshots.py), ``diagnostics.csv``
(io/diagnostics.py) and, when the case has probes, ``probes.csv``. Rows of a snapshot follow
the ranks that wrote it, so the same particle sits at another row after a migration, a
rebalance or a restart on another rank count; every snapshot this module returns is sorted
by the particle's global id ``gid``, so ``run[k]["x"][i]`` is the same particle for every k
whatever wrote the file (one rank, collective MPI-IO or the per-rank layout joined by
virtual datasets; io/snapshot_read.py reads all three).

    run = pmpmsph.read("output/two_disks")
    run.times, run.steps          # one entry per snapshot
    snap = run[-1]                # dict of arrays sorted by gid, plus .time and .step
    snap["sigma"][:, 0, 1]        # the xy stress of every particle
    run.series("x")               # (snapshots, particles, 3) when the count does not change
    run.diagnostics["total"]      # columns of diagnostics.csv as arrays

Snapshots are read when asked for (a long run does not have to fit in memory).
"""
import os

import numpy as np

from .diagnostics import read_diagnostics
from .h5files import GROUP, open_h5
from .snapshot_read import list_snapshots, read_attrs, read_snapshot


class Snapshot(dict):
    """One snapshot's fields (name -> array, rows sorted by gid) with its ``time``,
    ``step`` and ``index`` (position among the run's snapshots)."""

    def __init__(self, fields, time, step, index):
        super().__init__(fields)
        self.time = time
        self.step = step
        self.index = index

    def __repr__(self):
        n = len(self["gid"]) if "gid" in self else len(next(iter(self.values()), ()))
        return (f"Snapshot(index={self.index}, step={self.step}, time={self.time:.6g}, "
                f"{n} particles, fields={list(self)})")


class Run:
    """The results of one run folder; see the module docstring."""

    def __init__(self, path):
        path = os.fspath(path)
        if path.endswith(".h5"):
            self.folder, self.h5 = os.path.dirname(os.path.abspath(path)), path
        else:
            self.folder, self.h5 = path, os.path.join(path, "particles.h5")
        if not os.path.isdir(self.folder):
            raise FileNotFoundError(f"no run folder {self.folder}")
        self._infos = list_snapshots(self.h5) if os.path.exists(self.h5) else []
        self._diagnostics = self._probes = None

    # -- snapshots ---------------------------------------------------------------------
    def __len__(self):
        return len(self._infos)

    @property
    def times(self):
        return np.array([i.time for i in self._infos])

    @property
    def steps(self):
        return np.array([i.step for i in self._infos], dtype=np.int64)

    @property
    def fields(self):
        """The field names of the last snapshot (an empty list before the first)."""
        if not self._infos:
            return []
        with open_h5(self.h5, "r") as f:
            return list(f[GROUP][self._infos[-1].name].keys())

    def __getitem__(self, index):
        """Snapshot `index` (a Python list index: -1 is the last), sorted by gid."""
        if not self._infos:
            raise IndexError(f"{self.h5} holds no snapshots")
        info = self._infos[range(len(self._infos))[index]]
        time, step, data = read_snapshot(self.h5, info.index)
        if "gid" in data:
            order = np.argsort(data["gid"], kind="stable")
            if np.any(order != np.arange(len(order))):
                data = {k: v[order] for k, v in data.items()}
        return Snapshot(data, time, step, info.index)

    def __iter__(self):
        for k in range(len(self._infos)):
            yield self[k]

    def at_step(self, step):
        """The snapshot written at time step `step`."""
        for info in self._infos:
            if info.step == step:
                return self[info.index]
        raise KeyError(f"{self.h5} has no snapshot of step {step}; steps: "
                       f"{', '.join(str(i.step) for i in self._infos) or 'none'}")

    def at_time(self, time):
        """The snapshot written closest to `time`."""
        if not self._infos:
            raise IndexError(f"{self.h5} holds no snapshots")
        return self[int(np.argmin(np.abs(self.times - time)))]

    def series(self, field):
        """One field over every snapshot, stacked: (snapshots, particles, ...) sorted by gid.
        Needs the same particles in every snapshot (no body added or removed)."""
        arrays = [self._read_field(k, field) for k in range(len(self._infos))]
        if len({a.shape for a in arrays}) > 1:
            raise ValueError(f"{field!r} changes shape between snapshots (particle count "
                             f"{sorted({len(a) for a in arrays})}): index the run instead")
        return np.stack(arrays) if arrays else np.empty((0,))

    def _read_field(self, k, field):
        names = [field] if field == "gid" else [field, "gid"]
        _, _, data = read_snapshot(self.h5, self._infos[k].index, fields=names)
        if "gid" in data and field != "gid":
            return data[field][np.argsort(data["gid"], kind="stable")]
        return np.sort(data[field]) if field == "gid" else data[field]

    # -- the rest of the folder ------------------------------------------------------------
    @property
    def attrs(self):
        """The run file's root attributes: case text, code version, ranks, layout."""
        return read_attrs(self.h5)

    @property
    def case_text(self):
        return self.attrs.get("case", "")

    @property
    def diagnostics(self):
        """diagnostics.csv as {column: array}."""
        if self._diagnostics is None:
            self._diagnostics = read_diagnostics(os.path.join(self.folder, "diagnostics.csv"))
        return self._diagnostics

    @property
    def probes(self):
        """probes.csv as {column: array} (empty when the case had no probes)."""
        if self._probes is None:
            path = os.path.join(self.folder, "probes.csv")
            self._probes = read_diagnostics(path) if os.path.exists(path) else {}
        return self._probes

    def __repr__(self):
        span = (f", t = {self._infos[0].time:.4g} .. {self._infos[-1].time:.4g}"
                if self._infos else "")
        return f"Run({self.folder!r}, {len(self)} snapshots{span})"


def read(run):
    """The results of a run folder (or its particles.h5) as a :class:`Run`."""
    return Run(run)
