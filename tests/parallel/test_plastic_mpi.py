"""The plasticity models on N ranks equal one rank (DESIGN.md §4 invariant, issue 21): a
granular column (Drucker-Prager, friction floor) collapsing in 3D with MPM and in 2D with
updated-Lagrangian SPH, the slab faces balanced into the column so that the spreading
material and its plastic state (be, alpha, the flag, Fn) migrate and travel in the halo."""
import pytest

from mpi_util import assert_equals_one_rank, serial, world
from pmpmsph.scene_api import Scene

pytestmark = pytest.mark.mpi

FIELDS = ("x", "v", "sigma", "F", "mstate")
SAND = dict(model="drucker_prager", E=2e6, nu=0.3, rho=1500.0, friction_angle=30.0)


def column_3d(fbar=False):
    """A 4 x 8 x 6 cm column on a friction floor between slip walls in z (MPM, GIMP, APIC;
    `fbar`: F-bar, whose nodal averages are summed over the ranks like every nodal sum)."""
    sc = Scene(3, time=dict(end=1.0, cfl=0.5), gravity=[0.0, -9.81, 0.0],
               grid=dict(origin=[0.0, 0.0, 0.0], cell_size=0.01, cells=[16, 10, 6]),
               mpm=dict(shape="gimp", transfer="usl", velocity_update="apic", fbar=fbar),
               parallel=dict(axis="x", balance_every=20),
               boundaries=[dict(face="x-", type="slip"), dict(face="z-", type="slip"),
                           dict(face="z+", type="slip"),
                           dict(face="y-", type="friction", friction=0.5774)])
    sc.material("sand", **SAND)
    sc.body(name="column", material="sand", shape="box", min=[0.0, 0.0, 0.0],
            max=[0.04, 0.08, 0.06], ppc=2)
    return sc


def column_sph():
    """The column in 2D SPH: a held layer of sand as the floor and the wall at x = 0."""
    sc = Scene(2, time=dict(end=1.0, cfl=0.3), gravity=[0.0, -9.81],
               domain=dict(min=[-0.02, -0.02], max=[0.2, 0.1]),
               parallel=dict(axis="x", balance_every=20),
               prescribed=[dict(body="sand", box=dict(min=[-1.0, -1.0], max=[1.0, 0.0]),
                                velocity=[0.0, 0.0]),
                           dict(body="sand", box=dict(min=[-1.0, 0.0], max=[0.0, 1.0]),
                                velocity=[0.0, "free"])])
    sc.material("sand", **SAND)
    sc.body(name="sand", material="sand", shape="box", min=[-0.0075, -0.0075],
            max=[0.04, 0.08], spacing=0.0025, method="sph")
    return sc


def column_3d_fbar():
    return column_3d(fbar=True)


@pytest.mark.parametrize("make, steps", [(column_3d, 900), (column_3d_fbar, 900),
                                         (column_sph, 2500)],
                         ids=["mpm_3d", "mpm_3d_fbar", "sph_2d"])
def test_collapsing_column_equals_one_rank(make, steps):
    dist = world()
    sim = make().simulation(dist=dist)
    ref = make().simulation(dist=serial())
    start = sim.particles.n_owned
    for s in (sim, ref):
        s.run(max_steps=steps)
    assert ref.particles["mstate"][:, 6].max() > 0.01  # it flowed plastically
    assert dist.sum(abs(sim.particles.n_owned - start)) > 0  # and rows changed rank
    assert_equals_one_rank(dist, sim, ref, FIELDS, exact=("mat",))
