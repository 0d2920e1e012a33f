"""Strong and weak scaling on 1..N ranks of a scene: the MPM column, the coupled dam break or
any case file.

`python -m pmpmsph.bench scaling [--ranks 1 2] [--particles 500000] [--steps 100]` starts
`mpirun -n N python -m pmpmsph.bench scaling-worker` for each N and tabulates: wall time per
step, particle-steps/s per rank, per-phase times (slowest rank), bytes sent per rank per step
(ghost nodes and migration), the point-to-point messages and collectives per rank per step,
and the parallel efficiency: E(N) = T(1) / (N T(N)) for strong scaling, T(1) / T(N) for weak
scaling (`--weak`). It writes scaling.json and scaling.png (efficiency against ranks) in
`--out`.

The scene (`--scene column`, the default): a 2D water column (Tait, c ~ 30 m/s) collapsing
in a 2 x 1 box, quadratic B-splines, USL, CFL 0.5; particles flow across the slab faces, so
migration and the load balancer take part. `--scene coupled_dam --spacing S`: the coupled
dam break on an elastic obstacle (cases/coupled_dam_obstacle.toml: SPH water and walls, an
MPM rubber obstacle) with every body seeded at spacing S and the walls 4 layers thick
(0.0033: 55,231 particles); its table adds the SPH phases. `--case FILE [--set key=value
...]`: any case file (MPM, SPH, TL-SPH, coupled; 1D to 3D), with the loader's overrides; the
phases tabulated are those the run timed.

Weak scaling (`--weak`) keeps the particles per rank fixed by growing the scene along the
slab axis, the axis the decomposition cuts (parallel/decomposition.py): on N ranks the
scene is replicated N times side by side along that axis (`replicate`), at a pitch of the
grid's (or the SPH [domain]'s) length along it. Every body, box boundary, load, prescribed
region, method region and damping zone is copied and shifted; the grid (or domain) gets N
times the cells (length) along the axis, and the faces' boundaries stay at the ends. Copying
rather than stretching keeps every body's shape, spacing and the physics of each copy (a
stretched scene would change the flow: a longer column, a wider tank); the copies only
meet at their common faces, where nothing separates them any more (a copy's water may flow
into the next copy's tank past its dummy walls, as in a row of tanks). With the slab faces
at equal cell counts, each of the N ranks starts with exactly one copy: the particle count
per rank is the one-rank count.

`--corun` adds the co-run ceiling: one 1-rank run of half the particles alone, then two such
runs at once (separate processes, no MPI between them). Their slowdown is what two ranks on
this machine lose to each other through shared caches and memory bandwidth alone, so
T(alone) / T(co-run) bounds the 2-rank efficiency a bandwidth-bound step can reach here.
"""
import argparse
import copy
import json
import math
import os
import subprocess
import sys
import time
import tomllib
from types import SimpleNamespace

from ..config.load import apply_overrides, case_from_dict, parse_set
from ..config.sections import CASE_DIR
from ..errors import ConfigError
from ..parallel.distributor import Distributor
from ..parallel.migration import migrate
from ..scene_api import Scene
from ..simulation import Simulation

PHASES = ("p2g", "grid", "g2p", "halo", "migration", "balance", "output")
COMPUTE = ("p2g", "grid", "g2p")
#: every phase `Simulation.timers` knows, in the order tabulated (a case's run times some)
ALL_PHASES = ("p2g", "grid", "g2p", "sph", "integrate", "coupling", "neighbours", "sort",
              "halo", "migration", "balance", "output")
#: the phases that are not the particles' own work (exchanges, balancing, writing)
OVERHEAD = ("halo", "migration", "balance", "output", "checkpoint")
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


def _coupled_dam_sets(spacing):
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
    return sets


def coupled_dam_case(spacing):
    """The coupled dam break of `_coupled_dam_sets` as a Case."""
    data, name, base = case_data(os.path.normpath(COUPLED_CASE), _coupled_dam_sets(spacing))
    return build_case(data, name, base)


# -- any case file, and its copies along the slab axis ----------------------------------------
def case_data(path, overrides=()):
    """(the raw dict of the case file with `overrides` applied, its name, its folder)."""
    try:
        with open(path, encoding="utf-8-sig") as fh:
            data = tomllib.loads(fh.read())
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise ConfigError("--case", f"cannot read {path}: {exc}") from None
    name = os.path.splitext(os.path.basename(path))[0]
    return apply_overrides(data, overrides), name, os.path.dirname(os.path.abspath(path))


