"""`python -m pmpmsph.bench plastic`: what plasticity costs per particle-step (issue 21: at
most 1.3x the same scene with neo-Hookean), in one invocation.

The scene: a 2D block of sand (n x n particles, 2 x 2 per cell) slumping under gravity on a
friction floor, the same particles, steps and fixed dt for every material: neo-Hookean (the
reference), von Mises, Drucker-Prager (E = 2 MPa, nu = 0.3, rho = 1500; yield 5 kPa;
phi = 30 deg), in MPM (GIMP, USL) with and without F-bar, and in updated-Lagrangian SPH
(the floor a held layer). Best of `repeat` blocks of `steps` steps after a warm-up that
compiles and lets the block start to flow plastically.
"""
from ..scene_api import Scene
from . import write_json
from .throughput import time_simulation

MATERIALS = {
    "neo_hookean": dict(model="neo_hookean"),
    "von_mises": dict(model="von_mises", yield_stress=5e3),
    "drucker_prager": dict(model="drucker_prager", friction_angle=30.0),
}


def block(method, material, n, fbar=False):
    """The slumping block of the module docstring, n x n particles."""
    width = 0.2
    spacing = width / n
    dt = 0.25 * spacing / 45.0  # a quarter of the CFL step of the elastic wave (c ~ 45 m/s)
    kw = dict(time=dict(end=1e9, dt=dt), gravity=[0.0, -9.81])
    if method == "mpm":
        kw.update(grid=dict(origin=[0.0, 0.0], cell_size=2 * spacing,
                            cells=[int(round(3 * width / (2 * spacing))),
                                   int(round(1.2 * width / (2 * spacing)))]),
                  mpm=dict(shape="gimp", transfer="usl", fbar=fbar),
                  boundaries=[dict(face="x-", type="slip"),
                              dict(face="y-", type="friction", friction=0.5)])
        lo = [0.0, 0.0]
    else:
        kw.update(domain=dict(min=[-3 * spacing, -3 * spacing], max=[3 * width, 1.2 * width]),
                  prescribed=[dict(body="sand", box=dict(min=[-1.0, -1.0], max=[9.0, 0.0]),
                                   velocity=[0.0, 0.0])])
        lo = [0.0, -3 * spacing]
    sc = Scene(2, **kw)
    sc.material("sand", E=2e6, nu=0.3, rho=1500.0, **MATERIALS[material])
    sc.body(name="sand", material="sand", shape="box", min=lo, max=[width, width],
            spacing=spacing, method=method)
    return sc


def run(args):
    rows = []
    variants = [("mpm", False), ("mpm", True), ("sph", False)]
    print(f"{'method':<12}{'material':<16}{'particles':>10}{'M p-steps/s':>13}"
          f"{'cost / neo-Hookean':>20}")
    for method, fbar in variants:
        base = None
        for material in MATERIALS:
            if fbar and material == "neo_hookean":
                base_sim = block(method, material, args.n).simulation()  # (no F-bar: elastic)
            else:
                base_sim = block(method, material, args.n, fbar).simulation()
            secs, _ = time_simulation(base_sim, args.steps, warmup=args.warmup,
                                      repeat=args.repeat)
            n = base_sim.particles.n_owned
            rate = n * args.steps / secs
            base = rate if material == "neo_hookean" else base
            label = method + (" fbar" if fbar else "")
            ratio = base / rate
            print(f"{label:<12}{material:<16}{n:>10}{rate / 1e6:>13.2f}{ratio:>15.2f}",
                  flush=True)
            rows.append({"method": label, "material": material, "particles": n,
                         "rate": rate, "cost_ratio": ratio})
    write_json(args.out, "plastic_cost.json", rows)
    return 0
