"""Scene 16 (BENCHMARKS.md) in SPH: speed and arrival time of an elastic pulse, in a 1D bar
(c = sqrt(E/rho)) and in plane strain (c_p = sqrt((lambda + 2 mu)/rho)).

Set-up (Python Scene API; the MPM twin is test_wave_speed.py): linear elastic, E = 100,
rho = 1 (1D: c = 10; 2D: nu = 0.3, c_p = 11.602, against the plate speed 10.48 and the bar
speed 10), bar [0, 10] with free ends, square lattice, no artificial viscosity,
predictor-corrector at Courant number 0.2. SPH particles take no traction load, so the pulse is
an initial condition: a right-going sin^2 pulse of width 4 centred at x0 = 3, v = v0 sin^2(...)
with v0 = 0.01 c, and the matching strain F_xx = 1 - v/c (sigma = -rho c v, rho = rho0/F_xx).
Plane strain: a block [0, 10] x [0, 9] with v_y = 0 prescribed on every particle (the slip
walls of the MPM test: uniaxial strain), measured on the rows within 1 of the mid-height, which
the disturbance from the free lateral surfaces (carried inward at the shear speed 6.2) has not
reached.
Measured: the times at which the pulse peak passes the stations x = 4 and x = 8 (parabolic
fit through the sampled peak), front speed = 4 / (t_8 - t_4); and the time at which the free
end's velocity peaks (at 2 v0, the reflection), against (L - x0)/c.

The kernel matters, not only the spacing. On a lattice of spacing dp the SPH gradient of a
linear field is off by the sum rule G = -sum_j dp^d x_j^2 W'(r_j)/r_j (exactly 1 in the
continuum): the velocity gradient and the force both carry G, so long waves travel at G c.
For the cubic spline G = 1 at h = 1.0 and 2.0 dp in 1D, but G = 1.0224 at h = 1.3 dp (the
solver's default), and in 2D G = 0.9991 at h = 2 dp, 1.0105 at h = 1.3 dp. The error does not
fall with dp at a fixed h/dp. So the targets run at h = 2 dp; h = 1.3 dp is pinned by a
characterisation test.

Measured (this build), error of the front speed / of the free-end arrival:
  1D, h = 2 dp:   dp = 0.05: -0.18 % / +0.85 %;  dp = 0.025: -0.10 % / +0.40 %
                  (the arrival error is a boundary layer of O(h) at the free end)
  2D plane strain, h = 2 dp, dp = 0.05 (36,000 particles): -0.26 % / +0.89 %
  h = 1.3 dp:     1D +1.91 % / -1.47 % (dp = 0.05), +1.90 % / -1.74 % (dp = 0.025);
                  2D +1.06 % / -0.63 % (G - 1 = +1.05 %)
  A narrower pulse (width 2) at h = 2 dp, dp = 0.05 is slowed by dispersion: -2.5 %.
  Runtime: < 1 s per 1D case, ~15 s for the 2D case.
"""
import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph import Scene
from pmpmsph.kernels.sph.kernel_functions import kernel_dwdr
from pmpmsph.parallel.distributor import Distributor

E, NU, RHO, LENGTH = 100.0, 0.3, 1.0, 10.0
X0, WIDTH, AMP = 3.0, 4.0, 0.01
HEIGHT_2D = 9.0


def wave_speed(dim):
    if dim == 1:
        return np.sqrt(E / RHO)
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    return np.sqrt((lam + 2 * mu) / RHO)


def sum_rule(dim, h_factor, kern=0):
    """G = -sum_j dp^d x_j^2 W'(r_j)/r_j over a unit lattice (cubic spline: kern = 0)."""
    ax = np.arange(-8, 9, dtype=float)
    pts = np.stack(np.meshgrid(*([ax] * dim), indexing="ij"), -1).reshape(-1, dim)
    r = np.sqrt((pts ** 2).sum(axis=1))
    return -sum(p[0] ** 2 * kernel_dwdr(kern, dim, q, h_factor) / q
                for p, q in zip(pts, r) if q > 0)


