"""Accuracy-bench studies of the 2D scenes: 3 (two disks), 12 (TL-SPH plate) and the SPH /
MPM dam break (surge front). Same protocol as `accuracy_1d`."""
import numpy as np

from ..scene_api import Scene
from .accuracy_1d import mpm_methods
from .accuracy_core import advance, gathered
from .scenes import shear_velocity, sph_dam_break, tl_plate, two_disks

# -- scene 3: two elastic disks -------------------------------------------------------------
T_CONTACT = (0.6 * np.sqrt(2) - 0.4) / (0.2 * np.sqrt(2))  # 1.5858: first touch


def run_disks(dist, m, cells, quick):
    """Cells c across the unit square, point spacing 0.4 / c (316 points per disk at the
    thesis' 20 cells), dt = 0.01 / c."""
    sc = two_disks(contact=m["contact"], shape=m["shape"], transfer=m["transfer"],
                   cells=cells, spacing=0.4 / cells, dt=0.01 / cells)
    sim = sc.simulation(dist=dist)
    d0 = sim.diagnostics()
    falls = [np.nan]

    def track(s):  # contact is felt when the kinetic energy first drops by 0.1 %
        if np.isnan(falls[0]) and s.diagnostics()["kinetic"] < 0.999 * d0["kinetic"]:
            falls[0] = s.time

    secs = advance(sim, 3.0, track)
    drift = abs(sim.diagnostics()["total"] / d0["total"] - 1.0)
    return sim, secs, {"error": drift, "aux": falls[0] - T_CONTACT}


DISKS = dict(
    key="two_disks", scene=3, title="Scene 3: two elastic disks colliding (2D)",
    metric="|E(3) / E(0) - 1|, total-energy drift over the elastic collision (exact 0); "
           "aux = contact-time error t_KE drop - 1.5858",
    aux="contact time - 1.5858", knob="cell size / (1/20); spacing 0.4 cells, dt = 0.01 cells",
    methods=[dict(m, label=m["label"] + " 1 field", contact="single")
             for m in mpm_methods(transfers=("usl", "musl"))]
    + [dict(label="MPM gimp musl per-body fields", family="MPM", shape="gimp", transfer="musl",
            contact="multi")],
    levels={"full": [10, 20, 40], "quick": [10, 20]}, knob_of=lambda c: 20.0 / c,
    run=run_disks,
    not_applicable={"SPH UL, SPH TL, coupled": "no contact between SPH bodies: two SPH disks "
                    "would interact through the kernel as one continuum (not this scene)"})


# -- scene 12: TL-SPH plate in simple shear ---------------------------------------------------
def _plate_mpm(n, m):
    """The plate in 2D MPM: n x n particles (spacing 1/n), cells of 2 spacings with a node
    on the plate's edges, a grid that holds the sheared plate."""
    c = 2.0 / n
    lo = -c * np.ceil(0.5 / c)
    sc = Scene(2, grid=dict(origin=[lo, lo], cell_size=c,
                            cells=[int(np.ceil((2.2 - lo) / c)), int(np.ceil((1.5 - lo) / c))]),
               time=dict(end=1.2, cfl=0.3), mpm=dict(shape=m["shape"], transfer=m["transfer"]),
               parallel=dict(axis="x", balance_every=0))
    sc.material("rubber", model="hartmann_neff", mu=1.25, k=5.833, rho=3.0)
    sc.body(name="plate", material="rubber", shape="box", min=[0.0, 0.0], max=[1.0, 1.0],
            count=[n, n])
    return sc


def _plate(n, m):
    fam = m["family"]
    if fam == "MPM":
        return _plate_mpm(n, m)
    if fam == "SPH UL":
        return tl_plate(n=n, formulation="updated", k_h=m.get("k_h", 1.4))
    return tl_plate(n=n, corrected=m["corrected"], force=m.get("force", "current"),
                    k_h=m.get("k_h", 1.4))


def plate_field(dist, n, m):
    """(X0, displacement at t = 1.2, simulation, seconds) of one plate run; X0 sorted by gid."""
    sim = _plate(n, m).simulation(dist=dist)
    shear_velocity(sim)
    if sim.sph is not None:
        sim.sph.evaluated = False
    x0 = gathered(sim, ["x"])["x"]
    secs = advance(sim, 1.2)
    return x0, gathered(sim, ["x"])["x"] - x0, sim, secs


