"""Snapshots and the diagnostics file of a `Simulation`: the `Output` methods (opening the
output folder, the fields a snapshot holds and when one is due). The HDF5/XDMF writing is
in `io/snapshots.py`, the CSV in `io/diagnostics.py`; `Simulation` inherits these methods,
which use its state (case, particles, dist, timers, time and step)."""
import os

import numpy as np

from .derived_fields import DERIVED, derived_field
from .diagnostics import DIAG_COLUMNS, DiagnosticsCSV
from .folders import check_output_folder, make_output_folder
from .h5files import code_version
from .snapshots import SnapshotWriter


class Output:
    """Output methods of `Simulation`."""

    def _open_output(self, overwrite):
        def make():  # checked again: files may have appeared while the scene was built
            check_output_folder(self.out_dir, overwrite, self.out_key)
            make_output_folder(self.out_dir, self.out_key)

        self.dist.agree("output files", make, root_only=True)
        h5 = os.path.join(self.out_dir, "particles.h5")
        csv = os.path.join(self.out_dir, "diagnostics.csv")
        self.writer = SnapshotWriter(self.dist, h5, case_text=self.case.text,
                                     attrs={"case_name": self.case.name, "dim": self.dim,
                                            "code_version": code_version()},
                                     overwrite=True, **self._snapshot_format())
        self.diag = DiagnosticsCSV(self.dist, csv, self.diagnostics_columns(), overwrite=True)
        self._open_probes(append=False)

    def _open_probes(self, append):
        """RUN/probes.csv of the `[[probes]]` (io/probes.py), if the case has any: a new
        file, or with `append` the restarted run's continued one."""
        if getattr(self, "probes", None) is None:
            return
        path = os.path.join(self.out_dir, "probes.csv")
        self.probes.open(DiagnosticsCSV(self.dist, path, self.probes.columns,
                                        overwrite=not append, append=append))

    def diagnostics_columns(self):
        """DIAG_COLUMNS, then the reactions of the `[[prescribed]]` constraints if any
        (physics/loads.py PrescribedVelocity)."""
        extra = self.prescribed.columns(self.dim) if self.prescribed is not None else ()
        return DIAG_COLUMNS + extra

    def _snapshot_format(self):
        """Stored float type of this run's snapshots (io/snapshots.py). sigma keeps its full
        3x3 form (12 bytes more per particle in float32 than its 6 components): ParaView's
        XDMF3 reader does not expand a Tensor6 and would label its 6 raw components in
        VTK's order (xx, yy, zz, xy, yz, xz), not XDMF's (xx, xy, xz, yy, yz, zz)."""
        return {"precision": self.case.output.precision}

    def snapshot_fields(self):
        """The case's output fields, plus gid and x if it leaves them out: a snapshot is
        matched to another by gid (rows follow the ranks, io/xdmf.py) and drawn at x."""
        p = self.particles
        n = p.n_owned
        out = {}
        fields = self.case.output.fields
        for name in fields + tuple(k for k in ("gid", "x") if k not in fields):
            if name not in p and name in DERIVED:
                out[name] = derived_field(name, p, n, self.case)
            elif name in p:
                arr = p[name][:n]
                if name in ("x", "v") and self.dim < 3:  # XDMF geometry wants 3 components
                    full = np.zeros((n, 3))
                    full[:, : self.dim] = arr
                    arr = full
                out[name] = arr
        return out

    def write_snapshot(self):
        if self.writer is None:
            return
        with self.timers.phase("output"):
            self.writer.write(self.step_count, self.time, self.snapshot_fields())
        self._last_snapshot_step = self.step_count

    def _scheduled_snapshot(self):
        o = self.case.output
        if o.every_steps is not None:
            return self.step_count % o.every_steps == 0
        if o.every is not None:
            return self.time >= self._next_snapshot_time - 1e-12 * o.every
        return False

    def _after_snapshot(self):
        o = self.case.output
        if o.every is not None:
            while self._next_snapshot_time <= self.time + 1e-12 * o.every:
                self._next_snapshot_time += o.every
