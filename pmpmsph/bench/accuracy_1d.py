"""Accuracy-bench studies of the 1D scenes 1, 8, 9 and 14 (BENCHMARKS.md).

Each study names its error metric and reference, the resolution knob (`knob` = particle
spacing relative to the scene's base spacing; time steps shrink with it, Courant number
fixed), the methods that apply and those that do not (with the reason), and a `run(dist,
method, level, quick)` returning (simulation, seconds in steps, {"error", "aux"}).
"""
import numpy as np

from ..simulation import Simulation
from .accuracy_core import advance, gathered, masked_sum, steps_for
from ..scene_api import Scene
from .scenes import (BAR_E, BAR_L, BAR_RHO, BAR_V0, coupled_bar_1d, mode_velocity,
                     sph_bar_1d, spring_case, stress_bar, vibrating_bar_case)

SHAPES = ("linear", "gimp", "quadratic", "cubic")
TRANSFERS = ("usl", "usf", "musl")


def mpm_methods(shapes=SHAPES, transfers=TRANSFERS):
    """One method per MPM shape function and transfer scheme."""
    return [dict(label=f"MPM {s} {t}", family="MPM", shape=s, transfer=t)
            for s in shapes for t in transfers]


# -- scene 1: spring under self-weight ------------------------------------------------------
U_SPRING = 9.81 * 1500.0 * 0.2**2 / (2 * 1.0e5)  # g rho l0^2 / (2 E) = 2.943e-3, thesis eq. 87


def run_spring(dist, m, k, quick):
    sim = Simulation(spring_case(k, m["shape"], m["transfer"]), dist=dist)
    x0 = gathered(sim, ["x"])["x"][:, 0]
    tip = int(np.argmax(x0))
    secs = advance(sim, 2.0)
    u = gathered(sim, ["x"])["x"][tip, 0] - x0[tip]
    return sim, secs, {"error": abs(u / U_SPRING - 1.0), "aux": u}


SPRING = dict(
    key="spring", scene=1, title="Scene 1: spring under self-weight (1D)",
    metric="|u_tip / (g rho l0^2 / 2E) - 1| at t = 2 (closed form 2.943e-3)",
    aux="u_tip", knob="particle spacing / 0.02 (10 k particles, 21 k cells, dt = 1e-4 / k)",
    methods=mpm_methods(), levels={"full": [1, 2, 4, 8], "quick": [1, 2]},
    knob_of=lambda k: 1.0 / k, run=run_spring,
    not_applicable={"SPH UL, SPH TL, coupled": "the spring hangs from a fixed end; SPH "
                    "solids have no displacement boundary (dummy walls are for fluids)"})


# -- scene 14: vibrating bar ------------------------------------------------------------------
BETA = np.pi / (2 * BAR_L)
OMEGA = BETA * np.sqrt(BAR_E / BAR_RHO)
V_CM = 2 * BAR_V0 / np.pi  # amplitude of the centre-of-mass velocity, v0 (1 - cos bL) / bL


def _bar_sph(k, end, h_factor):
    """The free-free bar [-L, L] in UL SPH: its first mode is v0 sin(beta x), odd about
    x = 0, which therefore stays fixed; the half x > 0 is the fixed-free bar of scene 14."""
    s = 0.5 / k
    sc = Scene(1, domain=dict(min=[-BAR_L - 2], max=[BAR_L + 2]),
               time=dict(end=end, dt=0.01 / k),
               sph=dict(h_factor=h_factor, integrator="verlet",
                        viscosity=dict(alpha=0.0, beta=0.0)),
               parallel=dict(balance_every=0))
    sc.material("bar", model="linear_elastic", E=BAR_E, nu=0.0, rho=BAR_RHO)
    sc.body(name="bar", method="sph", material="bar", shape="box", min=[-BAR_L], max=[BAR_L],
            spacing=s)
    return sc


def _bar_coupled(k, end):
    """Fixed end in MPM (GIMP, MUSL) on [0, 5], the rest of the bar SPH (Verlet)."""
    h = 1.0 / k
    sc = Scene(1, grid=dict(origin=[0.0], cell_size=h, cells=[27 * k]),
               time=dict(end=end, dt=0.01 * h), mpm=dict(shape="gimp", transfer="musl"),
               sph=dict(integrator="verlet", viscosity=dict(alpha=0.0, beta=0.0)),
               parallel=dict(balance_every=0))
    sc.material("bar", model="linear_elastic", E=BAR_E, nu=0.0, rho=BAR_RHO)
    sc.body(name="bar", material="bar", shape="box", min=[0.0], max=[BAR_L], ppc=2)
    sc.boundary(face="x-", type="fixed")
    sc.data["regions"] = [dict(method="sph", shape="box", min=[5.0], max=[27.0])]
    return sc


def run_bar(dist, m, k, quick):
    end = 10.0 if quick else 20.0
    if m["family"] == "MPM":
        sim = Simulation(vibrating_bar_case(k, m["shape"], m["transfer"], end), dist=dist)
    elif m["family"] == "SPH UL":
        sim = _bar_sph(k, end, m["h_factor"]).simulation(dist=dist)
    else:
        sim = _bar_coupled(k, end).simulation(dist=dist)
    mode_velocity(sim)
    if sim.sph is not None:
        sim.sph.evaluated = False
    right = sim.particles["x"][:, 0] > 0.0  # the fixed-free half (all of it but for SPH)
    mass = masked_sum(sim, sim.particles["mass"][right])
    worst = [0.0]

    def track(s):
        p = s.particles
        half = p["x"][:, 0] > 0.0
        vcm = masked_sum(s, p["mass"][half] * p["v"][half, 0]) / mass
        worst[0] = max(worst[0], abs(vcm - V_CM * np.cos(OMEGA * s.time)))

    secs = advance(sim, end, track)
    return sim, secs, {"error": worst[0] / V_CM, "aux": np.nan}


