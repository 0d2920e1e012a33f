"""Slabs, ghost nodes, migration and load balance on N ranks against one rank (DESIGN.md §4).

Run with `scripts/mpirun -n 2 (or 3) .venv/bin/python -m pytest -m mpi tests/parallel`.
Each test builds the one-rank reference in the same job on COMM_SELF; assertions are on
global quantities and do not depend on the number of ranks.
"""
import numpy as np
import pytest

from mpi_util import assert_equals_one_rank, gathered, rel_diff, serial, world
from pmpmsph.scene_api import Scene
from scenes import dam_break, loaded_bar, two_disks

pytestmark = pytest.mark.mpi


def test_ghost_node_sums_equal_the_serial_grid():
    dist = world()
    for shape in ("linear", "quadratic", "cubic"):
        sim = dam_break(shape=shape).simulation(dist=dist)
        ref = dam_break(shape=shape).simulation(dist=serial())
        for s in (sim, ref):
            s.run(max_steps=30)  # particles have moved, some across faces
        # same particle state, then one P2G on both
        sim.mpm._p2g(True)
        ref.mpm._p2g(True)
        g, rg = sim.mpm.grid, ref.mpm.grid
        lo, hi = sim.decomposition.owned_nodes()
        axis = sim.decomposition.axis
        owned = np.nonzero((g.global_index()[axis] >= lo) & (g.global_index()[axis] < hi))[0]
        flat_ref = np.ravel_multi_index(tuple(g.global_index()[:, owned]), rg.shape)
        for name in ("mass", "mom", "force"):
            mine = getattr(g, name)[:, owned]
            theirs = getattr(rg, name)[:, flat_ref]
            assert rel_diff(mine, theirs) < 1e-10, (shape, name)
        # ghosts receive the owners' values after the grid update
        sim.mpm._solve(sim.dt, sim.time, True)
        ref.mpm._solve(ref.dt, ref.time, True)
        every = np.ravel_multi_index(tuple(g.global_index()), rg.shape)
        assert rel_diff(g.vel[0], rg.vel[0, every]) < 1e-10, shape


@pytest.mark.parametrize("thin", [False, True])
def test_ghost_nodes_hold_the_owners_values_bit_for_bit(thin):
    """`GridHalo.sum` gives owners and ghost holders the same nodal sums, and the node-local
    grid update then the same velocities, with no broadcast: every node held by two ranks
    has equal mass, momentum, velocity and increment on both, exactly. `thin` (3 or more
    ranks) makes an interior slab thinner than two ghost widths, where a node is held by
    three ranks and `sum` takes the reduce-and-broadcast path instead; the result must be
    the same."""
    dist = world()
    sim = dam_break(barrier=True).simulation(dist=dist)
    sim.run(max_steps=30)
    dec = sim.decomposition
    if thin and dist.size >= 3:
        faces = dec.faces.copy()
        faces[2] = faces[1] + dec.ghost  # the second slab: one ghost width thick
        sim.rebalance(force_faces=faces)
        dec = sim.decomposition
    assert sim.mpm.halo.pairwise == (not thin or dist.size < 3)
    sim.mpm._p2g(True)
    sim.mpm._solve(sim.dt, sim.time, True)
    g = sim.mpm.grid
    gidx = g.global_index()
    key = gidx[0] * 100_000 + gidx[1]
    rows = np.concatenate([g.mass.T, g.mom[0], g.vel[0], g.dv[0]], axis=1)
    keys = np.concatenate(dist.allgather(key))
    vals = np.concatenate(dist.allgather(rows))
    order = np.argsort(keys, kind="stable")
    keys, vals = keys[order], vals[order]
    dup = np.nonzero(keys[1:] == keys[:-1])[0]
    assert len(dup) > 0  # nodes are shared
    assert np.array_equal(vals[dup], vals[dup + 1])
    # and the values are the serial grid's
    ref = dam_break(barrier=True).simulation(dist=serial())
    ref.run(max_steps=30)
    ref.mpm._p2g(True)
    ref.mpm._solve(ref.dt, ref.time, True)
    every = np.ravel_multi_index(tuple(gidx), ref.mpm.grid.shape)
    assert rel_diff(g.vel[0], ref.mpm.grid.vel[0, every]) < 1e-10


