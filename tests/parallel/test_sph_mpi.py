"""SPH on N ranks equals SPH on one rank (DESIGN.md §4 invariant), to 1e-10 relative.

Run under `mpirun -n 2` and `-n 3`; the serial reference runs on MPI.COMM_SELF in the same
processes. Scenes: the copper bar of scene 8 (1D, all three integrators), the dam break
with dummy walls (2D, slab faces crossed by water and walls), and the rubber rings
(artificial stress).
"""
import numpy as np
import pytest

from mpi_util import assert_equals_one_rank, serial, world
from pmpmsph.bench.scenes import sph_cavity, sph_couette
from pmpmsph.errors import RunError
from scenes import sph_bar_1d, sph_block_on_walls, sph_dam_break

pytestmark = pytest.mark.mpi

FIELDS = ("x", "v", "rho", "sigma", "F")


def _bar_velocity(sim):
    x = sim.particles["x"][:, 0]
    sim.particles["v"][:, 0] = 0.01 * np.sqrt(128e9 / 8790.0) * np.sin(10 * np.pi * x)


def _compare(dist, sim, ref):
    assert_equals_one_rank(dist, sim, ref, FIELDS)


@pytest.mark.parametrize("integrator", ["verlet", "predictor_corrector", "rk3"])
def test_sph_bar_equals_one_rank(integrator):
    dist = world()
    sim = sph_bar_1d(integrator).simulation(dist=dist)
    ref = sph_bar_1d(integrator).simulation(dist=serial())
    _bar_velocity(sim)
    _bar_velocity(ref)
    sim.run(max_steps=300)
    ref.run(max_steps=300)
    _compare(dist, sim, ref)


@pytest.mark.parametrize("walls,balance,axis", [("slip", 0, "y"), ("no_slip", 25, "x")])
def test_sph_dam_break_equals_one_rank(walls, balance, axis):
    dist = world()
    sim = sph_dam_break(walls=walls, balance_every=balance, axis=axis).simulation(dist=dist)
    ref = sph_dam_break(walls=walls).simulation(dist=serial())
    sim.run(max_steps=1000)
    ref.run(max_steps=1000)
    assert dist.sum(sim.migrated) > 0
    _compare(dist, sim, ref)


def _on_both(scene, steps):
    """The scene run `steps` steps on all ranks and on one; returns (dist, sim, ref)."""
    dist = world()
    sim = scene().simulation(dist=dist)
    ref = scene().simulation(dist=serial())
    sim.run(max_steps=steps)
    ref.run(max_steps=steps)
    return dist, sim, ref


def test_sph_cavity_equals_one_rank():
    """The lid-driven cavity: walls with a velocity, Morris viscosity, delta-SPH."""
    def scene():
        sc = sph_cavity(n=20, end=1.0)
        sc.data["parallel"] = dict(axis="x", balance_every=25)
        return sc

    _compare(*_on_both(scene, 300))


def test_sph_moving_wall_equals_one_rank():
    """A wall body that moves with its velocity across the slab faces (bodies[].moving)."""
    def scene():
        sc = sph_cavity(n=20, end=1.0)
        sc.data["parallel"] = dict(axis="x", balance_every=0)
        sc.data["domain"]["max"][0] = 2.0
        sc.data["bodies"][-1]["moving"] = True  # the lid slides off to the right
        return sc

    dist, sim, ref = _on_both(scene, 300)
    assert dist.sum(sim.migrated) > 0
    _compare(dist, sim, ref)


def test_sph_periodic_couette_equals_one_rank():
    """Periodic along x (images inside each rank), slabs cut along y across the layer."""
    dist, sim, ref = _on_both(lambda: sph_couette(n=20, end=1.0), 300)
    assert sim.decomposition.axis == 1
    _compare(dist, sim, ref)


def test_sph_periodic_slab_axis_equals_one_rank():
    """Periodic along x and the slabs cut along x too: the first and last ranks are
    neighbours across the wrap (on two ranks both faces lead to the other rank), halo rows
    arrive shifted by the period and the fluid near the lid migrates across the wrap."""
    def scene():
        sc = sph_couette(n=20, end=1.0, periods=48)
        sc.data["parallel"] = dict(axis="x", balance_every=0)
        sc.data["bodies"][0]["velocity"] = [0.5, 0.0]  # the whole layer drifts along x
        return sc

    dist, sim, ref = _on_both(scene, 300)
    assert sim.decomposition.axis == 0 and sim.decomposition.period == pytest.approx(2.4)
    assert dist.sum(sim.migrated) > 0
    _compare(dist, sim, ref)


def test_sph_dam_break_with_shifting_and_viscosity_equals_one_rank():
    """delta-SPH (on by default), particle shifting and the Morris viscosity with no-slip
    walls: the same state on any number of ranks."""
    def scene():
        sc = sph_dam_break(walls="no_slip", balance_every=25, axis="x")
        sc.data["sph"]["shifting"] = 2.0
        sc.data["materials"]["water"]["mu"] = 1.0
        return sc

    _compare(*_on_both(scene, 600))


@pytest.mark.parametrize("kw", [dict(), dict(force="reference", integrator="verlet"),
                                dict(eta=0.2, integrator="predictor_corrector"),
                                dict(deformation="rate")])
def test_tl_plate_equals_one_rank(kw):
    from scenes import shear_velocity, tl_plate

    dist = world()
    sim = tl_plate(n=11, **kw).simulation(dist=dist)
    ref = tl_plate(n=11, **kw).simulation(dist=serial())
    shear_velocity(sim)
    shear_velocity(ref)
    sim.run(max_steps=60)
    ref.run(max_steps=60)
    assert dist.sum(sim.migrated) > 0
    _compare(dist, sim, ref)


def test_a_particle_skipping_a_slab_stops_every_rank():
    """A particle that would skip a whole slab in one step stops the run on every rank with
    its gid (no rank left waiting in the exchange). The flag rides on the step's one
    allreduce (`Simulation._step_check`); three ranks or more are needed for a slab between."""
    dist = world()
    if dist.size < 3:
        pytest.skip("needs a slab between two others")
    sim = sph_bar_1d("verlet").simulation(dist=dist)
    sim.run(max_steps=5)
    dec = sim.decomposition
    gid = -1
    if dist.rank == 0:  # one of rank 0's particles into the last slab
        far = dec.origin + (dec.faces[-2] + 0.5) * dec.dx
        sim.particles["x"][0, 0] = far
        gid = int(sim.particles["gid"][0])
    gid = dist.bcast(gid)
    with pytest.raises(RunError, match="jumped over a whole slab") as err:
        sim.step()
    if dist.rank == 0:
        assert err.value.gid == gid


def test_sph_block_on_walls_equals_one_rank():
    """The contact walls (kernels/sph/contact.py: the gaps to wall cells found over the
    halo's wall rows, the push and the Coulomb friction) are rank-invariant: a block
    sliding down a rough incline (mu = 0.3), cut by the slab faces."""
    dist, sim, ref = _on_both(sph_block_on_walls, 600)
    block = sim.particles["body"][: sim.particles.n_owned] == 0
    assert dist.size == 1 or dist.min(int(block.sum())) > 0  # (the block is cut)
    _compare(dist, sim, ref)
