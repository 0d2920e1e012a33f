"""Checkpoints and restarts of a `Simulation` (DESIGN.md §6): the `Restart` methods.

Writing the whole state (every migrating particle field, time, step, dt, slab faces, the
snapshot schedule and the case), the checkpoints at a failure and on a stop signal, and the
restart on any number of ranks with the output files continued. The file format and the
parallel reads and writes are in `io/checkpoint.py`; this is the part that knows the
simulation's state. `Simulation` inherits it.
"""
import json
import logging
import os

import numpy as np

from ..errors import ConfigError, RunStopped
from .checkpoint import read_header, read_rows, signal_name, write_checkpoint
from .diagnostics import DiagnosticsCSV, truncate_rows
from .h5files import code_version
from .snapshots import SnapshotWriter

log = logging.getLogger("pmpmsph")

class Restart:
    """Checkpoint and restart methods of `Simulation` (they use its state: particles,
    decomposition, dist, timers, case, output writers)."""

    def checkpoint_path(self, name="checkpoint.h5"):
        """Where checkpoints go: the output folder (None when the run writes no output)."""
        if self.out_dir is None or self.writer is None:
            return None
        return os.path.join(self.out_dir, name)

    def write_checkpoint(self, path=None, failed=None):
        """Write the whole state (collective): every migrating particle field (owned rows),
        time, step, dt, slab faces, next snapshot time and the case. Returns the path, or
        None when there is nowhere to write (no output folder and no `path`)."""
        path = path or self.checkpoint_path()
        if path is None:
            return None
        p = self.particles
        dec = self.decomposition
        attrs = {"case": self.case.text, "case_name": self.case.name,
                 "case_overrides": json.dumps([list(kv) for kv in self.case_overrides],
                                              default=str),
                 "case_dir": self.case_dir or "", "dim": self.dim, "time": float(self.time),
                 "step": int(self.step_count), "dt": float(self.dt),
                 "next_snapshot_time": float(self._next_snapshot_time),
                 "axis": dec.axis if dec is not None else -1,
                 "faces": (np.asarray(dec.faces, np.int64) if dec is not None
                           else np.zeros(0, np.int64))}
        if failed is not None:
            attrs["failed"] = str(failed)
        with self.timers.phase("checkpoint"):
            write_checkpoint(self.dist, path, {k: p[k] for k in p.fields(migrate=True)}, attrs)
        if failed is None:
            self._last_checkpoint_step = self.step_count
        return path

    def _failure_checkpoint(self, exc):
        """State at a RunError into checkpoint_failed.h5 (the last good checkpoint.h5 is kept:
        the failed state is half a step and not a restart point)."""
        path = self.checkpoint_path("checkpoint_failed.h5")
        if path is None:
            return
        try:
            self.write_checkpoint(path, failed=exc)
            log.error("state at the failure written to %s", path)
        except Exception as err:  # noqa: BLE001 - the RunError is what the user must see
            log.error("could not write %s: %s", path, err)

    def _stop_on_signal(self, signum):
        """A signal asked to stop: snapshot + checkpoint of this step, close, RunStopped."""
        if self.writer is not None and self._last_snapshot_step != self.step_count:
            self.write_snapshot()
        path = self.write_checkpoint() if self._last_checkpoint_step != self.step_count \
            else self.checkpoint_path()
        self.close()
        raise RunStopped(signal_name(signum), self.step_count, self.time, path)

    def restore_checkpoint(self, path):
        """Continue from a checkpoint (collective), on any number of ranks: every rank reads
        the rows it owns under this run's decomposition and restores every field, then time,
        step, dt and the snapshot schedule. With the checkpoint's rank count its slab faces
        are taken over; otherwise the load balancer (if any) balances the restored particles.
        A checkpoint that does not fit this case is a ConfigError on '--restart'."""
        head = self._agree("--restart", lambda: read_header(path), root_only=True)
        p = self.particles
        names = p.fields(migrate=True)
        if head["dim"] != self.dim:
            raise ConfigError("--restart", f"checkpoint is {head['dim']}D, the case "
                              f"{self.dim}D")
        if sorted(head["fields"]) != sorted(names):
            raise ConfigError("--restart", f"checkpoint fields {sorted(head['fields'])} "
                              f"differ from this case's {sorted(names)}")
        for k in names:
            trailing, dtype = head["field_specs"][k]
            want = p.arrays[k].shape[1:]
            if tuple(trailing) != tuple(want) or np.dtype(dtype) != p.arrays[k].dtype:
                raise ConfigError("--restart", f"checkpoint field {k!r} is {dtype} "
                                  f"{tuple(trailing)}, this case has {p.arrays[k].dtype} {want}")
        dec = self.decomposition
        n_total = int(head["n_total"])
        faces = np.asarray(head["faces"], np.int64)
        same_slabs = (dec is not None and len(faces) == self.dist.size + 1
                      and head["axis"] == dec.axis and faces[-1] == dec.ncells)
        if same_slabs:
            # the checkpoint's slabs and each rank's own rows in their order: a particle not
            # yet migrated (MigrationSchedule) stays where it was, so the run goes on bit for
            # bit as if never interrupted
            if not np.array_equal(faces, dec.faces):
                self._apply_faces(faces)
                dec = self.decomposition
            counts = np.asarray(head["counts"], np.int64)
            lo = int(counts[: self.dist.rank].sum())
            kw = {"rows": (lo, lo + int(counts[self.dist.rank]))}
        elif dec is not None:
            kw = {"keep": dec.keep}
        else:  # no slabs: rank r takes an equal share of the rows
            r, size = self.dist.rank, self.dist.size
            kw = {"rows": (n_total * r // size, n_total * (r + 1) // size)}
        rows = self._agree("--restart", lambda: read_rows(path, names, **kw))
        for key, count in (("mat", len(self.case.materials)), ("body", len(self.case.bodies))):
            top = int(self.dist.max(int(rows[key].max()) if len(rows[key]) else -1))
            if top >= count:  # the kernels index tables with these: never out of range
                raise ConfigError("--restart", f"checkpoint particles refer to {key} {top}, "
                                  f"this case has {count}")
        p.drop_halo()
        p.n_owned = p.n_total = 0
        p.append(rows)
        got = int(self.dist.sum(p.n_owned))
        if got != n_total:
            raise ConfigError("--restart", f"restored {got} of the checkpoint's {n_total} "
                              "particles")
        if not same_slabs and self.balancer is not None:
            self.rebalance()
        self.time = float(head["time"])
        self.step_count = int(head["step"])
        # A fixed dt comes from the case (so --set time.dt can change it; the stored one may
        # be the last step's, cut short to end exactly at time.end); a CFL dt is the stored
        # one: a checkpoint is written after a step, whose end chose the next dt from state
        # a restart cannot recompute exactly (the SPH rates of the last evaluation, the MPM
        # signal speed of the last G2P)
        if self.sph is not None:
            self.sph.resume()
        if self.case.time.dt is not None:
            self.dt = self.case.time.dt
        else:
            self.dt = float(head["dt"])
        self._next_snapshot_time = float(head["next_snapshot_time"])
        self._last_snapshot_step = -1
        self._last_checkpoint_step = self.step_count
        log.info("restarted from %s: step %d, t = %.6g, %d particles on %d rank(s) "
                 "(written on %d)", path, self.step_count, self.time, n_total, self.dist.size,
                 head["n_ranks"])
        return head

    def _agree(self, key, fn, root_only=False):
        """fn() agreed on by every rank (`Distributor.agree`, place "restart"), any failure
        of it bad input at `key` (a file that cannot be read or changed)."""
        def guarded():
            try:
                return fn()
            except ConfigError:
                raise
            except Exception as exc:  # noqa: BLE001 - reported as bad input at `key`
                raise ConfigError(key, f"cannot use {key} file: {exc}") from None

        return self.dist.agree("restart", guarded, root_only=root_only)

    def open_restart_output(self, out_dir, overwrite=False):
        """Output of a restarted run (after `restore_checkpoint`): continue particles.h5 and
        diagnostics.csv in `out_dir` if present (snapshots after the restart step and rows
        from it on are dropped first), start new files otherwise (or with `overwrite`)."""
        self.out_dir = out_dir
        h5 = os.path.join(out_dir, "particles.h5")
        csv = os.path.join(out_dir, "diagnostics.csv")
        exists = self.dist.bcast(os.path.exists(h5) or os.path.exists(csv))
        if overwrite or not exists:
            self._open_output(overwrite=True)
            return False
        self.writer = SnapshotWriter(self.dist, h5, case_text=self.case.text,
                                     attrs={"case_name": self.case.name, "dim": self.dim,
                                            "code_version": code_version()},
                                     append=True, after_step=self.step_count,
                                     **self._snapshot_format())
        if self.writer.appending:  # no second snapshot of the restart step
            self._last_snapshot_step = self.step_count
        self._agree("--out", lambda: truncate_rows(csv, "step", self.step_count),
                    root_only=True)
        self.diag = DiagnosticsCSV(self.dist, csv, self.diagnostics_columns(), append=True)
        if getattr(self, "probes", None) is not None:  # rows up to this step stay
            probes = os.path.join(out_dir, "probes.csv")
            self._agree("--out", lambda: truncate_rows(probes, "step", self.step_count + 1),
                        root_only=True)
            self._open_probes(append=True)
            self.probes.resumed_at(self.step_count)
        return True