def pulse_run(dim, dp, h_factor):
    c = wave_speed(dim)
    sc = Scene(dim, domain=dict(min=[-1.0] * dim,
                                max=[LENGTH + 2] + ([HEIGHT_2D + 1] if dim == 2 else [])),
               time=dict(end=(LENGTH - X0) / c + 0.15, cfl=0.2),
               sph=dict(h_factor=h_factor, integrator="predictor_corrector",
                        viscosity=dict(alpha=0.0, beta=0.0)),
               parallel=dict(balance_every=0))
    sc.material("bar", model="linear_elastic", E=E, nu=NU if dim == 2 else 0.0, rho=RHO)
    sc.body(name="bar", method="sph", material="bar", shape="box", min=[0.0] * dim,
            max=[LENGTH] + ([HEIGHT_2D] if dim == 2 else []), spacing=dp)
    if dim == 2:  # lateral motion blocked everywhere: uniaxial strain
        sc.data["prescribed"] = [dict(body="bar", velocity=["free", 0.0])]
    sim = sc.simulation(dist=Distributor(MPI.COMM_SELF))
    p = sim.particles
    n = p.n_owned
    assert sim.case.sph.h == pytest.approx(h_factor * dp)
    # a right-going pulse: v and the strain that goes with it (sigma = -rho c v)
    X = p["x"][:n, 0].copy()
    s = np.clip((X - X0) / WIDTH + 0.5, 0.0, 1.0)
    v = AMP * c * np.sin(np.pi * s) ** 2
    p["v"][:n, 0] = v
    p["F"][:n, 0, 0] = 1.0 - v / c
    p["rho"][:n] = RHO / p["F"][:n, 0, 0]
    sim.sph.evaluated = False  # stress and rates from this state
    gid = p["gid"][:n].copy()
    xg = np.empty((n, dim))
    xg[gid] = p["x"][:n]
    core = np.abs(xg[:, 1] - 0.5 * HEIGHT_2D) < 1.0 if dim == 2 else np.ones(n, bool)

    def station(xs):
        d = np.abs(xg[:, 0] - xs)
        return (d <= d.min() + 1e-9) & core

    stations = {4.0: station(4.0), 8.0: station(8.0), "end": station(LENGTH)}
    times, hist = [], {k: [] for k in stations}

    def watch(s_):
        q = s_.particles
        vg = np.empty(q.n_owned)
        vg[q["gid"][:q.n_owned]] = q["v"][:q.n_owned, 0]
        times.append(s_.time)
        for key, sel in stations.items():
            hist[key].append(vg[sel].mean())

    sim.run(on_step=watch)
    t = np.array(times)

    def peak(key):
        y = np.array(hist[key])
        i = int(np.argmax(y))
        assert 0 < i < len(y) - 1, f"no peak at station {key}"
        a, b, e = y[i - 1], y[i], y[i + 1]
        return t[i] + 0.5 * (a - e) / (a - 2 * b + e) * (t[i + 1] - t[i]), b

    t4, _ = peak(4.0)
    t8, _ = peak(8.0)
    t_end, v_end = peak("end")
    speed = 4.0 / (t8 - t4)
    arrival = (LENGTH - X0) / c
    out = dict(speed=speed / c - 1, arrival=t_end / arrival - 1, doubling=v_end / (2 * AMP * c),
               G=sum_rule(dim, h_factor), n=n)
    print(f"SPH scene 16, {dim}D, dp = {dp}, h = {h_factor} dp ({n} particles): front speed "
          f"{speed:.4f} vs c = {c:.4f} ({out['speed']:+.2%}; sum rule G - 1 = "
          f"{out['G'] - 1:+.2%}); free end peaks at t = {t_end:.4f} vs (L - x0)/c = "
          f"{arrival:.4f} ({out['arrival']:+.2%}) with v = {out['doubling']:.3f} x 2 v0")
    return out


@pytest.mark.parametrize("dim,dp,tol_speed,tol_arrival", [(1, 0.05, 0.005, 0.0125),
                                                          (1, 0.025, 0.005, 0.0075),
                                                          (2, 0.05, 0.005, 0.0125)])
def test_pulse_speed_and_arrival(dim, dp, tol_speed, tol_arrival):
    r = pulse_run(dim, dp, 2.0)
    assert abs(r["G"] - 1) < 1e-3
    assert abs(r["speed"]) < tol_speed
    assert abs(r["arrival"]) < tol_arrival
    # the reflection at the free end doubles the particle velocity
    assert r["doubling"] == pytest.approx(1.0, abs=0.02)


def test_default_smoothing_length_runs_fast_by_the_lattice_sum_rule():
    """Characterisation, not a target: at h = 1.3 dp (cubic spline) long waves travel at
    G c with G = 1.0224 in 1D, whatever the spacing; measured +1.9 %."""
    r = pulse_run(1, 0.05, 1.3)
    assert r["G"] == pytest.approx(1.0224, abs=1e-4)
    assert 0.015 < r["speed"] < r["G"] - 1 + 0.003
    assert -0.025 < r["arrival"] < -0.01
