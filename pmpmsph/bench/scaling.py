"""Strong scaling on 1..N ranks of an MPM scene of at least 500,000 particles.

`python -m pmpmsph.bench scaling [--ranks 1 2] [--particles 500000] [--steps 100]` starts
`mpirun -n N python -m pmpmsph.bench scaling-worker` for each N and tabulates: wall time per
step, particle-steps/s per rank, per-phase times (slowest rank), bytes sent per rank per step
(ghost nodes and migration) and parallel efficiency E(N) = T(1) / (N T(N)).

The scene (`--scene column`, the default): a 2D water column (Tait, c ~ 30 m/s) collapsing
in a 2 x 1 box, quadratic B-splines, USL, CFL 0.5; particles flow across the slab faces, so
migration and the load balancer take part. `--scene coupled_dam --spacing S`: the coupled
dam break on an elastic obstacle (cases/coupled_dam_obstacle.toml: SPH water and walls, an
MPM rubber obstacle) with every body seeded at spacing S and the walls 4 layers thick
(0.0033: 55,231 particles); its
table adds the SPH phases.

`--corun` adds the co-run ceiling: one 1-rank run of half the particles alone, then two such
runs at once (separate processes, no MPI between them). Their slowdown is what two ranks on
this machine lose to each other through shared caches and memory bandwidth alone, so
T(alone) / T(co-run) bounds the 2-rank efficiency a bandwidth-bound step can reach here.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

from ..config.load import load_case_file
from ..parallel.distributor import Distributor
from ..parallel.migration import migrate
from ..scene_api import Scene
from ..simulation import Simulation

PHASES = ("p2g", "grid", "g2p", "halo", "migration", "balance", "output")
COMPUTE = ("p2g", "grid", "g2p")
#: per scene: (the phases tabulated, those that are the particles' own work)
SCENES = {"column": (PHASES, COMPUTE),
          "coupled_dam": (("p2g", "grid", "g2p", "sph", "integrate", "coupling", "neighbours",
                           "halo", "migration", "balance", "output"),
                          ("p2g", "grid", "g2p", "sph", "integrate", "coupling",
                           "neighbours"))}
COUPLED_CASE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "cases",
                            "coupled_dam_obstacle.toml")


def scaling_scene(particles=500_000, balance_every=25):
    ppc = 2
    cells_needed = particles / ppc**2
    ny = int(math.ceil(math.sqrt(cells_needed)))          # the column is about square
    dx = 1.0 / ny
    nx_col = int(math.ceil(cells_needed / ny))
    sc = Scene(2, grid=dict(origin=[0, 0], cell_size=dx, cells=[2 * ny, ny + 4]),
               time=dict(end=10.0, cfl=0.5), gravity=[0.0, -9.81],
               mpm=dict(shape="quadratic", transfer="usl"),
               # faces follow the measured compute time to within 3 % (the default 10 % would
               # let the slower rank idle up to a tenth of every step)
               parallel=dict(axis="x", balance_every=balance_every, balance_by="time",
                             balance_threshold=0.03))
    sc.material("water", model="tait", rho=1000.0, kappa=1.3e5, gamma=7.0, mu=1e-3)
    sc.body(name="water", material="water", shape="box", min=[0.0, 0.0],
            max=[nx_col * dx, ny * dx], ppc=ppc)
    for face in ("x-", "x+", "y-", "y+"):
        sc.boundary(face=face, type="slip")
    return sc


#: the case's dummy walls are this many particle layers thick (cases/coupled_dam_obstacle.toml)
WALL_LAYERS = 4


def coupled_dam_case(spacing):
    """cases/coupled_dam_obstacle.toml with all five bodies seeded at `spacing`, the dummy
    walls kept WALL_LAYERS layers thick (as in the case: enough for the kernel's support of
    1.3 x 2 spacings). Kept at the case's 0.08 m they would grow to 20 layers at spacing 0.004,
    a third of the particles and more than a third of the SPH work spent deep inside walls
    that no fluid particle reaches."""
    t = WALL_LAYERS * spacing
    sets = [(f"bodies[{i}].spacing", spacing) for i in range(5)]
    sets += [("bodies[2].min", [0.0, -t]),                 # floor
             ("bodies[3].min", [-t, -t]), ("bodies[3].max", [0.0, 1.4]),   # left wall
             ("bodies[4].min", [2.0, -t]), ("bodies[4].max", [2.0 + t, 1.4])]  # right wall
    # faces follow the measured compute time, as in the column scene (equal slabs of cells
    # left the rank holding the water column a quarter slower per particle)
    sets += [("parallel.balance_every", 25), ("parallel.balance_by", "time"),
             ("parallel.balance_threshold", 0.03)]
    return load_case_file(os.path.normpath(COUPLED_CASE), overrides=sets)


def worker(argv):

    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="column", choices=sorted(SCENES))
    ap.add_argument("--spacing", type=float, default=0.0033)
    ap.add_argument("--particles", type=int, default=500_000)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--warmup", type=int, default=10)
    ap.add_argument("--out-dir", default=None)
    ap.add_argument("--output-every", type=int, default=0, help="snapshot every N steps")
    ap.add_argument("--json", required=True)
    a = ap.parse_args(argv)
    dist = Distributor()
    if a.scene == "column":
        scene = scaling_scene(a.particles)
        if a.output_every:
            scene.set("output.every_steps", a.output_every)
        sim = scene.simulation(dist=dist, out_dir=a.out_dir, overwrite=True)
    else:
        sim = Simulation(coupled_dam_case(a.spacing), dist=dist, write_output=False)
    phases = SCENES[a.scene][0]
    n_global = dist.sum(sim.particles.n_owned)
    sim.run(max_steps=a.warmup)  # JIT compile / cache load, first balance
    sim.timers.total.clear()

    def halo_bytes():  # ghost nodes, and the SPH particle halo of a coupled scene
        return sim.mpm.halo.bytes_sent + (sim.sph.halo.bytes_sent if sim.sph else 0)

    halo0 = halo_bytes()
    mig0 = migrate.bytes_sent
    dist.barrier()
    t0 = time.perf_counter()
    sim.run(max_steps=a.steps)
    dist.barrier()
    wall = time.perf_counter() - t0
    mine = {"phases": {k: sim.timers.total.get(k, 0.0) for k in phases},
            "halo_bytes": halo_bytes() - halo0,
            "migration_bytes": migrate.bytes_sent - mig0,
            "particles": sim.particles.n_owned}
    everyone = dist.gather(mine)
    if dist.is_root:
        result = {"ranks": dist.size, "particles": int(n_global), "steps": a.steps,
                  "wall": wall, "per_rank": everyone,
                  "faces": [int(f) for f in sim.decomposition.faces]}
        with open(a.json, "w") as fh:
            json.dump(result, fh, indent=1)
    sim.close()
    return 0


def _launcher():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    # on a cluster: PMPMSPH_MPIRUN="srun --ntasks" (see slurm/); here scripts/mpirun -n
    return os.environ.get("PMPMSPH_MPIRUN", os.path.join(root, "scripts", "mpirun") + " -n")


def _worker_cmd(ranks, particles, steps, path, unbound=False):
    """The worker's command line; `unbound` (co-runs under this machine's mpirun): each
    `mpirun -n 1` would bind its rank to the first core, so two of them would share it."""
    launcher = _launcher().split()
    if unbound and "PMPMSPH_MPIRUN" not in os.environ:
        launcher = launcher[:-1] + ["--bind-to", "none"] + launcher[-1:]
    return [*launcher, str(ranks), sys.executable, "-m", "pmpmsph.bench",
            "scaling-worker", "--particles", str(particles), "--steps", str(steps),
            "--json", path]


def corun(particles, steps, out):
    """Half the scene on one rank alone, then two copies at once (see the module doc)."""
    half = particles // 2
    alone = os.path.join(out, "corun_alone.json")
    subprocess.run(_worker_cmd(1, half, steps, alone, unbound=True), check=True)
    paths = [os.path.join(out, f"corun_{k}.json") for k in range(2)]
    procs = [subprocess.Popen(_worker_cmd(1, half, steps, p, unbound=True)) for p in paths]
    if any(p.wait() != 0 for p in procs):
        raise RuntimeError("a co-run worker failed")
    walls = []
    for p in [alone] + paths:
        with open(p) as fh:
            walls.append(json.load(fh)["wall"])
    ceiling = walls[0] / max(walls[1:])
    print(f"\nco-run ceiling, {half} particles per process, {steps} steps: alone "
          f"{walls[0] / steps:.4f} s/step, two at once {walls[1] / steps:.4f} and "
          f"{walls[2] / steps:.4f} s/step -> T(alone)/T(co-run) = {ceiling:.2f}")
    with open(os.path.join(out, "corun.json"), "w") as fh:
        json.dump({"particles_each": half, "steps": steps, "alone": walls[0],
                   "corun": walls[1:], "ceiling": ceiling}, fh, indent=1)
    return ceiling


def run(ranks: "list[int]", particles: int, steps: int, out: str, output_every: int = 0,
        repeat: int = 3, scene: str = "column", spacing: float = 0.0033) -> "list[dict]":
    """`repeat` rounds, each running every rank count once in turn (so slow spells of a shared
    machine hit all counts alike); each count's fastest round is tabulated, as timeit does,
    and the efficiency of every round is printed beside it."""
    os.makedirs(out, exist_ok=True)
    rounds = []
    for k in range(repeat):
        row = []
        for n in ranks:
            path = os.path.join(out, f"scaling_{n}_{k}.json")
            cmd = _worker_cmd(n, particles, steps, path) + ["--scene", scene,
                                                            "--spacing", str(spacing)]
            if output_every:
                cmd += ["--out-dir", os.path.join(out, f"scaling_run_{n}"), "--output-every",
                        str(output_every)]
            subprocess.run(cmd, check=True)
            with open(path) as fh:
                row.append(json.load(fh))
        rounds.append(row)
    rows = [min((r[i] for r in rounds), key=lambda x: x["wall"]) for i in range(len(ranks))]
    for i, n in enumerate(ranks[1:], 1):
        effs = [r[0]["wall"] * r[0]["ranks"] / (n * r[i]["wall"]) for r in rounds]
        print(f"efficiency on {n} ranks in each of {repeat} rounds: "
              + " ".join(f"{e:.2f}" for e in effs))
    phases, compute = SCENES[scene]
    t1 = rows[0]["wall"] * rows[0]["ranks"]
    print(f"\nstrong scaling, {rows[0]['particles']} particles, {steps} steps "
          f"(slowest rank's phase times, seconds per step)")
    head = f"{'ranks':>5} {'s/step':>8} {'Mps/s/rank':>10} {'eff':>5} " + " ".join(
        f"{p:>9}" for p in phases) + f" {'halo B/step':>11} {'migr B/step':>11}"
    print(head)
    for r in rows:
        n, steps_ = r["ranks"], r["steps"]
        per = r["per_rank"]
        phase = {p: max(x["phases"][p] for x in per) / steps_ for p in phases}
        eff = t1 / (n * r["wall"])
        rate = r["particles"] * steps_ / r["wall"] / n / 1e6
        halo_b = max(x["halo_bytes"] for x in per) / steps_
        mig_b = max(x["migration_bytes"] for x in per) / steps_
        r["efficiency"] = eff
        print(f"{n:>5} {r['wall'] / steps_:>8.4f} {rate:>10.2f} {eff:>5.2f} " + " ".join(
            f"{phase[p]:>9.4f}" for p in phases) + f" {halo_b:>11.0f} {mig_b:>11.0f}")
    # each rank's own speed: unequal figures mean unequal cores (or cores slowing each
    # other), which no decomposition can hide
    for r in rows:
        speeds = [sum(x["phases"][p] for p in compute) / max(x["particles"], 1) / r["steps"]
                  * 1e9 for x in r["per_rank"]]
        r["compute_ns_per_particle_step"] = speeds
        print(f"{r['ranks']:>5} ranks: {' + '.join(compute)} per particle-step on each rank: "
              + ", ".join(f"{v:.1f}" for v in speeds) + " ns")
    with open(os.path.join(out, "scaling.json"), "w") as fh:
        json.dump(rows, fh, indent=1)
    return rows
