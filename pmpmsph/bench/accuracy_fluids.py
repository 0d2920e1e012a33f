"""Accuracy-bench studies of viscous fluids: the lid-driven cavity at Re = 100 against Ghia,
Ghia & Shin (1982), and the Couette start-up against its series solution. Same protocol as
`accuracy_1d` / `accuracy_2d`."""
import numpy as np

from ..codes import MPM
from .accuracy_core import advance, gathered
from .scenes import couette_exact, mpm_couette, sph_cavity, sph_couette

# Ghia, Ghia & Shin (1982), J. Comput. Phys. 48, 387-411, Table I, Re = 100: u / U on the
# vertical centre line x = 0.5 (the interior points; y = 0 and 1 are the walls)
GHIA_Y = np.array([0.0547, 0.0625, 0.0703, 0.1016, 0.1719, 0.2813, 0.4531, 0.5000, 0.6172,
                   0.7344, 0.8516, 0.9531, 0.9609, 0.9688, 0.9766])
GHIA_U = np.array([-0.03717, -0.04192, -0.04775, -0.06434, -0.10150, -0.15662, -0.21090,
                   -0.20581, -0.13641, 0.00332, 0.23151, 0.68717, 0.73722, 0.78871, 0.84123])
#: the four points the issue names: the minimum, and either side of it and of the core
GHIA_KEY = np.array([5, 6, 9, 10])
#: the centre line is averaged over the last AVERAGE s of the run (SPH particle noise)
AVERAGE = 3.0


def centre_line_u(sim, dp, h_factor=1.3):
    """u at (0.5, GHIA_Y): the Shepard (normalised) Wendland interpolation of the fluid and
    wall velocities (walls: their own, the lid's U), over all ranks."""
    g = gathered(sim, ["x", "v", "mass", "rho", "method"])
    keep = g["method"] != MPM
    x, u = g["x"][keep], g["v"][keep, 0]
    vol = g["mass"][keep] / g["rho"][keep]
    probes = np.c_[np.full(len(GHIA_Y), 0.5), GHIA_Y]
    q = np.linalg.norm(probes[:, None, :] - x[None, :, :], axis=2) / (h_factor * dp)
    w = np.clip(1.0 - 0.5 * q, 0.0, None) ** 4 * (1.0 + 2.0 * q) * vol[None, :]
    return (w @ u) / w.sum(axis=1)


def run_cavity(dist, m, n, quick):
    end = 10.0 if quick else 20.0
    sim = sph_cavity(n=n, end=end, laminar=m["laminar"]).simulation(dist=dist)
    samples = []

    def sample(s):
        if s.time > end - AVERAGE and s.step_count % 100 == 0:
            samples.append(centre_line_u(s, 1.0 / n))

    secs = advance(sim, end, sample)
    u = np.mean(samples, axis=0)
    err = np.abs(u - GHIA_U)
    return sim, secs, {"error": float(err[GHIA_KEY].max()), "aux": float(err.max())}


CAVITY = dict(
    key="cavity", scene="cavity", title="Lid-driven cavity, Re = 100 (2D): u on the centre line",
    metric="max |u - u_Ghia| / U at y = 0.2813, 0.4531, 0.7344, 0.8516 (Ghia et al. 1982), "
           "u averaged over the last 3 s of 20; aux = the same over all 15 interior points",
    aux="max over 15 points", knob="particle spacing x 30",
    methods=[dict(label="SPH UL wendland PEC morris", family="SPH UL", laminar="morris"),
             dict(label="SPH UL wendland PEC stress", family="SPH UL", laminar="stress")],
    levels={"full": [20, 30, 50], "quick": [20]}, knob_of=lambda n: 30.0 / n, run=run_cavity,
    not_applicable={"SPH TL": "a fluid has no reference configuration",
                    "MPM": "the corner cells under the lid are compressed without bound "
                           "(J 0.04 by t = 0.25 s at 32 x 32, bench/scenes.py mpm_cavity): "
                           "a weakly compressible MPM fluid cannot take the lid's velocity "
                           "jump at the corners; needs a projection step",
                    "coupled": "one fluid, no solid to couple"})


#: the times of the Couette study (start-up, half-way, steady) and its kinematic viscosity
COUETTE_TIMES = (0.1, 0.5, 2.5)
COUETTE_NU = 0.5


def couette_error(sim, across):
    """max over the fluid's particle rows (`across` of them in 0 < y < 1) of |row-mean u -
    the series solution at the row's mean y| / U, over all ranks."""
    g = gathered(sim, ["x", "v"])
    y, u = g["x"][:, 1], g["v"][:, 0]
    fluid = (y > 0.0) & (y < 1.0)
    row = np.minimum((y[fluid] * across).astype(int), across - 1)
    count = np.bincount(row, minlength=across)
    ym = np.bincount(row, y[fluid], across) / count
    um = np.bincount(row, u[fluid], across) / count
    return float(np.abs(um - couette_exact(ym, sim.time, COUETTE_NU)).max())


def run_couette(dist, m, across, quick):
    if m["family"] == "MPM":
        sc = mpm_couette(n=across // 2, nu=COUETTE_NU, velocity_update=m["velocity_update"])
    else:
        sc = sph_couette(n=across, nu=COUETTE_NU, laminar=m["laminar"])
    sim = sc.simulation(dist=dist)
    secs, errors = 0.0, []
    for t in COUETTE_TIMES:
        secs += advance(sim, t)
        errors.append(couette_error(sim, across))
    return sim, secs, {"error": max(errors), "aux": errors[-1]}


COUETTE = dict(
    key="couette", scene="couette", title="Couette start-up, Re = 2 (2D, periodic along the "
    "flow)",
    metric="max |u - u_exact| / U over the particle rows at t = 0.1, 0.5 and 2.5 (steady), "
           "u averaged along each row, against the series solution; aux = at t = 2.5 alone",
    aux="steady state", knob="particle spacing x 40",
    methods=[dict(label="SPH UL wendland PEC morris", family="SPH UL", laminar="morris"),
             dict(label="MPM quadratic usl apic", family="MPM", velocity_update="apic"),
             dict(label="MPM quadratic usl mls", family="MPM", velocity_update="mls")],
    levels={"full": [20, 40, 80], "quick": [20]}, knob_of=lambda n: 40.0 / n,
    run=run_couette,
    not_applicable={"SPH TL": "a fluid has no reference configuration",
                    "coupled": "one fluid, no solid to couple"})