def build_case(data, name="scene", base_dir=None):
    """A Case from a raw dict (relative mesh paths taken from `base_dir`, as the loader does)."""
    token = CASE_DIR.set(base_dir)
    try:
        return case_from_dict(data, name=name)
    finally:
        CASE_DIR.reset(token)


def slab_axis(case):
    """The axis the decomposition of `case` cuts (`Simulation._decompose`'s own choice, on a
    one-rank distributor: the same rule on any number of ranks)."""
    dec = Simulation._decompose(SimpleNamespace(dist=Distributor.serial()), case)
    if dec is None:
        raise ConfigError("--case", "the case has neither a grid nor an SPH domain to cut")
    return dec.axis


def _pitch(data, axis, h=None):
    """The copies' spacing along `axis`: the grid's length along it; for a pure-SPH scene the
    [domain]'s length rounded up to whole decomposition cells of 2h (`Simulation._decompose`
    cuts the domain into floor(length / 2h) cells), so that the copies' common faces are
    cell faces of the longer domain too and the N equal slabs hold one copy each (a
    periodic axis keeps its length: the period is the scene's)."""
    grid = data.get("grid")
    if grid is not None:
        cells = grid["cells"]
        n = cells[axis] if isinstance(cells, list) else cells
        if "cell_size" in grid:
            size = grid["cell_size"]
            return n * (size[axis] if isinstance(size, list) else size)
        length = grid["length"]
        return length[axis] if isinstance(length, list) else length
    dom = data["domain"]
    length = dom["max"][axis] - dom["min"][axis]
    if h is None or "xyz"[axis] in dom.get("periodic", []):
        return length
    return math.ceil(length / (2.0 * h) - 1e-9) * 2.0 * h


def _per_axis(value, dim):
    """A scalar-or-list setting as a list of `dim` values (so one axis can change)."""
    return list(value) if isinstance(value, list) else [value] * dim


def _shifted(entry, axis, offset):
    """A copy of a body or region table moved by `offset` along `axis` (every point it
    names: box corners, a disc's centre, polygon vertices, a nested `box`)."""
    out = copy.deepcopy(entry)
    if out.get("shape") == "mesh":
        raise ConfigError("--weak", "a mesh body cannot be replicated (its file has fixed "
                          "coordinates): run strong scaling, or give the case as boxes")
    for key in ("min", "max", "centre", "center"):
        if isinstance(out.get(key), list):
            out[key][axis] += offset
    if isinstance(out.get("vertices"), list):
        for v in out["vertices"]:
            v[axis] += offset
    if isinstance(out.get("box"), dict):
        out["box"] = _shifted(out["box"], axis, offset)
    return out


def replicate(data, copies, axis, h=None):
    """The raw case `data` repeated `copies` times along `axis` (module doc): a new dict.

    Bodies are renamed `<name>_<k>` (k >= 1; copy 0 keeps its names) and every table that
    names a body (loads, prescribed) is copied with the copy's name. Probes and their output
    settings are dropped (the bench writes no output; a probe is a point of copy 0) and
    `[parallel] axis` is pinned, so the longer scene is still cut along the same axis. `h`:
    the SPH smoothing length of a scene without a grid (`_pitch`)."""
    data = copy.deepcopy(data)
    dim = int(data["dimension"])
    data.setdefault("parallel", {})["axis"] = "xyz"[axis]
    data.pop("probes", None)
    for key in [k for k in data.get("output", {}) if k.startswith("probes")]:
        del data["output"][key]  # (their settings are refused without probes)
    if copies == 1:
        return data
    pitch = _pitch(data, axis, h)
    grid = data.get("grid")
    if grid is not None:
        cells = _per_axis(grid["cells"], dim)
        cells[axis] *= copies
        grid["cells"] = cells
        if "length" in grid:
            length = _per_axis(grid["length"], dim)
            length[axis] *= copies
            grid["length"] = length
    dom = data.get("domain")
    if dom is not None:
        dom["max"] = list(dom["max"])
        # (grown by a hair more than the copies, so that floor(length / 2h) is not one cell
        # short by round-off)
        dom["max"][axis] = dom["min"][axis] + copies * pitch * (1.0 + 1e-12)

    def renamed(name, k):
        return name if k == 0 else f"{name}_{k}"

    bodies = data.get("bodies", [])
    data["bodies"] = [dict(_shifted(b, axis, k * pitch), **(
        {"name": renamed(b["name"], k)} if "name" in b else {}))
        for k in range(copies) for b in bodies]
    for key in ("loads", "prescribed"):
        if key in data:
            data[key] = [dict(_shifted(t, axis, k * pitch), **(
                {"body": renamed(t["body"], k)} if "body" in t else {}))
                for k in range(copies) for t in data[key]]
    for key in ("regions", "damping"):
        if key in data:
            data[key] = [_shifted(t, axis, k * pitch) for k in range(copies)
                         for t in data[key]]
    if "boundaries" in data:  # faces stay the scene's ends; boxes go with each copy
        data["boundaries"] = ([b for b in data["boundaries"] if "face" in b]
                              + [_shifted(b, axis, k * pitch) for k in range(copies)
                                 for b in data["boundaries"] if "face" not in b])
    return data


