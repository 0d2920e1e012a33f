"""Simulation: owns particles, grid stages, decomposition and writers (DESIGN.md §1, §3).

`step()` runs the fixed stage order of DESIGN.md §3 (only the stages the scene needs exist);
`run()` loops, schedules output and diagnostics, and turns a failing particle into a
`RunError` decided collectively on all ranks.
"""
from __future__ import annotations

import logging
import math
import os
import time
from typing import Any, Callable, Optional

import numpy as np

from .config.case import Case, GridSpec
from .initial_particles import build_particles, material_arrays, sph_stage_class
from .errors import RunError
from .io.checkpoint import STOP
from .io.folders import check_output_folder
from .io.output import Output
from .io.probes import Probes
from .io.restart import Restart
from .kernels.deformation import jacobian
from .kernels.diagnostics import particle_sums
from .materials.dispatch import material_tag
from .parallel.decomposition import Decomposition, default_axis
from .parallel.distributor import Distributor
from .parallel.balance import LoadBalancer
from .parallel.rebalancing import Rebalancing
from .parallel.migration import MigrationSchedule, migrate, plan_migration
from .physics.coupling import interface_for
from .physics.hydrostatic import hydrostatic_mpm
from .physics.damping import DampingZones
from .physics.loads import PrescribedVelocity, TractionLoads
from .physics.mpm.stage import MPMStage
from .time_step import TimeStepControl
from .timing import Timers
from .warmup import compile_kernels

log = logging.getLogger("pmpmsph")

#: steps between re-sorting particles by grid cell (memory locality of P2G/G2P)
SORT_EVERY = 100
#: below this many particles per rank everything is in cache and sorting buys nothing
SORT_MIN_PARTICLES = 20_000


def _hms(seconds):
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


