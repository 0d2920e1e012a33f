"""The time step of a Simulation (DESIGN.md §3): the CFL limit h / max(c + |v|) and the SPH
limits, the checks of a chosen dt and of the step count before step 1, and the CFL update
after each step. A mixin of `Simulation` (as `Output`, `Restart`, `Rebalancing`): it reads
the simulation's particles, stages, distributor and the limits the step's allreduce fused
(`_fused_signal`, `_fused_sph_limit`: (step, value))."""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from .errors import ConfigError, RunError
from .kernels.diagnostics import max_signal_speed

#: a CFL time step below this fraction of the first one stops the run: the speeds (or wave
#: speeds) grew a thousandfold, which no stable solution does; without the stop a blowing-up
#: run crawls on with an ever smaller dt instead of failing
DT_COLLAPSE = 1e-3


class TimeStepControl:
    def _local_signal_speed(self):
        """This rank's max (c + |v|) over its owned particles (no collective)."""
        p = self.particles
        n = p.n_owned
        if self.mpm is None and self.sph is not None:
            c = self.sph.signal_speed()
            if c is not None:
                return c
        mtypes, mparams = self.materials
        return max_signal_speed(self.dim, p["v"][:n], p.deformation(n), p["mat"][:n], mtypes,
                                mparams, self._mtag)

    def signal_speed(self):
        """Global max (c + |v|): reduced in the step's allreduce when the step computed it
        (from the MPM step's G2P when that saw the final state: pure MPM, no prescribed
        velocities, not USF; else a pass over the particles), else reduced here."""
        if self._fused_signal[0] == self.step_count:  # already the global maximum
            return self._fused_signal[1]
        return self.dist.max(self._local_signal_speed())

    def stable_dt(self) -> float:
        """CFL limit with Courant number 1: h / max(c + |v|) (and the SPH viscous limit)."""
        c = self.signal_speed()
        limit = self.h / c if c > 0 else math.inf
        if self.sph is not None:
            if self._fused_sph_limit[0] == self.step_count:
                limit = min(limit, self._fused_sph_limit[1])
            else:
                limit = min(limit, self.sph.stable_dt())
        return limit

    def _initial_dt(self):
        tspec = self.case.time
        limit = self.stable_dt()  # collective; the check below is local and agreed on

        def check():
            if tspec.dt is not None and tspec.dt > limit:
                raise ConfigError("time.dt", f"{tspec.dt:g} is above the stable limit "
                                  f"{limit:.4g} (= cell size / (wave speed + |v|))")
            return tspec.dt if tspec.dt is not None else tspec.cfl * limit

        return self.dist.agree("time", check)

    def steps_to_end(self) -> float:
        """About how many steps remain to time.end at the current dt."""
        return max(self.case.time.end - self.time, 0.0) / self.dt

    def check_step_count(self, max_steps: Optional[int] = None) -> None:
        """Refuse a run that would take more than time.max_steps steps (a dt typed 1e-15
        would run until killed) unless `max_steps` (--max-steps) bounds it. Collective."""
        tspec = self.case.time

        def check():
            steps = self.steps_to_end()
            if max_steps is None and steps > tspec.max_steps:
                key = "time.dt" if tspec.dt is not None else "time.end"
                how = f"dt = {self.dt:.4g}" + ("" if tspec.dt is not None else " (from cfl)")
                raise ConfigError(key, f"{how} and end = {tspec.end:g} mean about "
                                  f"{steps:.3g} steps, more than time.max_steps = "
                                  f"{tspec.max_steps}: check dt and end, or raise "
                                  "time.max_steps (or bound the run with --max-steps) if you "
                                  "mean it")

        self.dist.agree("time", check)

    def _update_dt(self):
        if self.case.time.cfl is not None:
            limit = self.stable_dt()
            if not math.isfinite(limit) or limit <= 0:
                raise RunError(self.step_count, -1, "no finite time step (NaN velocity/stress)")
            dt = self.case.time.cfl * limit
            if dt < DT_COLLAPSE * self.first_dt:  # the same verdict on every rank
                self._collapsed(dt)
            self.dt = dt

    def _collapsed(self, dt):
        """Stop a run whose CFL step fell below DT_COLLAPSE of the first one, naming the
        fastest particle of all ranks (collective)."""
        p = self.particles
        n = p.n_owned
        speed = np.linalg.norm(p["v"][:n], axis=1) if n else np.zeros(1)
        k = int(np.argmax(speed))
        local = (float(speed[k]), int(p["gid"][k]) if n else -1)
        fastest, gid = max(self.dist.allgather(local))
        raise RunError(self.step_count, gid, f"the time step collapsed to {dt:.3g} s, below "
                       f"{DT_COLLAPSE:g} of the first ({self.first_dt:.3g} s): the wave or "
                       f"particle speeds grew a thousandfold (particle speeds up to "
                       f"{fastest:.3g} m/s), the solution is blowing up")
