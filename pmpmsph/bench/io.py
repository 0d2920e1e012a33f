"""Output overhead: the same MPM run with snapshots every N steps and with no output.

`python -m pmpmsph.bench io [--particles 1000000] [--steps 200] [--every 100] [--ranks 2]`
starts `mpirun -n RANKS python -m pmpmsph.bench io-worker` once per configuration on the
scaling scene (2D water column, quadratic B-splines, USL; see bench/scaling.py):

    none         no output at all
    snapshots    a snapshot every `--every` steps (with the XDMF sidecar) and a diagnostics
                 row at the same cadence (output.diagnostics_every = every)
    diag/step    the same plus a diagnostics row every step (the default diagnostics_every)

Each worker first calls run(max_steps=0), which writes the step-0 snapshot and row, then
times run(max_steps=STEPS) from step 0, so the timed part holds STEPS / every snapshots.
Reported: the overhead (T - T_none) / T_none, the `output` phase (slowest rank), the bytes
added to particles.h5 and the write bandwidth = bytes / output-phase time, and one
checkpoint written at the end (time, size, bandwidth). `--repeat R` runs the configurations
R times, interleaved, and keeps the fastest of each (the machine may be shared). Writes
bench_results/io.json.
"""
import json
import os
import subprocess
import sys
import time

from .scaling import scaling_scene

CONFIGS = ("none", "snapshots", "diag/step")


def worker(argv):
    import argparse

    from ..parallel.distributor import Distributor

    ap = argparse.ArgumentParser()
    ap.add_argument("--particles", type=int, required=True)
    ap.add_argument("--steps", type=int, required=True)
    ap.add_argument("--every", type=int, default=0, help="snapshot every N steps (0: no output)")
    ap.add_argument("--diag-every", type=int, default=1)
    ap.add_argument("--out-dir", default=None)
    ap.add_argument("--json", required=True)
    a = ap.parse_args(argv)
    dist = Distributor()
    scene = scaling_scene(a.particles)
    out = a.out_dir if a.every else None
    if a.every:
        scene.set("output.every_steps", a.every)
        scene.set("output.diagnostics_every", a.diag_every)
    sim = scene.simulation(dist=dist, out_dir=out, overwrite=True)
    n_global = int(dist.sum(sim.particles.n_owned))
    h5 = os.path.join(out, "particles.h5") if out else None
    sim.run(max_steps=0)  # the step-0 snapshot and diagnostics row
    bytes0 = os.path.getsize(h5) if h5 and dist.is_root else 0
    snaps0 = sim.writer.index if sim.writer is not None else 0
    sim.timers.total.clear()
    dist.barrier()
    t0 = time.perf_counter()
    sim.run(max_steps=a.steps)
    dist.barrier()
    wall = time.perf_counter() - t0
    output = dist.max(sim.timers.total.get("output", 0.0))
    snapshots = (sim.writer.index - snaps0) if sim.writer is not None else 0
    layout = sim.writer.mode if sim.writer is not None else None
    ck_time = ck_bytes = 0.0
    if a.every:
        dist.barrier()
        t1 = time.perf_counter()
        path = sim.write_checkpoint()
        dist.barrier()
        ck_time = time.perf_counter() - t1
        ck_bytes = os.path.getsize(path) if dist.is_root else 0
    sim.close()
    if dist.is_root:
        result = {"ranks": dist.size, "particles": n_global, "steps": a.steps,
                  "every": a.every, "diag_every": a.diag_every, "wall": wall,
                  "output_phase": output, "snapshots": snapshots,
                  "bytes": (os.path.getsize(h5) - bytes0) if h5 else 0, "layout": layout,
                  "checkpoint_s": ck_time, "checkpoint_bytes": ck_bytes}
        with open(a.json, "w") as fh:
            json.dump(result, fh, indent=1)
    return 0


def run(ranks=2, particles=1_000_000, steps=200, every=100, out="bench_results", repeat=1):
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    launcher = os.environ.get("PMPMSPH_MPIRUN", os.path.join(root, "scripts", "mpirun") + " -n")
    os.makedirs(out, exist_ok=True)
    best = {}
    for _ in range(repeat):
        for label in CONFIGS:
            ev, diag = {"none": (0, 1), "snapshots": (every, every),
                        "diag/step": (every, 1)}[label]
            path = os.path.join(out, f"io_{label.replace('/', '_')}.json")
            cmd = [*launcher.split(), str(ranks), sys.executable, "-m", "pmpmsph.bench",
                   "io-worker", "--particles", str(particles), "--steps", str(steps),
                   "--every", str(ev), "--diag-every", str(diag), "--json", path]
            if ev:
                cmd += ["--out-dir", os.path.join(out, "io_run")]
            subprocess.run(cmd, check=True)
            with open(path) as fh:
                row = json.load(fh)
            if label not in best or row["wall"] < best[label]["wall"]:
                best[label] = row
    none = best["none"]["wall"]
    summary = {"ranks": ranks, "particles": best["none"]["particles"], "steps": steps,
               "every": every, "repeat": repeat, "configs": {}}
    print(f"\noutput overhead: {summary['particles']} particles on {ranks} ranks, {steps} "
          f"steps, a snapshot every {every} steps ({best['snapshots']['layout']} layout); "
          f"best of {repeat}")
    print(f"{'configuration':<14}{'wall s':>8}{'overhead':>10}{'output s':>10}{'snapshots':>10}"
          f"{'MiB':>8}{'MiB/s':>8}")
    for label in CONFIGS:
        r = best[label]
        bw = r["bytes"] / r["output_phase"] if r["output_phase"] > 0 else 0.0
        over = (r["wall"] - none) / none
        summary["configs"][label] = dict(r, overhead=over, bandwidth=bw)
        print(f"{label:<14}{r['wall']:>8.2f}{100 * over:>9.2f}%{r['output_phase']:>10.2f}"
              f"{r['snapshots']:>10d}{r['bytes'] / 2**20:>8.0f}{bw / 2**20:>8.0f}")
    r = best["snapshots"]
    ck_bw = r["checkpoint_bytes"] / r["checkpoint_s"] if r["checkpoint_s"] > 0 else 0.0
    print(f"one checkpoint: {r['checkpoint_s']:.2f} s, {r['checkpoint_bytes'] / 2**20:.0f} MiB, "
          f"{ck_bw / 2**20:.0f} MiB/s")
    summary["checkpoint"] = {"seconds": r["checkpoint_s"], "bytes": r["checkpoint_bytes"],
                             "bandwidth": ck_bw}
    with open(os.path.join(out, "io.json"), "w") as fh:
        json.dump(summary, fh, indent=1)
    return summary
