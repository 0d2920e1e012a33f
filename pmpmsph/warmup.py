"""The JIT warm-up of a `Simulation`: every kernel its scene uses compiled (or loaded from
the on-disk cache) before step 1, and reported apart from the run (Dedalus style)."""
import logging
import threading
import time

import numba
import numpy as np

from .kernels.diagnostics import max_signal_speed, particle_sums
from .kernels.partition import cell_keys, slab_leavers

log = logging.getLogger("pmpmsph")
#: seconds of warm-up after which the wait is announced (loading a warm cache takes less)
ANNOUNCE_AFTER = 3.0


def _announce():
    log.info("compiling the kernels this scene uses: the first run of a version (or of a new "
             "kind of scene) takes up to a few minutes; they are cached in %s",
             numba.config.CACHE_DIR)


def compile_kernels(sim):
    """Compile (or load from the cache) every kernel this scene uses, before step 1.

    Rank 0 goes first and fills the shared on-disk cache; the other ranks then load from
    it, so N ranks never compile the same kernel N times nor race on the cache files.
    The kernels run on zero particles with the halo exchanges off, which compiles exactly
    the signatures the real steps use. Reported apart as the JIT warm-up.
    """
    t0 = time.perf_counter()
    before = dict(sim.timers.total)
    # A timer rather than a guess at the cache's state: only a wait that happens is announced.
    notice = threading.Timer(ANNOUNCE_AFTER, _announce) if sim.dist.rank == 0 else None
    if notice is not None:
        notice.daemon = True
        notice.start()
    try:
        for turn in (0, 1):
            if (sim.dist.rank == 0) == (turn == 0):
                _dry_step(sim)
            sim.dist.barrier()
    finally:
        if notice is not None:
            notice.cancel()
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
        max_signal_speed(sim.dim, p["v"], p.deformation(), p["mat"], mtypes, mparams, sim._mtag)
        if sim.decomposition is not None:
            dec = sim.decomposition
            slab_leavers(p["x"], dec.axis, dec.origin, 1.0 / dec.dx, dec.ncells,
                         dec.lo_cell, dec.hi_cell)
    finally:
        p.n_owned, p.n_total = n_owned, n_total
        p.epoch += 1  # (rows found by gid during the dry step were of no particles)
