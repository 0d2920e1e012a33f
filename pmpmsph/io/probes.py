"""RUN/probes.csv: when the `[[probes]]` are read and where the rows go (docs/probes.md).

A row is due at t = 0, then at every multiple of `[output] probes_every` the run reaches
(the first step at or past it), or, without that key, on the diagnostics schedule (every
step up to 100,000 particles, every 100 above); and at the run's last step. Reading is
collective: each rank's partial sums (io/probe_sampling.py), one allreduce through the
`Distributor`, and rank 0 writes the row (the `DiagnosticsCSV` writer: shortest
round-trip floats, a line flushed per row). A restart keeps the rows up to the restart step
and continues after it, on the same schedule; without a CSV (no output folder) the rows
are kept in `rows`, for scripts.
"""
import math

from ..timing import Timers
from .probe_sampling import ProbeSampler


class Probes:
    def __init__(self, case, particles, dist, prescribed=None, timers=None):
        self.dist = dist
        self.timers = timers if timers is not None else Timers()  # phase "probes"
        self.sampler = ProbeSampler(case, particles, prescribed)
        self.columns = self.sampler.columns
        self.every = case.output.probes_every
        n_global = int(dist.sum(particles.n_owned))
        self.every_steps = case.output.diagnostics_interval(n_global)
        self.csv = None
        self.rows = []            # the rows, when there is no CSV to write them to
        self.written_step = -1    # step of the last row (written or taken as written)

    def open(self, csv):
        """Write the rows to `csv` (an io/diagnostics.py DiagnosticsCSV) from now on."""
        self.csv = csv

    def close(self):
        if self.csv is not None:
            self.csv.close()
            self.csv = None

    def due(self, time, step):
        """Whether a row is due after the step that ended at (time, step)."""
        if self.every is None:
            return step % self.every_steps == 0
        # the first step at or past a multiple of `every` after the last row's time
        last = self._last_time
        return math.floor(time / self.every + 1e-9) > math.floor(last / self.every + 1e-9)

    _last_time = 0.0

    def sample(self, time, step):
        """Read every probe (collective) and return the row; also sets the start of the
        next force interval."""
        with self.timers.phase("probes"):
            sums = self.dist.sum(self.sampler.local())
            self._last_time = time
            return self.sampler.values(sums, time, step)

    def write(self, time, step):
        """Read and record one row (collective)."""
        row = self.sample(time, step)
        self.written_step = step
        if self.csv is not None:
            self.csv.append(row)
        else:
            self.rows.append(row)
        return row

    def start(self, time, step):
        """At the start of `run`: the first row, or after a restart whose file already
        holds the row of this step, a reading that only starts the force intervals."""
        if self.written_step == step:
            self.sample(time, step)
        else:
            self.write(time, step)

    def resumed_at(self, step):
        """A restart continues a file whose rows end at (or before) `step`."""
        self.written_step = step