# -- messages and bytes, counted at the communicator --------------------------------------------
class CountingComm:
    """An mpi4py communicator that counts what this rank sends: point-to-point messages and
    their bytes (halo of nodes and particles, migration, the coupling's node sums: every
    Isend/Send, empty ones too, since each costs a latency) and collective calls. The solver
    reaches MPI only through `Distributor.comm` (parallel/distributor.py), so wrapping that
    one object sees everything; it is not given to parallel HDF5 (no output is written)."""

    def __init__(self, comm):
        self._comm = comm
        self.messages = 0
        self.bytes = 0
        self.collectives = 0

    def __getattr__(self, name):
        return getattr(self._comm, name)

    def _sent(self, buf):
        self.messages += 1
        self.bytes += int(getattr(buf, "nbytes", 0))

    def Isend(self, buf, *args, **kw):
        self._sent(buf)
        return self._comm.Isend(buf, *args, **kw)

    def Send(self, buf, *args, **kw):
        self._sent(buf)
        return self._comm.Send(buf, *args, **kw)

    def _collective(self, name):
        method = getattr(self._comm, name)

        def call(*args, **kw):
            self.collectives += 1
            return method(*args, **kw)
        return call

    def __getattribute__(self, name):
        if name in ("Allreduce", "allreduce", "allgather", "gather", "bcast", "exscan",
                    "Barrier", "Bcast", "Allgather", "Gather", "Reduce", "reduce"):
            return object.__getattribute__(self, "_collective")(name)
        return object.__getattribute__(self, name)


