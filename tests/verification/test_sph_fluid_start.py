"""SPH fluid options for free-surface and coupled scenes (kernels/sph/integrate.py,
kernels/sph/rates.py, physics/sph/stage.py), each against its closed form:

* `sph.hydrostatic = true`: a Tait column starts at rest in the hydrostatic state,
  rho = rho0 (1 + (gamma-1)/gamma rho0 g z/kappa)^(1/(gamma-1)) at depth z below its top;
  then sigma_yy = -p(z) with p = kappa ((rho/rho0)^gamma - 1), exactly kappa ((1 +
  (gamma-1)/gamma rho0 g z/kappa)^(gamma/(gamma-1)) - 1), which is rho g z to first order.
  Without it the column of cases/sph_hydrostatic.toml drops by its compression and rings.
* the continuity density is advanced as log rho (predictor-corrector, RK3): positive for any
  step, equal to the linear update to first order.
* `sph.pressure_min`: a fluid's pressure is floored (0: no tension).
"""
from pathlib import Path

import numpy as np
from mpi4py import MPI

from pmpmsph import load_case_file
from pmpmsph.kernels.sph.integrate import advance
from pmpmsph.kernels.sph.views import sph_state, rates
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.simulation import Simulation

CASE = Path(__file__).resolve().parents[2] / "cases" / "sph_hydrostatic.toml"
KAPPA, GAMMA, RHO0, G, H = 140142.857, 7.0, 1000.0, 9.81, 1.0


def _column(**sets):
    overrides = [("sph.damping", 0.0), ("time.end", 0.3)] + list(sets.items())
    return Simulation(load_case_file(CASE, overrides=overrides),
                      dist=Distributor(MPI.COMM_SELF))


def _water(sim):
    p = sim.particles
    return (p["body"] == 0) & (p["method"] == 1)


def test_hydrostatic_start_is_the_tait_hydrostatic_state_and_stays_at_rest():
    sim = _column(**{"sph.hydrostatic": True})
    p, w = sim.particles, _water(sim)
    sim.sph.hydrostatic_start()     # done at set-up already: applying it again changes nothing
    sim.sph.stress(0.0, np.zeros((p.n_owned, 0)))
    top = H  # the column's top row sits half a spacing below y = 1
    z = top - p["x"][w, 1]
    u = 1.0 + (GAMMA - 1.0) / GAMMA * RHO0 * G * z / KAPPA
    assert np.allclose(p["rho"][w], RHO0 * u ** (1.0 / (GAMMA - 1.0)), rtol=1e-13)
    p_exact = KAPPA * (u ** (GAMMA / (GAMMA - 1.0)) - 1.0)
    assert np.allclose(-p["sigma"][w, 1, 1], p_exact, rtol=1e-10)
    y0 = p["x"][w, 1].copy()
    sim.run()
    # at rest below the surface rows (measured 1e-4 at y < 0.8; the top rows, where the
    # kernel is truncated, settle by 3e-3): the column seeded at rho0 instead sags by its
    # compression and rings (5.6e-3 at y < 0.8, 8e-3 at the top)
    deep = y0 < 0.8
    assert np.max(np.abs(p["x"][_water(sim), 1] - y0)[deep]) < 2e-4
    ref = _column()
    ref.run()
    assert np.max(np.abs(ref.particles["x"][_water(ref), 1] - y0)[deep]) > 4e-3


def test_log_density_update_stays_positive_and_is_first_order_linear():
    dim_tag = (0, 0)
    n = 2
    method = np.ones(n, np.int32)
    x, v, acc = np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2))
    F, L = np.tile(np.eye(3), (n, 1, 1)), np.zeros((n, 3, 3))
    rho = np.array([1000.0, 1000.0])
    drho = np.array([-3.0e5, -1.0])   # a splash (rate 300 / s) and a gentle one
    x0, v0, r0, F0 = x.copy(), v.copy(), rho.copy(), F.copy()
    dt = 1e-2
    advance(dim_tag, n, method, sph_state(x0, v0, r0, F0), sph_state(x, v, rho, F),
            rates(acc, drho, L), 1.0, 0.0, dt, False, False)
    assert np.allclose(rho, 1000.0 * np.exp(dt * drho / 1000.0), rtol=1e-14)
    assert rho[0] > 0.0                        # the linear update gives -2000
    assert abs(rho[1] - (1000.0 + dt * drho[1])) < 1e-7


def test_pressure_floor_removes_tension():
    sim = _column(**{"sph.pressure_min": 0.0})
    p, w = sim.particles, _water(sim)
    sim.step()
    p["rho"][w] = 990.0                          # expanded: Tait pressure < 0
    sim.sph.stress(0.0, np.zeros((p.n_owned, 0)))
    assert np.allclose(p["sigma"][w], 0.0, atol=1e-9)
    sim2 = _column()
    sim2.step()
    p2 = sim2.particles
    p2["rho"][_water(sim2)] = 990.0
    sim2.sph.stress(0.0, np.zeros((p2.n_owned, 0)))
    expect = KAPPA * ((0.99) ** GAMMA - 1.0)     # -9.3 kPa of tension without the floor
    assert np.allclose(-p2["sigma"][_water(sim2), 1, 1], expect, rtol=1e-12)


def test_hydrostatic_start_with_gamma_one_is_exponential():
    """gamma = 1 (p = kappa (rho/rho0 - 1)): dp/dz = rho g gives rho = rho0 exp(rho0 g z/kappa);
    the general formula's exponent 1/(gamma - 1) has no value there."""
    sim = _column(**{"sph.hydrostatic": True, "materials.water.gamma": 1.0})
    p, w = sim.particles, _water(sim)
    sim.sph.hydrostatic_start()
    z = H - p["x"][w, 1]
    assert np.allclose(p["rho"][w], RHO0 * np.exp(RHO0 * G * z / KAPPA), rtol=1e-13)
    assert p["rho"][w].max() > RHO0 * (1.0 + 0.5 * RHO0 * G * z.max() / KAPPA)
