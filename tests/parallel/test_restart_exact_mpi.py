"""A restart reproduces the uninterrupted run (issue 17, item 3; DESIGN.md §6): every scene
kind runs N steps uninterrupted on all ranks; the same scene runs K steps, writes a
checkpoint, and is restored on all ranks (the same rank count) and on one rank (another
rank count), then runs the other N - K steps; x and v equal the uninterrupted run's to 1e-10
relative (sorted by gid). Scenes: MPM (two disks, USL), SPH fluid with each integrator
(the dam break with dummy walls, delta-SPH, and with shifting and viscosity), total-Lagrangian
SPH (the sheared plate), coupled MPM-SPH with the seed's interface and the conservative one.

What it caught: a restart re-evaluated the SPH rates at the restored state, where the step
after the checkpoint starts from the last evaluation's (at mid-step for the
predictor-corrector), and chose a new CFL time step from a state without those rates; a
coupled float (SPH water, predictor-corrector, MPM block) drifted by 1.5e-5 relative in v
within 50 steps. `SPHStage.resume` and the stored dt make it bit for bit on one rank.
"""
import numpy as np
import pytest

from mpi_util import assert_equals_one_rank, gathered, serial, world
from scenes import coupled_bar_1d, shear_velocity, sph_dam_break, tl_plate, two_disks

pytestmark = [pytest.mark.mpi, pytest.mark.timeout(300)]


def _wave(sim, k=1):
    x = sim.particles["x"][:, 0]
    sim.particles["v"][:, 0] = 0.01 * np.sqrt(128e9 / 8790.0) * np.sin(k * np.pi * x)


def _dam(integrator, extra=None):
    def build():
        sc = sph_dam_break(dx=0.1, integrator=integrator, walls="no_slip", axis="x",
                           balance_every=20)
        for key, value in (extra or {}).items():
            section, name = key.split(".")
            sc.data[section][name] = value
        return sc
    return build, None


def _coupled(interface):
    def build():
        sc = coupled_bar_1d(integrator="verlet")
        sc.data["coupling"] = dict(interface=interface)
        return sc
    return build, _wave


SCENES = {
    "mpm": (lambda: two_disks(spacing=0.04, cells=10), None),
    "sph_verlet": _dam("verlet"),
    "sph_pc": _dam("predictor_corrector"),
    "sph_rk3": _dam("rk3"),
    "sph_pc_shifting_viscous": _dam("predictor_corrector",
                                    {"sph.shifting": 2.0, "sph.density_diffusion": 0.1}),
    "tlsph": (lambda: tl_plate(n=11), shear_velocity),
    "coupled_seed": _coupled("seed"),
    "coupled_conservative": _coupled("conservative"),
}
N, K = 60, 25


@pytest.mark.parametrize("kind", sorted(SCENES))
def test_restart_continues_the_run_exactly(kind, shared_dir):
    dist = world()
    build, init = SCENES[kind]

    def start(d):
        sim = build().simulation(dist=d)
        if init is not None:
            init(sim)
        return sim

    whole = start(dist)
    whole.run(max_steps=N)
    first = start(dist)
    first.run(max_steps=K)
    path = dist.bcast(f"{shared_dir}/{kind}.h5")
    first.case_overrides, first.case_dir = (), None
    first.write_checkpoint(path)
    # the same rank count
    again = build().simulation(dist=dist)
    again.restore_checkpoint(path)
    again.run(max_steps=N - K)
    assert again.step_count == whole.step_count and again.time == whole.time
    assert_equals_one_rank(dist, again, _serial_copy(whole, dist), ("x", "v"))
    # one rank
    alone = build().simulation(dist=serial())
    alone.restore_checkpoint(path)
    alone.run(max_steps=N - K)
    assert alone.step_count == whole.step_count
    assert abs(alone.time - whole.time) <= 1e-14 * whole.time
    assert_equals_one_rank(dist, whole, alone, ("x", "v"))


class _serial_copy:
    """`whole`'s particles gathered onto every rank, in the shape assert_equals_one_rank
    reads a one-rank run in (`.particles[name]`)."""

    def __init__(self, sim, dist):
        self.particles = gathered(dist, sim, ("x", "v"))