@pytest.mark.parametrize("axis", ["x", "y"])
def test_trimmed_grid_on_n_ranks_equals_one_rank(axis):
    """`Grid.work_range` on slabs (forced on: these grids are below `TRIM_MIN_NODES`): along
    x each rank resets and solves only its particles' layers and the layers it shares with
    its neighbours; along y (not axis 0) every node. 200 steps of the dam break equal the
    one-rank state to 1e-10 while the front runs across the faces."""
    dist = world()
    scene = dam_break()
    scene.set("parallel.axis", axis)
    sim = scene.simulation(dist=dist)
    ref = dam_break().simulation(dist=serial())
    for s in (sim, ref):
        s.mpm._trim = True
    sim.run(max_steps=200)
    ref.run(max_steps=200)
    mine = gathered(dist, sim, ["x", "v"])
    p = ref.particles
    order = np.argsort(p["gid"])
    for name in ("x", "v"):
        assert rel_diff(mine[name], p[name][order]) < 1e-10, name
    a, b = ref.mpm._span
    assert b - a < ref.mpm.grid.n_nodes  # the one-rank grid did trim


def test_migration_conserves_count_mass_momentum_and_gids():
    dist = world()
    sim = dam_break().simulation(dist=dist)
    ref = dam_break().simulation(dist=serial())
    gids0 = np.sort(np.concatenate(dist.allgather(sim.particles["gid"].copy())))
    for _ in range(6):  # 600 steps: the front runs across the slab faces
        sim.run(max_steps=100)
        ref.run(max_steps=100)
        d, r = sim.diagnostics(), ref.diagnostics()
        assert d["mass"] == pytest.approx(r["mass"], rel=1e-12)
        assert d["px"] == pytest.approx(r["px"], rel=1e-8, abs=1e-9 * abs(r["py"]))
        assert d["py"] == pytest.approx(r["py"], rel=1e-8)
        gids = np.sort(np.concatenate(dist.allgather(sim.particles["gid"].copy())))
        assert np.array_equal(gids, gids0)
    assert dist.sum(sim.migrated) > 0  # particles did cross faces


@pytest.mark.parametrize("scene,kwargs", [(two_disks, {}), (two_disks, {"contact": "multi"}),
                                          (dam_break, {}), (dam_break, {"shape": "cubic",
                                                                         "transfer": "musl"}),
                                          (loaded_bar, {}),
                                          (loaded_bar, {"shape": "cpdi", "transfer": "musl"}),
                                          (dam_break, {"velocity_update": "apic"}),
                                          (dam_break, {"velocity_update": "mls",
                                                       "shape": "cubic"}),
                                          (loaded_bar, {"velocity_update": "apic",
                                                        "transfer": "musl"}),
                                          (dam_break, {"balance_every": 20,
                                                       "balance_by": "time",
                                                       "balance_threshold": 0.03})])
def test_state_after_200_steps_equals_one_rank(scene, kwargs):
    dist = world()
    sim = scene(**kwargs).simulation(dist=dist)
    ref = scene(**kwargs).simulation(dist=serial())
    sim.run(max_steps=200)
    ref.run(max_steps=200)
    names = ["x", "v", "F" if "F" in ref.particles else "J", "sigma"]  # fluids store J
    names += ["C"] if "C" in ref.particles else []  # APIC / MLS
    assert_equals_one_rank(dist, sim, ref, names)