BAR = dict(
    key="vibrating_bar", scene=14, title="Scene 14: vibrating bar, first mode (1D)",
    metric="max_t |v_cm - (2 v0/pi) cos(omega t)| / (2 v0/pi) over two periods (one in --quick)",
    aux="", knob="cell size (MPM; SPH spacing / 0.5) with 2 particles per cell, dt = 0.01 h",
    methods=mpm_methods() + [dict(label=f"SPH UL verlet h={f}s", family="SPH UL", h_factor=f)
                             for f in (1.3, 2.0)]
    + [dict(label="coupled gimp musl + SPH verlet", family="coupled")],
    levels={"full": [1, 2, 4, 8], "quick": [1, 2, 4]}, knob_of=lambda k: 1.0 / k,
    run=run_bar,
    not_applicable={"SPH TL": "1D total-Lagrangian SPH is not offered (TL-SPH is 2D/3D)"})


# -- scene 8: reversal and energy of the copper bar -----------------------------------------
C_CU = np.sqrt(128e9 / 8790.0)


def run_reversal(dist, m, k, quick):
    """v0 = 0.01 c sin(10 pi x); 500 k steps at Courant number 0.1 on the particle spacing,
    reverse every velocity, 500 k steps more (the same physical time at every level)."""
    s = 0.05 / k
    if m["family"] == "MPM":
        sc = coupled_bar_1d("mpm", shape=m["shape"], transfer=m["transfer"], spacing=s)
    elif m["family"] == "SPH UL":
        sc = sph_bar_1d(m["integrator"], spacing=s)
    else:
        sc = coupled_bar_1d("coupled", shape="gimp", transfer="musl", spacing=s)
    sc.data["time"].pop("cfl")
    sc.data["time"]["dt"] = 0.1 * s / C_CU
    sim = sc.simulation(dist=dist)
    p = sim.particles
    p["v"][:, 0] = 0.01 * C_CU * np.sin(10 * np.pi * p["x"][:, 0])
    v0 = gathered(sim, ["v"])["v"][:, 0]
    e0 = sim.diagnostics()["total"]
    worst = [0.0]

    def track(s_):
        worst[0] = max(worst[0], abs(s_.diagnostics()["total"] / e0 - 1.0))

    secs = 0.0
    for leg in range(2):
        secs += steps_for(sim, 500 * k, track)
        if leg == 0:
            p = sim.particles
            p["v"][:] *= -1.0
            if sim.sph is not None:
                sim.sph.evaluated = False  # rates again from the reversed state
    rev = np.abs(gathered(sim, ["v"])["v"][:, 0] + v0).max() / np.abs(v0).max()
    return sim, secs, {"error": worst[0], "aux": rev}


REVERSAL = dict(
    key="reversal", scene=8, title="Scene 8: copper bar, 500 steps, reverse, 500 (1D)",
    metric="max_t |E(t) / E(0) - 1| over the run (energy conservation; aux = velocity "
           "reversal error max|v_end + v0| / max|v0|)",
    aux="reversal error", knob="particle spacing / 0.05 (cell = 2 spacings, dt = 0.1 s/c)",
    methods=mpm_methods() + [dict(label=f"SPH UL {i}", family="SPH UL", integrator=i)
                             for i in ("verlet", "rk3", "predictor_corrector")]
    + [dict(label="coupled gimp musl + SPH verlet", family="coupled")],
    levels={"full": [1, 2, 4, 8], "quick": [1, 2]}, knob_of=lambda k: 1.0 / k,
    run=run_reversal,
    not_applicable={"SPH TL": "1D total-Lagrangian SPH is not offered (TL-SPH is 2D/3D)"})


# -- scene 9: static strain under a stress boundary ------------------------------------------
STRAIN = -1e6 / 128e9  # -7.8125e-6


def run_stress(dist, m, k, quick):
    s = 0.05 / k
    if m["family"] == "MPM":
        sc = stress_bar("mpm", shape=m["shape"], transfer=m["transfer"], spacing=s)
    else:
        sc = stress_bar("coupled", h=1.3 * s, spacing=s)
    sim = sc.simulation(dist=dist)
    x0 = gathered(sim, ["x"])["x"][:, 0]
    secs = advance(sim, sc.data["time"]["end"])
    strain = gathered(sim, ["F"])["F"][:, 0, 0] - 1.0
    inner = (x0 > 2 * s) & (x0 < 1.0 - 2 * s)  # not the two loaded layers at each end
    err = np.abs(strain[inner] / STRAIN - 1.0)
    return sim, secs, {"error": float(err.max()), "aux": float(strain[inner].mean() / STRAIN)}


STRESS = dict(
    key="stress_bar", scene=9, title="Scene 9: copper bar under 1 MPa end stress (1D)",
    metric="max over particles beyond two spacings from the ends of |strain / (-7.8125e-6) - 1| "
           "at t = 0.02 (damped); aux = mean strain / expected",
    aux="mean strain / expected", knob="particle spacing / 0.05 (cell = 2 spacings, CFL 0.1)",
    methods=mpm_methods() + [dict(label="coupled gimp musl + SPH verlet", family="coupled")],
    levels={"full": [1, 2, 4, 8], "quick": [1, 2]}, knob_of=lambda k: 1.0 / k,
    run=run_stress,
    not_applicable={"SPH UL, SPH TL": "no stress boundary in SPH: the load is applied on MPM "
                    "particles (the point of the coupling in seed 000)"})