def bilinear(X0, u, n, point):
    """Displacement at `point` from a run seeded on the n x n cell-centre lattice."""
    s = 1.0 / n
    grid = u[np.lexsort((X0[:, 1], X0[:, 0]))].reshape(n, n, 2)  # [i(x), j(y)]
    f = np.clip((np.asarray(point) - 0.5 * s) / s, 0.0, n - 1 - 1e-12)
    i, j = f.astype(int)
    a, b = f - (i, j)
    return ((1 - a) * (1 - b) * grid[i, j] + a * (1 - b) * grid[i + 1, j]
            + (1 - a) * b * grid[i, j + 1] + a * b * grid[i + 1, j + 1])


REFERENCE = dict(label="reference", family="SPH TL", corrected=True, force="reference", k_h=1.2)
_reference = {}


def plate_reference(dist, quick):
    """The fine run every plate error is measured against: TL-SPH with the energy-consistent
    total-Lagrangian force (force = "reference", k_h = 1.2, stable and converged: drift
    7.7e-7 at 81 x 81, tests/verification/test_tlsph_plate.py) at 81 x 81 (41 x 41 in
    --quick). The error of a coarser run is taken at its own corner particle's material
    point, interpolated in the reference field, so seeding offsets are not counted."""
    n = 41 if quick else 81
    if n not in _reference:
        X0, u, _, _ = plate_field(dist, n, REFERENCE)
        _reference[n] = (X0, u)
    return n, _reference[n]


def run_plate(dist, m, n, quick):
    n_ref, (X0r, ur) = plate_reference(dist, quick)
    X0, u, sim, secs = plate_field(dist, n, m)
    corner = int(np.argmax(X0[:, 0] + X0[:, 1]))
    ref = bilinear(X0r, ur, n_ref, X0[corner])
    err = np.linalg.norm(u[corner] - ref) / np.linalg.norm(ref)
    return sim, secs, {"error": float(err), "aux": float(u[corner][0])}


PLATE = dict(
    key="plate", scene=12, title="Scene 12: neo-Hookean plate in simple shear (2D)",
    metric="|u_corner(1.2) - u_ref| / |u_ref| at the top-right particle's material point; "
           "u_ref from TL-SPH (total-Lagrangian force, k_h 1.2) at 81 x 81 (41 x 41 in --quick)",
    aux="u1 corner", knob="particle spacing / (1/11) (n x n particles, CFL 0.3)",
    methods=[dict(label="SPH TL corrected", family="SPH TL", corrected=True),
             dict(label="SPH TL uncorrected", family="SPH TL", corrected=False),
             dict(label="SPH UL", family="SPH UL")]
    + [m for m in mpm_methods(shapes=("gimp", "quadratic", "cubic"), transfers=("usl", "musl"))],
    levels={"full": [11, 21, 41], "quick": [11, 21]}, knob_of=lambda n: 11.0 / n,
    run=run_plate,
    not_applicable={"coupled": "the seed's plate is one method throughout; no interface"})


# -- dam break: surge front against Koshizuka & Oka (1996) --------------------------------------
# Koshizuka, S. & Oka, Y. (1996), Moving-particle semi-implicit method for fragmentation of
# incompressible fluid, Nucl. Sci. Eng. 123, 421-434: surge front z/L against
# T = t sqrt(2 g / L) for a column of width L and height 2L (the values as tabulated in
# PySPH's examples/db_exp_data.py). L = 1 here.
KO_T = np.array([0.381, 0.769, 1.153, 1.537, 1.935])
KO_Z = np.array([1.111, 1.252, 1.505, 1.892, 2.241])
G = 9.81
T_END = 1.0  # s: T = 4.4, past the surge's impact on the far wall (x = 4) at T ~ 3
#: the pressure gauge on the far wall, y = 0.2 (a tenth of the column's height), sampled
#: every GAUGE_DT s: the Shepard average of the water particles' pressure within GAUGE_R
#: spacings of the wall point (particles sit half a spacing off the wall)
GAUGE = (4.0, 0.2)
GAUGE_DT = 0.005
GAUGE_R = 2.0


