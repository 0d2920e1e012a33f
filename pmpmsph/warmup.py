"""The JIT warm-up of a `Simulation`: every kernel its scene uses compiled (or loaded from
the on-disk cache) before step 1, and reported apart from the run (Dedalus style)."""
import time

import numpy as np

from .kernels.diagnostics import max_signal_speed, particle_sums
from .kernels.partition import cell_keys, slab_leavers


def compile_kernels(sim):
    """Compile (or load from the cache) every kernel this scene uses, before step 1.

    Rank 0 goes first and fills the shared on-disk cache; the other ranks then load from
    it, so N ranks never compile the same kernel N times nor race on the cache files.
    The kernels run on zero particles with the halo exchanges off, which compiles exactly
    the signatures the real steps use. Reported apart as the JIT warm-up.
    """
    t0 = time.perf_counter()
    before = dict(sim.timers.total)
    for turn in (0, 1):
        if (sim.dist.rank == 0) == (turn == 0):
            _dry_step(sim)
        sim.dist.barrier()
    sim.timers.total.clear()
    sim.timers.total.update(before)  # the dry step's phases are not run time
    sim.timers.add("jit_warmup", time.perf_counter() - t0)


def _dry_step(sim):
    p = sim.particles
    n_owned, n_total = p.n_owned, p.n_total
    p.n_owned = p.n_total = 0
    try:
        if sim.mpm is not None:
            with sim.mpm.detached():
                sim.mpm.step(1e-30, 0.0)
            g = sim.mpm.grid
            cell_keys(p["x"], g.origin, g.inv_dx, g.strides)
        if sim.sph is not None:
            sim.sph.warm_up()
        sim.coupling.warm_up(sim)
        mtypes, mparams = sim.materials
        mstate = p["mstate"] if "mstate" in p else np.zeros((0, 0))
        particle_sums(sim.dim, p["x"], p["v"], p["mass"], p["vol0"], p.deformation(),
                      p["mat"], mtypes, mparams, mstate, sim.gravity, sim._sums,
                      sim._mtag)
        max_signal_speed(sim.dim, p["v"], p.deformation(), p["mat"], mtypes, mparams)
        if sim.decomposition is not None:
            dec = sim.decomposition
            slab_leavers(p["x"], dec.axis, dec.origin, 1.0 / dec.dx, dec.ncells,
                         dec.lo_cell, dec.hi_cell)
    finally:
        p.n_owned, p.n_total = n_owned, n_total
        p.epoch += 1  # (rows found by gid during the dry step were of no particles)
