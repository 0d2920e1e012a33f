"""A cantilever held by a mirror clamp (`[[prescribed]] mirror`), total-Lagrangian and
updated-Lagrangian (with Liu's corrected kernel), on N ranks equals one rank (DESIGN.md §4
invariant), to 1e-10 relative. On 2 ranks the slab face is the clamp face, so every ghost
and its partner live on different ranks: the partners' displacements (and velocities) and
the ghosts' forces cross between them. Run under mpirun."""
import numpy as np
import pytest
from mpi_util import assert_equals_one_rank, serial, world

from pmpmsph import Scene
from pmpmsph.bench.plate_fsi import water_on_plate

pytestmark = pytest.mark.mpi


def _cantilever(formulation):
    """0.5 long, 0.1 thick (4 particles through), clamped over x < 0, sagging under gravity
    and swinging from v_y = -0.2 (x / 0.5)^2."""
    sc = Scene(2, domain=dict(min=[-0.5, -0.4], max=[0.5, 0.3]), gravity=[0.0, -9.81],
               time=dict(end=1.0, cfl=0.3),
               sph=dict(formulation=formulation, integrator="rk3")
               if formulation == "total" else
               dict(formulation=formulation, integrator="verlet", correction="liu"),
               parallel=dict(axis="x", balance_every=0))
    sc.material("rubber", model="neo_hookean", E=1.0e6, nu=0.3, rho=1000.0)
    sc.body(name="beam", method="sph", material="rubber", shape="box", min=[-0.1, 0.0],
            max=[0.5, 0.1], spacing=0.025)
    sc.data["prescribed"] = [dict(body="beam", box=dict(min=[-0.2, -0.1], max=[0.0, 0.2]),
                                  velocity=[0.0, 0.0], mirror="x+")]
    return sc


def _run(dist, formulation, steps=120):
    sim = _cantilever(formulation).simulation(dist=dist)
    x = sim.particles["x"]
    sim.particles["v"][:, 1] = np.where(x[:, 0] > 0, -0.2 * (x[:, 0] / 0.5) ** 2, 0.0)
    sim.run(max_steps=steps)
    return sim


@pytest.mark.parametrize("formulation", ["total", "updated"])
def test_mirror_clamp_equals_one_rank(formulation):
    dist = world()
    sim, ref = _run(dist, formulation), _run(serial(), formulation)
    assert_equals_one_rank(dist, sim, ref, ("x", "v", "F"))
    p = ref.particles
    free = p["X0"][:, 0] > 0
    assert np.abs(p["v"][free, 1]).max() > 0.05   # it moved
    assert np.all(p["x"][~free] == p["X0"][~free])  # the clamp did not


def _plate_under_water(dist, steps=150):
    """The updated plate under SPH water of bench/plate_fsi.py (Liu's kernel, mirror clamps,
    the quadratic-fit hourglass control, whose coefficients cross the slab face in the
    halo; held rows take no force from the water), spacing 0.01."""
    sc, _ = water_on_plate("sph_sph", spacing=0.01, end=1.0)
    assert sc.data["sph"]["hourglass_fit"] == "quadratic"
    sim = sc.simulation(dist=dist, write_output=False)
    sim.run(max_steps=steps)
    return sim


def test_updated_plate_under_water_equals_one_rank():
    dist = world()
    sim, ref = _plate_under_water(dist), _plate_under_water(serial())
    assert_equals_one_rank(dist, sim, ref, ("x", "v", "F"))
    p = ref.particles
    plate = p["body"] == 1
    assert p["v"][plate, 1].min() < -0.01   # it is sagging