def _dam_mpm(dx, flip=1.0, velocity_update="flip"):
    """The same column (1 x 2 in a 4 wide tank) in MPM: quadratic B-splines, USL, slip walls,
    cells of 2 spacings (4 particles per cell), CFL 0.3; `flip` the PIC/FLIP blend (1, the
    default: FLIP) or `velocity_update` "apic" / "mls" (kernels/mpm/affine.py)."""
    c = 2 * dx
    mpm = dict(shape="quadratic", transfer="usl", velocity_update=velocity_update)
    if velocity_update == "flip":
        mpm["flip"] = flip
    sc = Scene(2, grid=dict(origin=[0.0, 0.0], cell_size=c,
                            cells=[int(round(4.0 / c)), int(round(4.0 / c))]),
               gravity=[0, -G], time=dict(end=T_END, cfl=0.3),
               mpm=mpm, parallel=dict(axis="x", balance_every=50))
    sc.material("water", model="tait", rho=1000.0, kappa=560571.4, gamma=7.0, mu=0.0)
    sc.body(name="water", material="water", shape="box", min=[0, 0], max=[1, 2], spacing=dx)
    for face in ("x-", "x+", "y-", "y+"):
        sc.boundary(face=face, type="slip")
    return sc


def gauge_pressure(sim, dx):
    """Pressure at `GAUGE` (Shepard average over the water particles within GAUGE_R dx,
    weights (1 - r/R)^2), over all ranks; 0 when no water is near."""
    p = sim.particles
    n = p.n_owned
    water = p["body"][:n] == 0
    x, sigma = p["x"][:n][water], p["sigma"][:n][water]
    r = np.hypot(x[:, 0] - GAUGE[0], x[:, 1] - GAUGE[1]) / (GAUGE_R * dx)
    w = np.clip(1.0 - r, 0.0, None) ** 2
    pressure = -(sigma[:, 0, 0] + sigma[:, 1, 1] + sigma[:, 2, 2]) / 3.0
    num, den = sim.dist.sum(float(w @ pressure)), sim.dist.sum(float(w.sum()))
    return num / den if den > 0 else 0.0


def run_dam(dist, m, dx, quick):
    if m["family"] == "MPM":
        sc = _dam_mpm(dx, m.get("flip", 1.0), m.get("velocity_update", "flip"))
    else:
        sc = sph_dam_break(dx=dx, end=T_END, balance_every=50, axis="x", wall_height=4.0)
    sim = sc.simulation(dist=dist)
    hist = [(0.0, 1.0)]
    gauge = [(0.0, 0.0)]

    def track(s):  # front = largest water-particle x plus half a spacing (1 at t = 0)
        p = s.particles
        water = p["body"] == 0
        xf = p["x"][water, 0].max() if water.any() else -np.inf
        hist.append((s.time, s.dist.max(float(xf)) + 0.5 * dx))
        if s.time >= gauge[-1][0] + GAUGE_DT - 1e-12:
            gauge.append((s.time, gauge_pressure(s, dx)))

    secs = advance(sim, T_END, track)
    t, xf = np.array(hist).T
    z = np.interp(KO_T / np.sqrt(2 * G), t, xf)
    tg, pg = np.array(gauge).T
    series = {"T": (tg * np.sqrt(2 * G)).tolist(), "p / (rho g L)": (pg / (1000.0 * G)).tolist()}
    return sim, secs, {"error": float(np.max(np.abs(z / KO_Z - 1.0))), "aux": float(z[-1]),
                       "series": series}


DAM = dict(
    key="dam_break", scene="dam", title="Dam break: surge front of a 1 x 2 water column (2D)",
    metric="max over T = 0.38 ... 1.94 of |x_front / x_exp - 1| against Koshizuka & Oka "
           "(1996); aux = x_front at T = 1.94 (experiment 2.241)",
    aux="front at T=1.94", knob="particle spacing / 0.05",
    methods=[dict(label="SPH UL wendland PEC", family="SPH UL"),
             dict(label="MPM quadratic usl", family="MPM", shape="quadratic", transfer="usl",
                  quick=True),
             dict(label="MPM quadratic usl pic", family="MPM", shape="quadratic",
                  transfer="usl", flip=0.0),
             dict(label="MPM quadratic usl flip 0.99", family="MPM", shape="quadratic",
                  transfer="usl", flip=0.99),
             dict(label="MPM quadratic usl apic", family="MPM", shape="quadratic",
                  transfer="usl", velocity_update="apic"),
             dict(label="MPM quadratic usl mls", family="MPM", shape="quadratic",
                  transfer="usl", velocity_update="mls")],
    levels={"full": [0.05, 0.035, 0.025, 0.0177], "quick": [0.1, 0.05]},
    knob_of=lambda dx: dx / 0.05, run=run_dam,
    series=dict(title="Dam break: pressure on the far wall at y = 0.2 (a tenth of the "
                      "column height)", x="T", y="p / (rho g L)"),
    not_applicable={"SPH TL": "a fluid has no reference configuration",
                    "coupled": "one fluid, no solid to couple"})