def test_load_balancer_reduces_imbalance_and_holds_still():
    dist = world()
    from pmpmsph import Scene

    # a resting block in the left quarter of a long box: equal slabs are badly unbalanced
    sc = Scene(2, grid=dict(origin=[0, 0], length=[4, 1], cells=[40, 10]),
               time=dict(end=10.0, dt=1e-4), mpm=dict(shape="quadratic"),
               parallel=dict(axis="x", balance_every=10, balance_threshold=0.1))
    sc.material("rubber", model="neo_hookean", E=1e5, nu=0.3, rho=1000.0)
    sc.body(name="block", material="rubber", shape="box", min=[0.0, 0.0], max=[1.0, 1.0],
            ppc=2)
    sim = sc.simulation(dist=dist)  # seeded on equal slabs, balanced before step 1
    moved = list(sim.balancer.history)
    assert len(moved) == 1 and moved[0][0] == 0
    _, before, after, faces = moved[0]
    assert before > 0.5 and after < 0.5 * before
    equal = sim.decomposition.with_faces(
        np.round(np.linspace(0, 40, dist.size + 1)).astype(np.int64))
    x_all = np.concatenate(dist.allgather(sim.particles["x"].copy()))
    counts0 = np.bincount(equal.owner(x_all), minlength=dist.size)  # equal slabs' counts
    counts1 = dist.gather_counts(sim.particles.n_owned)
    imbalance = lambda c: c.max() / c.mean() - 1.0  # noqa: E731
    assert imbalance(counts1) < 0.5 * imbalance(counts0)
    assert counts1.sum() == counts0.sum() == 400
    sim.run(max_steps=100)  # ten checks: nothing moves
    assert len(sim.balancer.history) == 1
    assert list(sim.decomposition.faces) == faces


@pytest.mark.parametrize("axis", ["y", "x"])
def test_periodic_grid_on_n_ranks_equals_one_rank(axis):
    """An MPM grid periodic along x: a water column on the floor, thrown along x, slumps
    across the slab faces and flows through the periodic end. Slabs cut along y: the wrap
    is inside every rank (`Grid.fold_periodic` on every local grid, ghosts included); cut
    along x: the first and last slabs share ghost nodes across the wrap
    (`Decomposition.grid_neighbours`), particles migrate across it."""
    def scene():
        sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[24, 24],
                                periodic=["x"]),
                   time=dict(end=1e9, cfl=0.3), gravity=[0, -9.81],
                   mpm=dict(shape="quadratic", transfer="usl", velocity_update="apic"),
                   parallel=dict(axis=axis, balance_every=0))
        sc.material("water", model="tait", rho=1000.0, kappa=2e5, gamma=7.0, mu=0.01)
        sc.body(name="w", material="water", shape="box", min=[0.5, 0.0], max=[0.9, 0.7],
                ppc=2, velocity=[1.5, 0.0])
        sc.boundary(face="y-", type="slip")
        sc.boundary(face="y+", type="slip")
        return sc

    dist = world()
    sim = scene().simulation(dist=dist)
    ref = scene().simulation(dist=serial())
    # (migration is lazy: a particle moves to its owner once it strays most of a cell past
    # its slab face, which the slump across the y faces does after about 350 steps)
    sim.run(max_steps=400)
    ref.run(max_steps=400)
    assert dist.sum(sim.migrated) > 0
    assert ref.particles["x"][:, 0].min() < 0.3  # some crossed the end at x = 1
    assert_equals_one_rank(dist, sim, ref, ["x", "v", "J", "sigma", "C"])


@pytest.mark.parametrize("axis", ["y", "x"])
def test_periodic_coupled_scene_on_n_ranks_equals_one_rank(axis):
    """The coupled piston (bench/scenes.py `coupled_piston`: SPH water under an MPM ice
    layer, both periodic along x with the grid) moving along the period. Slabs cut along
    y: the water and the layer cross the slab faces as the layer bobs, and the seam is
    within every rank (SPH images, the grid's fold, both wraps). Cut along x: the seam runs
    between the first and last ranks (SPH halo rows shifted by the period, ghost nodes
    shared across the wrap), and every particle crosses it (a period of 6 cells per rank)."""
    from pmpmsph.bench.scenes import coupled_piston

    dist = world()
    period = 0.2 if axis == "y" else 0.12 * max(dist.size, 2)
    args = dict(spacing=0.01, end=0.1 if axis == "y" else 0.15, velocity=[1.0, 0.0],
                period=period, axis=axis)
    sim = coupled_piston(**args).simulation(dist=dist)
    ref = coupled_piston(**args).simulation(dist=serial())
    sim.run()
    ref.run()
    assert abs(sim.time - ref.time) < 1e-12 and sim.time > 0.099
    if axis == "x":
        assert dist.sum(sim.migrated) > 0
    assert_equals_one_rank(dist, sim, ref, ["x", "v", "rho", "sigma"])
