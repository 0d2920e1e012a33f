"""Diagnostics table of a run as CSV (time, dt, energies, momentum, mass, timings, ...).

Rank 0 writes; the values passed to :meth:`DiagnosticsCSV.append` are already global (the
caller reduces them), so ``append`` needs no communication and every rank may call it. Each
line is flushed, so the table can be plotted while the run goes on and survives a crash.
Floats are written with the shortest repr that reads back to the same double.
"""
import csv
import math
import os

import numpy as np

#: columns of diagnostics.csv
DIAG_COLUMNS = ("time", "step", "dt", "kinetic", "strain", "potential", "total",
                "px", "py", "pz", "mass")


def _format(value):
    if value is None:
        return "nan"
    if isinstance(value, (bool, np.bool_)):
        return str(int(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, str):
        return value
    arr = np.asarray(value)
    if arr.ndim == 0:
        return _format(arr.item())
    raise ValueError(f"diagnostics value {value!r} is not a number")


class DiagnosticsCSV:
    """CSV table with a fixed set of columns, written by rank 0.

    Refuses to replace an existing file unless ``overwrite``; with ``append`` an existing file
    with the same header is continued (a restarted run).
    """

    def __init__(self, dist, path, columns, overwrite=False, append=False):
        self.dist = dist
        self.path = os.path.abspath(os.fspath(dist.bcast(os.fspath(path))))
        self.columns = list(columns)
        if not self.columns or len(set(self.columns)) != len(self.columns):
            raise ValueError(f"diagnostics columns must be unique and non-empty: {self.columns}")
        self._fh = None
        self._writer = None

        decision = None
        if dist.is_root:
            exists = os.path.exists(self.path)
            if exists and append:
                decision = "append" if _read_header(self.path) == self.columns else "mismatch"
            elif exists and not overwrite:
                decision = "exists"
            else:
                decision = "new"
        decision = dist.bcast(decision)
        if decision == "exists":
            raise FileExistsError(
                f"diagnostics file {self.path} already exists (allow overwriting to replace it)")
        if decision == "mismatch":
            raise ValueError(f"cannot append to {self.path}: its columns differ from "
                             f"{self.columns}")

        err = None
        if dist.is_root:
            try:
                os.makedirs(os.path.dirname(self.path), exist_ok=True)
                self._fh = open(self.path, "a" if decision == "append" else "w", newline="")
                self._writer = csv.writer(self._fh, lineterminator="\n")
                if decision == "new":
                    self._writer.writerow(self.columns)
                    self._fh.flush()
            except OSError as exc:
                err = exc
        msg = dist.bcast(None if err is None else str(err))
        if err is not None:
            raise err
        if msg is not None:
            raise OSError(f"rank 0 could not open the diagnostics file: {msg}")

    def append(self, row):
        """Add one row (dict column -> number). Missing columns are written as nan."""
        unknown = [k for k in row if k not in self.columns]
        if unknown:
            raise KeyError(f"unknown diagnostics column(s) {unknown}; columns are {self.columns}")
        if self._writer is None:
            return
        self._writer.writerow([_format(row.get(c)) for c in self.columns])
        self._fh.flush()

    def close(self):
        if self._fh is not None:
            self._fh.close()
            self._fh = None
            self._writer = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _read_header(path):
    with open(path, newline="") as fh:
        for row in csv.reader(fh):
            return row
    return None


def _column_array(values):
    try:
        return np.array([int(v) for v in values], dtype=np.int64)
    except ValueError:
        pass
    try:
        return np.array([float(v) if v != "" else math.nan for v in values], dtype=np.float64)
    except ValueError:
        return np.array(values, dtype=str)


def read_diagnostics(path):
    """The table as {column: numpy array}: int64 where every value is an integer, else float64."""
    with open(os.fspath(path), newline="") as fh:
        rows = list(csv.reader(fh))
    if not rows:
        raise ValueError(f"{path} is empty (no header)")
    header, body = rows[0], [r for r in rows[1:] if r]
    if any(len(r) != len(header) for r in body):
        # A crash can cut the last line short: keep the complete rows.
        body = [r for r in body if len(r) == len(header)]
    return {name: _column_array([r[i] for r in body]) for i, name in enumerate(header)}


def truncate_rows(path, column, first_dropped):
    """Drop the rows whose `column` is >= `first_dropped` (a restarted run rewrites them);
    the file is replaced atomically. Nothing happens if the file or column is absent.
    Returns the number of rows dropped."""
    path = os.fspath(path)
    if not os.path.exists(path):
        return 0
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    if not rows or column not in rows[0]:
        return 0
    i = rows[0].index(column)
    keep = [rows[0]]
    for r in rows[1:]:
        try:
            if len(r) == len(rows[0]) and float(r[i]) < first_dropped:
                keep.append(r)
        except ValueError:
            continue
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", newline="") as fh:
        csv.writer(fh, lineterminator="\n").writerows(keep)
    os.replace(tmp, path)
    return len(rows) - len(keep)