class Simulation(Output, Restart, Rebalancing, TimeStepControl):
    def __init__(self, case: Case, dist: Optional[Distributor] = None,
                 out_dir: Optional[str] = None, overwrite: bool = False,
                 write_output: bool = True, out_key: str = "--out",
                 max_steps: Optional[int] = None, check_steps: bool = False) -> None:
        """`out_key` names the setting that chose `out_dir` in messages about it. With
        `check_steps` (the command line) a case needing more than time.max_steps steps is
        refused unless `max_steps` (--max-steps) bounds the run (`check_step_count`); a
        Python caller that steps by itself is not checked."""
        t0 = time.perf_counter()
        self.case = case
        self.dist = dist or Distributor()
        self.timers = Timers()
        self.time = 0.0
        self.step_count = 0
        self.dim = case.dim
        self.out_dir = out_dir
        self.out_key = out_key
        if write_output and out_dir is not None:  # before the work of building, and agreed
            self.dist.agree("output location", lambda: check_output_folder(
                out_dir, overwrite, out_key), root_only=True)
        # seeding and the stages are local work on every rank: agreed on before any collective
        self.dist.agree("build", lambda: self._build(case))
        self.migrated = 0
        # lazy migration lets a particle stay a while on the rank it left, within the reach
        # of every stage (MPM: a cell of ghost nodes; SPH: the halo's margin); across the
        # wrap of a periodic slab axis its position wraps at once (in the MPM grid or the SPH
        # stage), to the far end of the domain: beyond its rank's ghosts and halo
        wraps = self.decomposition is not None and self.decomposition.period is not None
        reach = min(s.stray_reach for s in (self.mpm, self.sph) if s is not None)
        self.migration = MigrationSchedule(self.dist, lazy=not wraps, reach=reach)
        self.loads = TractionLoads(case.loads, self.particles) if case.loads else None
        self.prescribed = (PrescribedVelocity(case.prescribed, self.particles)
                           if case.prescribed else None)
        if self.prescribed is not None and self.sph is not None:
            self.sph.set_constraint(self.prescribed)  # held within the SPH stages' steps
        self.damping = (DampingZones(case.damping, case, self.particles)
                        if case.damping else None)
        # [[probes]] (io/probes.py): RUN/probes.csv; None when the case has none
        self.probes = (Probes(case, self.particles, self.dist, self.prescribed, self.timers)
                       if case.probes else None)
        self._sums = np.zeros(7)
        # the energy of one material type is called directly, not through the type switch;
        # from the case's bodies (not this rank's particles, which migrate), as in MPMStage
        used = sorted({list(case.materials).index(b.material) for b in case.bodies})
        self._mtag = material_tag(self.materials[0][used])
        compile_kernels(self)
        if self.balancer is not None:  # seeding used equal slabs: balance before step 1
            with self.timers.phase("balance"):
                self.rebalance()
        # the hydrostatic initial condition (collective): [sph] hydrostatic starts the SPH
        # fluids and, in a coupled scene, the MPM ones too; [mpm] hydrostatic the MPM ones
        sph_start = self.sph is not None and case.sph.hydrostatic
        if sph_start:
            self.sph.hydrostatic_start()
        if self.mpm is not None and (sph_start or case.mpm.hydrostatic):
            hydrostatic_mpm(case, self.particles, self.materials, case.gravity, self.dist)
        self.h = min(min(case.grid.cell_size) if case.grid else np.inf,
                     case.sph.h if case.sph else np.inf)
        self.dt = self._initial_dt()
        self.first_dt = self.dt  # for the collapse check (time_step.py); kept on restart
        if check_steps:
            self.check_step_count(max_steps)
        self.writer = self.diag = None
        self._last_snapshot_step = -1
        fault = os.environ.get("PMPMSPH_INJECT_FAULT")  # "rank:step", for the fault tests
        self._fault = tuple(int(v) for v in fault.split(":")) if fault else None
        nan = os.environ.get("PMPMSPH_INJECT_NAN")  # "rank:step": a NaN velocity there
        self._nan = tuple(int(v) for v in nan.split(":")) if nan else None
        self._next_snapshot_time = 0.0
        if write_output and out_dir is not None:
            self._open_output(overwrite)
        self.timers.add("setup", time.perf_counter() - t0 - self.timers.total["jit_warmup"])

    def _build(self, case):
        """Slabs, this rank's particles and the stages the scene needs (no collective)."""
        self.decomposition = self._decompose(case)
        self.balancer = (LoadBalancer(case.parallel.balance_every,
                                      case.parallel.balance_threshold)
                         if self.decomposition is not None and self.dist.size > 1
                         and case.parallel.balance_every > 0 else None)
        self.particles = build_particles(
            case, keep=self.decomposition.keep if self.decomposition else None)
        self.materials = material_arrays(case)
        self.gravity = np.zeros(3)
        self.gravity[: self.dim] = case.gravity
        self.mpm = (MPMStage(case, self.particles, self.materials, self.decomposition,
                             self.timers) if case.has_mpm else None)
        self.sph = (sph_stage_class(case)(case, self.particles, self.materials,
                                          self.decomposition, self.dist, self.timers)
                    if case.has_sph else None)
        # the coupling's hooks in the step (`Uncoupled`: none; physics/coupling.py)
        self.coupling = interface_for(case, self.particles, self.mpm, self.sph, self.timers)
        if self.mpm is not None:
            self.mpm.attach(self.coupling)

    def _decompose(self, case):
        """Slabs of the grid; a pure-SPH scene cuts its [domain] box on a lattice of cells of
        the kernel support 2h instead (slab faces only, no grid is allocated)."""
        spec = case.grid
        if spec is None and case.has_sph:
            lo, hi = np.array(case.domain[0]), np.array(case.domain[1])
            cells = np.maximum(np.floor((hi - lo) / (2.0 * case.sph.h)), 1).astype(int)
            spec = GridSpec(tuple(lo), tuple((hi - lo) / cells), tuple(int(c) for c in cells))
        if spec is None:
            return None
        axis = case.parallel.axis
        periodic = case.periodic or (case.grid.periodic if case.grid else ())
        if periodic and axis is None:  # cut across a period if there is a free axis
            free = [a for a in range(case.dim) if a not in periodic] or list(range(case.dim))
            axis = max(free, key=lambda a: spec.cells[a])
        axis = default_axis(spec.cells) if axis is None else axis
        period = None
        if axis in periodic:  # the first and last slabs are neighbours
            period = spec.cells[axis] * spec.cell_size[axis] if case.grid else (
                case.domain[1][axis] - case.domain[0][axis])
        return Decomposition(self.dist, spec, axis=axis,
                             key="grid.cells" if case.grid else "domain", period=period)

    def diagnostics(self) -> dict[str, float]:
        """Global sums as a dict (every rank gets the same numbers)."""
        p = self.particles
        n = p.n_owned
        mtypes, mparams = self.materials
        mstate = p["mstate"][:n] if "mstate" in p else np.zeros((n, 0))
        particle_sums(self.dim, p["x"][:n], p["v"][:n], p["mass"][:n], p["vol0"][:n],
                      p.deformation(n), p["mat"][:n], mtypes, mparams, mstate, self.gravity,
                      self._sums, self._mtag)
        sums = self._sums.copy()
        if self.prescribed is not None:  # the reactions travel in the same collective
            sums = np.concatenate([sums, self.prescribed.local_impulse()])
        s = self.dist.sum(sums)
        k, u, pot = s[0], s[1], s[2]
        row = {"time": self.time, "step": self.step_count, "dt": self.dt, "kinetic": k,
               "strain": u, "potential": pot, "total": k + u + pot, "px": s[3], "py": s[4],
               "pz": s[5], "mass": s[6]}
        if self.prescribed is not None:
            row.update(self.prescribed.reaction_row(s[len(self._sums):], self.dim))
        return row

    # -- the step ----------------------------------------------------------------------------
    def step(self) -> None:
        """One time step in the fixed order of DESIGN.md §3 (stages the scene lacks are absent)."""
        if self._fault is not None and self._fault == (self.dist.rank, self.step_count):
            raise RuntimeError(f"fault injected on rank {self.dist.rank} at step "
                               f"{self.step_count} (PMPMSPH_INJECT_FAULT)")
        if (self._nan is not None and self._nan == (self.dist.rank, self.step_count)
                and self.particles.n_owned):
            self.particles["v"][0] = np.nan  # the fault tests' NaN, caught by the step checks
        x_before = None
        if self.prescribed is not None:
            self.prescribed.apply(self.time)
            x_before = self.prescribed.positions()
        if self.loads is not None:
            self.loads.update(self.time)
        bad = -1
        self.coupling.prepare()
        self.coupling.before_mpm(self.dt)
        fused = None  # this rank's CFL signal speed from G2P, when valid for the new state
        if self.mpm is not None:
            bad = self.mpm.step(self.dt, self.time)
            if (self.mpm.signal is not None and self.sph is None
                    and self.prescribed is None):
                fused = self.mpm.signal
        self.coupling.after_mpm()
        if self.sph is not None:
            bad_sph = self.coupling.sph_step(self.sph, self.dt, self.time)
            bad = bad if bad >= 0 else bad_sph
            self.particles.drop_halo()
        self.coupling.after_sph(self.dt)
        if self.prescribed is not None:
            self.prescribed.apply(self.time, self.dt, x_before)
        if self.damping is not None:
            self.damping.apply(self.dt)
        dec = self.decomposition
        # a scene that migrates every step plans it before the step's allreduce, which then
        # carries the flag of a particle skipping a slab too (one collective fewer)
        plan, far = None, None
        if self.migration.every_step:
            far = False
            if bad < 0:
                with self.timers.phase("migration"):
                    if dec.wraps:  # into the period, then to the owner across the wrap
                        dec.wrap(self.particles["x"][: self.particles.n_owned])
                    plan = plan_migration(dec, self.particles)
                far = len(plan[2]) > 0
        # a CFL time step's global numbers ride on the step's allreduce too: the max signal
        # speed and the SPH stage's limit of the new state (migration and balancing, which
        # come between, only move particles between ranks: the global values stay)
        signal, sph_limit = None, None
        if self.case.time.cfl is not None:
            signal, sph_limit = 0.0, (math.inf if self.sph is not None else None)
            if bad < 0:
                signal = fused if fused is not None else self._local_signal_speed()
                if self.sph is not None:
                    sph_limit = self.sph.local_stable_dt()
        failed, speed, stray, signal, far, sph_limit = self._step_check(bad >= 0, signal,
                                                                        far, sph_limit)
        if signal is not None:
            self._fused_signal = (self.step_count + 1, signal)
        if sph_limit is not None:
            self._fused_sph_limit = (self.step_count + 1, sph_limit)
        if failed:
            self._fail(bad)
        due = self.migration.due(speed, stray, self.dt)
        self.time += self.dt
        self.step_count += 1
        if due and dec is not None:
            if dec.wraps and plan is None:
                dec.wrap(self.particles["x"][: self.particles.n_owned])
            with self.timers.phase("migration"):
                sent, received = migrate(dec, self.particles, self.step_count, plan=plan,
                                         far_anywhere=far)
                self.migrated += sent
            if self.sph is not None and (sent or received):
                self.sph.invalidate()
        if (self.mpm is not None and not self.coupling.keeps_row_order
                and self.step_count % SORT_EVERY == 0
                and self.particles.n_owned >= SORT_MIN_PARTICLES):
            with self.timers.phase("sort"):
                self.mpm.sort_by_cell()
        if self.balancer is not None and self.step_count % self.balancer.every == 0:
            with self.timers.phase("balance"):
                self.rebalance()
        self._update_dt()

    def _step_check(self, failed, signal, far=None, sph_limit=None):
        """The step's one collective: (failure on any rank, global max |v| along the slab
        axis and farthest stray past a slab face for `MigrationSchedule.due` or None, global
        CFL signal speed or None when `signal` is None, a particle about to skip a slab on
        any rank or None when `far` is None, the global minimum of `sph_limit` or None).
        Every rank passes the same Nones. A NaN signal counts as infinite, so no rank ever
        gets a finite time step from a broken state."""
        speed, stray = self.migration.local_state(self.particles, self.decomposition)
        # every entry as a maximum: a minimum as the max of its negative, flags as 0 / 1
        entries = {"failed": float(failed), "far": None if far is None else float(far),
                   "speed": speed, "stray": stray,
                   "sph_limit": None if sph_limit is None else -sph_limit,
                   "signal": None if signal is None else
                   (signal if signal == signal else math.inf)}
        present = [k for k, value in entries.items() if value is not None]
        out = dict(zip(present, self.dist.max_array([entries[k] for k in present])))
        return (out["failed"] > 0.0, out.get("speed"), out.get("stray"), out.get("signal"),
                out["far"] > 0.0 if "far" in out else None,
                -out["sph_limit"] if "sph_limit" in out else None)

    def _fail(self, bad):
        p = self.particles
        gid, cause = -1, "failure on another rank"
        if bad >= 0:
            gid = int(p["gid"][bad])
            x = p["x"][bad]
            J = float(jacobian(p.deformation(), bad))
            if not np.all(np.isfinite(x)) or not np.isfinite(J):
                cause = "NaN in position or deformation gradient"
            elif not J > 0:
                cause = f"det F = {J:.3g} <= 0 (inverted material)"
            elif self.mpm is not None and (domain := self.mpm.domain_failure(bad)):
                cause = domain
            else:
                where = "grid" if self.case.grid else "domain"
                cause = f"left the {where} at x = {np.round(x, 6).tolist()}"
        if self.dist.size > 1:  # every rank reports the same failure (printed once, by rank 0)
            found = [f for f in self.dist.allgather((gid, cause)) if f[0] >= 0]
            gid, cause = found[0] if found else (gid, cause)
        raise RunError(self.step_count + 1, gid, cause)

    # -- the loop ------------------------------------------------------------------------------
    def run(self, max_steps: Optional[int] = None, progress_every: Optional[float] = None,
            on_step: Optional[Callable[[Simulation], Any]] = None) -> dict[str, Any]:
        """Advance to case.time.end (or max_steps); returns a summary dict."""
        end = self.case.time.end
        n_global = int(self.dist.sum(self.particles.n_owned))
        diag_every = self.case.output.diagnostics_interval(n_global)
        ck_every = self.case.output.checkpoint_every
        if self._last_snapshot_step != self.step_count:
            self.write_snapshot()
            self._after_snapshot() if self.writer else None
        if self.diag:
            self.diag.append(self.diagnostics())
        if self.probes is not None:
            self.probes.start(self.time, self.step_count)
        t_start = time.perf_counter()
        steps0 = self.step_count
        t0_sim = self.time
        try:
            while self.time < end - 1e-6 * self.dt:
                if max_steps is not None and self.step_count - steps0 >= max_steps:
                    break
                if self.time + self.dt > end:
                    self.dt = end - self.time
                self.step()
                if self.diag and self.step_count % diag_every == 0:
                    self.diag.append(self.diagnostics())
                if self.probes is not None and self.probes.due(self.time, self.step_count):
                    self.probes.write(self.time, self.step_count)
                if self.writer and self._scheduled_snapshot():
                    self.write_snapshot()
                    self._after_snapshot()
                if ck_every and self.step_count % ck_every == 0:
                    self.write_checkpoint()
                if on_step is not None:
                    on_step(self)
                if progress_every and self.dist.is_root and self.step_count % progress_every == 0:
                    el = time.perf_counter() - t_start
                    done = self.step_count - steps0
                    rate = n_global * done / max(el, 1e-9)
                    eta = el / max(self.time - t0_sim, 1e-300) * (end - self.time)
                    if max_steps is not None:
                        eta = min(eta, el / done * (max_steps - done))
                    log.info("t=%.6g step=%d dt=%.3g %.3g particle-steps/s ETA %s", self.time,
                             self.step_count, self.dt, rate, _hms(eta))
                if STOP.installed:  # a signal on any rank: all stop after this step
                    signum = self.dist.max(STOP.signum)
                    if signum:
                        self._stop_on_signal(signum)
        except RunError as exc:
            self.write_snapshot()
            self._failure_checkpoint(exc)
            self.close()
            raise
        if self.writer and self._last_snapshot_step != self.step_count:
            self.write_snapshot()
        if ck_every and self._last_checkpoint_step != self.step_count:
            self.write_checkpoint()
        if self.diag and self.step_count % diag_every != 0:
            self.diag.append(self.diagnostics())
        if self.probes is not None and self.probes.written_step != self.step_count:
            self.probes.write(self.time, self.step_count)
        wall = time.perf_counter() - t_start
        self.timers.add("run", wall)
        n_steps = self.step_count - steps0
        return {"steps": n_steps, "time": self.time, "wall": wall,
                "warmup": self.timers.total.get("jit_warmup", 0.0), "particles": n_global,
                "timers": self.timers.as_dict()}

    def close(self) -> None:
        if self.writer is not None:
            self.writer.close()
            self.writer = None
        if self.diag is not None:
            self.diag.close()
            self.diag = None
        if self.probes is not None:
            self.probes.close()

    # -- checkpoints and restart (DESIGN.md §6; file layout in io/checkpoint.py) ------------------
    #: the --set overrides the case was loaded with and the case file's folder (relative mesh
    #: paths): stored in checkpoints so that a restart rebuilds the same case (set by the CLI)
    case_overrides = ()
    case_dir = None
    _last_checkpoint_step = -1
    _fused_signal = (-1, 0.0)  # (step it belongs to, global max (c + |v|), step-reduced)
    _fused_sph_limit = (-1, math.inf)  # (step it belongs to, the SPH stage's global limit)
