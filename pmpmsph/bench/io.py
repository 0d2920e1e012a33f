"""Output overhead: the same MPM run with snapshots every N steps and with no output.

`python -m pmpmsph.bench io [--particles 1000000] [--steps 200] [--every 100] [--ranks 2]`
starts one `mpirun -n RANKS python -m pmpmsph.bench io-worker` on the scaling scene (2D water
column, quadratic B-splines, USL; see bench/scaling.py) and times blocks of `--every` steps
in four configurations, each output block between two blocks without output (none,
default, none, double, none, diag/step, none, default, ...):

    none         no output at all
    default      what a run does with `[output] every_steps = N` and nothing else set: a
                 snapshot (particles.h5 + XDMF sidecar; default fields in float32) every N
                 steps and a diagnostics row at the default interval
                 for this particle count (OutputSpec.diagnostics_interval: every 100 steps
                 above 100,000 particles, so one row per block of 100)
    double       the same with `precision = "double"` snapshots
    diag/step    the default plus a diagnostics row every step (`diagnostics_every = 1`)

Each output configuration runs `--steps` steps in all. Its baseline T_base is the mean of
the no-output blocks just before and after each of its blocks: the cost of a step drifts as
the column collapses (and with the load of a shared machine), which a fixed order of blocks
(none, default, double, diag/step, none, ...) turns into a bias of the later ones. Reported:
the overhead (T - T_base) / T_base from the wall times (still noisy on a shared machine),
the `output` phase and the diagnostics time (slowest rank) and their sum over T_base
("direct" overhead, steadier), the bytes written (and per particle), the write bandwidth =
bytes / output-phase time, and one checkpoint (time, size, bandwidth). The page cache is
flushed (os.sync, outside the timed blocks) before every block, so that the dirty pages of
one write do not throttle the next. Writes bench_results/io.json.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

from ..parallel.distributor import Distributor
from .scaling import scaling_scene

CONFIGS = ("none", "default", "double", "diag/step")


def worker(argv):


    ap = argparse.ArgumentParser()
    ap.add_argument("--particles", type=int, required=True)
    ap.add_argument("--steps", type=int, required=True)
    ap.add_argument("--every", type=int, required=True)
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--json", required=True)
    a = ap.parse_args(argv)
    dist = Distributor()
    scene = scaling_scene(a.particles)
    scene.set("output.every_steps", a.every)
    sim = scene.simulation(dist=dist, out_dir=a.out_dir, overwrite=True)
    n_global = int(dist.sum(sim.particles.n_owned))
    diag_every = sim.case.output.diagnostics_interval(n_global)
    single = sim.writer.float_dtype
    h5 = os.path.join(a.out_dir, "particles.h5")
    for _ in range(10):  # first steps (first balancing, caches), outside the timing
        sim.step()
    sim.write_snapshot()  # outside the timing
    res = {c: {"wall": 0.0, "output_phase": 0.0, "diagnostics": 0.0, "snapshots": 0, "bytes": 0,
               "base": 0.0} for c in CONFIGS}
    blocks = max(a.steps // a.every, 1)
    order = ["none"]
    for _ in range(blocks):
        for config in CONFIGS[1:]:
            order += [config, "none"]
    walls = []  # of every block, in order
    for config in order:  # blocks of a.every steps
        if dist.is_root:
            os.sync()
        size0 = os.path.getsize(h5) if dist.is_root else 0
        out0 = sim.timers.total.get("output", 0.0)
        diag = 0.0
        # the stored float type is the writer's; "double" switches it for its blocks
        sim.writer.float_dtype = np.float64 if config == "double" else single
        every = 1 if config == "diag/step" else diag_every
        dist.barrier()
        t0 = time.perf_counter()
        for _ in range(a.every):  # what Simulation.run does per step for output
            sim.step()
            if config != "none" and sim.step_count % every == 0:
                td = time.perf_counter()
                sim.diag.append(sim.diagnostics())
                diag += time.perf_counter() - td
            if config != "none" and sim.step_count % a.every == 0:
                sim.write_snapshot()
        dist.barrier()
        r = res[config]
        walls.append(time.perf_counter() - t0)
        r["wall"] += walls[-1]
        r["output_phase"] += dist.max(sim.timers.total.get("output", 0.0) - out0)
        r["diagnostics"] += dist.max(diag)
        r["snapshots"] += int(config != "none")
        r["bytes"] += (os.path.getsize(h5) - size0) if dist.is_root else 0
    for i, config in enumerate(order):  # output blocks sit between two none blocks
        if config != "none":
            res[config]["base"] += 0.5 * (walls[i - 1] + walls[i + 1])
    res["none"]["base"] = res["none"]["wall"]
    if dist.is_root:
        os.sync()
    dist.barrier()
    t1 = time.perf_counter()
    path = sim.write_checkpoint()
    dist.barrier()
    ck_time = time.perf_counter() - t1
    layout = sim.writer.mode
    sim.close()
    if dist.is_root:
        result = {"ranks": dist.size, "particles": n_global, "steps": blocks * a.every,
                  "every": a.every, "layout": layout, "configs": res,
                  "diagnostics_every": diag_every, "fields": list(sim.case.output.fields),
                  "checkpoint_s": ck_time, "checkpoint_bytes": os.path.getsize(path)}
        with open(a.json, "w") as fh:
            json.dump(result, fh, indent=1)
    return 0


def run(ranks: int = 2, particles: int = 1_000_000, steps: int = 200, every: int = 100,
        out: str = "bench_results") -> dict:
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    launcher = os.environ.get("PMPMSPH_MPIRUN", os.path.join(root, "scripts", "mpirun") + " -n")
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "io_raw.json")
    cmd = [*launcher.split(), str(ranks), sys.executable, "-m", "pmpmsph.bench", "io-worker",
           "--particles", str(particles), "--steps", str(steps), "--every", str(every),
           "--out-dir", os.path.join(out, "io_run"), "--json", path]
    subprocess.run(cmd, check=True)
    with open(path) as fh:
        raw = json.load(fh)
    res = raw["configs"]
    summary = dict(raw)
    print(f"\noutput overhead: {raw['particles']} particles on {ranks} ranks, {raw['steps']} "
          f"steps per configuration, a snapshot every {every} steps ({raw['layout']} layout), "
          f"default diagnostics every {raw['diagnostics_every']} steps; fields "
          f"{', '.join(raw['fields'])}")
    print(f"{'configuration':<14}{'wall s':>8}{'base s':>8}{'overhead':>10}{'output s':>10}"
          f"{'diag s':>8}{'direct':>8}{'snapshots':>10}{'MiB':>8}{'MiB/s':>8}{'B/particle':>12}")
    for label in CONFIGS:
        r = res[label]
        r["overhead"] = (r["wall"] - r["base"]) / r["base"]
        r["bandwidth"] = r["bytes"] / r["output_phase"] if r["output_phase"] > 0 else 0.0
        r["direct"] = (r["output_phase"] + r["diagnostics"]) / r["base"]
        r["bytes_per_particle"] = (r["bytes"] / r["snapshots"] / raw["particles"]
                                   if r["snapshots"] else 0.0)
        print(f"{label:<14}{r['wall']:>8.2f}{r['base']:>8.2f}{100 * r['overhead']:>9.2f}%"
              f"{r['output_phase']:>10.2f}{r['diagnostics']:>8.2f}{100 * r['direct']:>7.2f}%"
              f"{r['snapshots']:>10d}{r['bytes'] / 2**20:>8.0f}{r['bandwidth'] / 2**20:>8.0f}"
              f"{r['bytes_per_particle']:>12.1f}")
    ck_bw = raw["checkpoint_bytes"] / raw["checkpoint_s"] if raw["checkpoint_s"] > 0 else 0.0
    summary["checkpoint_bandwidth"] = ck_bw
    print(f"one checkpoint: {raw['checkpoint_s']:.2f} s, {raw['checkpoint_bytes'] / 2**20:.0f} "
          f"MiB, {ck_bw / 2**20:.0f} MiB/s")
    with open(os.path.join(out, "io.json"), "w") as fh:
        json.dump(summary, fh, indent=1)
    return summary
