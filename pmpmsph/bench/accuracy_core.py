"""What every point of the accuracy bench measures, on whatever communicator it is given.

A point is one run of one scene by one method at one resolution. Its cost is the wall time
spent inside `Simulation.step` (the slowest rank's; the probes that read the error out of
the state are not counted: they are the bench's, not the method's), particle-steps (global
particles, walls included, times steps) and memory as the bytes of the particle arrays
(global, allocated capacity). The peak resident set of the process is recorded too, but it
is a high-water mark over the whole sweep, so it only ever grows from point to point.
"""
import csv
import resource
import time

import numpy as np

#: the columns of a study's CSV, one row a point
COLUMNS = ["scene", "method", "family", "level", "knob", "error", "aux", "particles", "steps",
           "particle_steps", "wall", "particle_bytes", "peak_rss_mb", "note"]


def _timed_step(sim, on_step):
    """One `sim.step()`, then `on_step(sim)` if given; the seconds spent in the step."""
    t0 = time.perf_counter()
    sim.step()
    spent = time.perf_counter() - t0
    if on_step is not None:
        on_step(sim)
    return spent


def advance(sim, end, on_step=None):
    """Step `sim` to time `end` (the last step shortened to land on it); `on_step(sim)`
    after every step. Returns the seconds this rank spent in `sim.step` alone."""
    spent = 0.0
    while sim.time < end - 1e-6 * sim.dt:
        if sim.time + sim.dt > end:
            sim.dt = end - sim.time
        spent += _timed_step(sim, on_step)
    return spent


def steps_for(sim, n, on_step=None):
    """Exactly `n` steps (fixed-step scenes such as the reversal); seconds in `step`."""
    return sum(_timed_step(sim, on_step) for _ in range(n))


def gathered(sim, names):
    """Global arrays of the owned rows of `names`, sorted by gid, on every rank."""
    p = sim.particles
    dist = sim.dist
    gid = np.concatenate(dist.allgather(p["gid"].copy()))
    parts = {k: np.concatenate(dist.allgather(p[k].copy())) for k in names}
    order = np.argsort(gid)
    return {k: v[order] for k, v in parts.items()}


def masked_sum(sim, values):
    """Global sum of a per-particle array over every rank's owned rows."""
    return float(sim.dist.sum(float(np.sum(values))))


def particle_bytes(sim):
    """Bytes held by the particle arrays on every rank together (allocated capacity)."""
    local = sum(a.nbytes for a in sim.particles.arrays.values())
    return int(sim.dist.sum(local))


def peak_rss_mb(dist):
    """Largest peak resident set over the ranks, MiB (Linux reports KiB)."""
    return dist.max(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0)


def cost(sim, seconds):
    """The cost columns of a finished point; collective."""
    n = int(sim.dist.sum(sim.particles.n_owned))
    return {"particles": n, "steps": sim.step_count, "particle_steps": n * sim.step_count,
            "wall": float(sim.dist.max(seconds)), "particle_bytes": particle_bytes(sim),
            "peak_rss_mb": round(peak_rss_mb(sim.dist), 1)}


def read_csv(path):
    """Rows of a scene CSV with numbers as floats (the report reads back what it wrote)."""
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:
        for k in COLUMNS[4:-1]:
            r[k] = float(r[k]) if r[k] not in ("", None) else np.nan
    return rows