def worker(argv):

    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="column", choices=sorted(SCENES))
    ap.add_argument("--case", default=None)
    ap.add_argument("--set", action="append", default=[], dest="sets")
    ap.add_argument("--replicas", type=int, default=1)
    ap.add_argument("--spacing", type=float, default=0.0033)
    ap.add_argument("--particles", type=int, default=500_000)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--warmup", type=int, default=10)
    ap.add_argument("--out-dir", default=None)
    ap.add_argument("--output-every", type=int, default=0, help="snapshot every N steps")
    ap.add_argument("--json", required=True)
    a = ap.parse_args(argv)
    base, name = None, a.scene
    if a.case:
        data, name, base = case_data(a.case, parse_set(a.sets))
        data.setdefault("time", {})["end"] = 1e9  # the steps asked, whatever the case's end
    elif a.scene == "column":
        data = scaling_scene(a.particles).data
        if a.output_every:
            data.setdefault("output", {})["every_steps"] = a.output_every
    else:
        data, name, base = case_data(os.path.normpath(COUPLED_CASE),
                                     _coupled_dam_sets(a.spacing))
    one = build_case(data, name, base)
    axis = slab_axis(one)
    h = one.sph.h if one.grid is None and one.has_sph else None
    case = build_case(replicate(data, a.replicas, axis, h), name, base)
    world = Distributor()
    writes = bool(a.output_every and a.out_dir)
    # the counting communicator stays out of parallel HDF5, which needs the real one
    counter = None if writes else CountingComm(world.comm)
    dist = world if writes else Distributor(counter)
    sim = Simulation(case, dist=dist, out_dir=a.out_dir if writes else None, overwrite=True,
                     write_output=writes)
    if a.case:
        phases = tuple(ALL_PHASES)
    else:
        phases = SCENES[a.scene][0]
    n_global = dist.sum(sim.particles.n_owned)
    start_particles = sim.particles.n_owned
    sim.run(max_steps=a.warmup)  # JIT compile / cache load, first balance
    sim.timers.total.clear()

    def halo_bytes():  # ghost nodes, and the SPH particle halo of a coupled scene
        return ((sim.mpm.halo.bytes_sent if sim.mpm else 0)
                + (sim.sph.halo.bytes_sent if sim.sph else 0))

    def counts():
        return ((counter.messages, counter.bytes, counter.collectives) if counter
                else (0, 0, 0))

    halo0 = halo_bytes()
    mig0 = migrate.bytes_sent
    dist.barrier()
    c0 = counts()
    t0 = time.perf_counter()
    sim.run(max_steps=a.steps)
    c1 = counts()
    dist.barrier()
    wall = time.perf_counter() - t0
    timed = sim.timers.total
    if a.case:  # the phases this scene has
        phases = tuple(p for p in ALL_PHASES if p in timed)
    mine = {"phases": {k: timed.get(k, 0.0) for k in phases},
            "halo_bytes": halo_bytes() - halo0,
            "migration_bytes": migrate.bytes_sent - mig0,
            "messages": c1[0] - c0[0], "p2p_bytes": c1[1] - c0[1],
            "collectives": c1[2] - c0[2],
            "particles": sim.particles.n_owned, "start_particles": start_particles}
    # the row sizes of the model (docs/scaling.md): a particle in the SPH halo and a
    # migrating particle, in bytes
    p = sim.particles
    if sim.sph is not None and sim.sph.halo is not None:
        mine["sph_halo_row_bytes"] = int(p.byte_views(sim.sph.halo.names)[1])
        plan = sim.sph.halo._plan  # (send lists per route, ...) of the last exchange
        mine["sph_halo_rows_sent"] = int(sum(len(i) for i in plan[0].values())) if plan else 0
    mine["migration_row_bytes"] = int(p.byte_views(p.fields(migrate=True))[1])
    everyone = dist.gather(mine)
    if dist.is_root:
        result = {"ranks": dist.size, "particles": int(n_global), "steps": a.steps,
                  "scene": a.case or a.scene, "replicas": a.replicas, "axis": int(axis),
                  "counted": counter is not None, "wall": wall, "per_rank": everyone,
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


def _efficiency(row, first, weak):
    """E(N) against the first rank count's row: T(1)/T(N) weak, T(1)/(N T(N)) strong (with
    the first count r0 in place of 1: r0 T(r0) / (N T(N)))."""
    if weak:
        return first["wall"] / row["wall"]
    return first["wall"] * first["ranks"] / (row["ranks"] * row["wall"])


def plot(rows, rounds, path, title, weak):
    """Efficiency against ranks (matplotlib Agg, no display): the best round of each count
    (line) and every round's own pair (dots), the ideal 1 dashed."""
    import matplotlib  # noqa: PLC0415 - only the plot needs it

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: PLC0415

    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    ranks = [r["ranks"] for r in rows]
    for rnd in rounds:
        ax.plot(ranks, [_efficiency(r, rnd[0], weak) for r in rnd], "o", color="0.7", ms=4)
    ax.plot(ranks, [r["efficiency"] for r in rows], "o-", color="C0",
            label="best round of each count")
    ax.axhline(1.0, ls="--", color="0.4", lw=1)
    if len(set(ranks)) > 1 and min(ranks) > 0:
        ax.set_xscale("log", base=2)
    ax.set_xticks(ranks, [str(n) for n in ranks])
    ax.set_xlabel("ranks")
    ax.set_ylabel("weak efficiency T(1)/T(N)" if weak else "strong efficiency T(1)/(N T(N))")
    ax.set_ylim(0.0, max(1.1, max(r["efficiency"] for r in rows) * 1.05))
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def run(ranks: "list[int]", particles: int, steps: int, out: str, output_every: int = 0,
        repeat: int = 3, scene: str = "column", spacing: float = 0.0033,
        case: "str | None" = None, sets: "list[str] | tuple" = (), weak: bool = False,
        warmup: int = 10) -> "list[dict]":
    """`repeat` rounds, each running every rank count once in turn (so slow spells of a shared
    machine hit all counts alike); each count's fastest round is tabulated, as timeit does,
    and the efficiency of every round is printed beside it. `case` (a case file, with `sets`
    as --set key=value) replaces `scene`; `weak` runs N copies of the scene on N ranks
    (module doc). Writes scaling.json and scaling.png in `out`."""
    os.makedirs(out, exist_ok=True)
    rounds = []
    for k in range(repeat):
        row = []
        for n in ranks:
            path = os.path.join(out, f"scaling_{n}_{k}.json")
            cmd = _worker_cmd(n, particles, steps, path) + ["--scene", scene,
                                                            "--spacing", str(spacing),
                                                            "--warmup", str(warmup)]
            if case:
                cmd += ["--case", case] + [x for s in sets for x in ("--set", s)]
            if weak:
                cmd += ["--replicas", str(n)]
            if output_every:
                cmd += ["--out-dir", os.path.join(out, f"scaling_run_{n}"), "--output-every",
                        str(output_every)]
            # os.environ as Python read it at start: a process that has initialised MPI
            # (a test that ran a worker in-process) carries the singleton's PMIx variables
            # in its C environment, and an mpirun started with those fails at once
            subprocess.run(cmd, check=True, env=dict(os.environ))
            with open(path) as fh:
                row.append(json.load(fh))
        rounds.append(row)
    rows = [min((r[i] for r in rounds), key=lambda x: x["wall"]) for i in range(len(ranks))]
    kind = "weak" if weak else "strong"
    for i, n in enumerate(ranks[1:], 1):
        effs = [_efficiency(r[i], r[0], weak) for r in rounds]
        print(f"{kind} efficiency on {n} ranks in each of {repeat} rounds: "
              + " ".join(f"{e:.2f}" for e in effs))
    if case:
        timed = {p for r in rows for x in r["per_rank"] for p in x["phases"]}
        phases = tuple(p for p in ALL_PHASES if p in timed)
        compute = tuple(p for p in phases if p not in OVERHEAD)
    else:
        phases, compute = SCENES[scene]
    label = os.path.basename(case) if case else scene
    print(f"\n{kind} scaling of {label}, {rows[0]['particles']} particles on "
          f"{rows[0]['ranks']} rank(s)" + (", one copy per rank along the slab axis "
                                           f"{'xyz'[rows[0]['axis']]}" if weak else "")
          + f", {steps} steps (slowest rank's phase times, seconds per step)")
    head = (f"{'ranks':>5} {'particles':>9} {'s/step':>8} {'Mps/s/rank':>10} {'eff':>5} "
            + " ".join(f"{p:>9}" for p in phases)
            + f" {'halo B/step':>11} {'migr B/step':>11} {'msgs/step':>9} {'coll/step':>9}")
    print(head)
    for r in rows:
        n, steps_ = r["ranks"], r["steps"]
        per = r["per_rank"]
        phase = {p: max(x["phases"].get(p, 0.0) for x in per) / steps_ for p in phases}
        eff = _efficiency(r, rows[0], weak)
        rate = r["particles"] * steps_ / r["wall"] / n / 1e6
        halo_b = max(x["halo_bytes"] for x in per) / steps_
        mig_b = max(x["migration_bytes"] for x in per) / steps_
        # per rank and step, the busiest rank's (an interior rank of many has two neighbours)
        r["messages_per_step"] = max(x.get("messages", 0) for x in per) / steps_
        r["p2p_bytes_per_step"] = max(x.get("p2p_bytes", 0) for x in per) / steps_
        r["collectives_per_step"] = max(x.get("collectives", 0) for x in per) / steps_
        r["efficiency"] = eff
        r["kind"] = kind
        print(f"{n:>5} {r['particles']:>9} {r['wall'] / steps_:>8.4f} {rate:>10.2f} "
              f"{eff:>5.2f} " + " ".join(f"{phase[p]:>9.4f}" for p in phases)
              + f" {halo_b:>11.0f} {mig_b:>11.0f} {r['messages_per_step']:>9.1f}"
              f" {r['collectives_per_step']:>9.1f}")
    if weak:  # what weak scaling holds fixed: the particles each rank starts with
        for r in rows:
            print(f"{r['ranks']:>5} ranks: particles per rank at the start "
                  + ", ".join(str(x["start_particles"]) for x in r["per_rank"]))
    # each rank's own speed: unequal figures mean unequal cores (or cores slowing each
    # other), which no decomposition can hide
    for r in rows:
        speeds = [sum(x["phases"].get(p, 0.0) for p in compute) / max(x["particles"], 1)
                  / r["steps"] * 1e9 for x in r["per_rank"]]
        r["compute_ns_per_particle_step"] = speeds
        print(f"{r['ranks']:>5} ranks: {' + '.join(compute)} per particle-step on each rank: "
              + ", ".join(f"{v:.1f}" for v in speeds) + " ns")
    with open(os.path.join(out, "scaling.json"), "w") as fh:
        json.dump(rows, fh, indent=1)
    png = os.path.join(out, "scaling.png")
    plot(rows, rounds, png, f"{kind} scaling, {label}, {steps} steps, best of {repeat}", weak)
    print(f"written {os.path.join(out, 'scaling.json')} and {png}")
    return rows
