"""Small scenes shared by the parallel tests (Python Scene API, seconds to run)."""
from pmpmsph import Scene


def two_disks(contact="single", shape="linear", spacing=0.02):
    """BENCHMARKS.md scene 3 (thesis §8.3) on its 20x20 grid."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[1, 1], cells=[20, 20]),
               time=dict(end=3.0, dt=1e-3), mpm=dict(shape=shape, contact=contact))
    sc.material("m", model="neo_hookean", E=1000.0, nu=0.3, rho=1000.0)
    sc.body(name="a", material="m", shape="disc", centre=[0.2, 0.2], radius=0.2,
            spacing=spacing, velocity=[0.1, 0.1])
    sc.body(name="b", material="m", shape="disc", centre=[0.8, 0.8], radius=0.2,
            spacing=spacing, velocity=[-0.1, -0.1])
    return sc


def dam_break(shape="quadratic", transfer="usl", barrier=True, balance_every=0):
    """BENCHMARKS.md scene 4 set-up (thesis §8.4): 4 x 2 column behind a gate removed at
    t = 0, slip walls, a barrier at x = 6 inside a grid extended to x = 8."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[8, 8], cells=[24, 24]),
               time=dict(end=2.0, dt=1e-3), gravity=[0, -9.81],
               mpm=dict(shape=shape, transfer=transfer),
               parallel=dict(axis="x", balance_every=balance_every))
    sc.material("water", model="tait", rho=997.5, kappa=2e6, gamma=7.0, mu=0.01)
    sc.body(name="water", material="water", shape="box", min=[0, 0], max=[4, 2], ppc=2)
    for face in ("x-", "x+", "y-", "y+"):
        sc.boundary(face=face, type="slip")
    if barrier:
        sc.boundary(box=dict(min=[6, 0], max=[6, 1]), type="slip", normal=[1, 0])
    return sc


def loaded_bar(shape="gimp", transfer="usf"):
    """An elastic bar across every slab face with the features a slab face must not change:
    fixed face, traction load with a ramp, prescribed velocity, a gate, damping, gravity."""
    sc = Scene(2, grid=dict(origin=[0, 0], length=[2.0, 0.5], cells=[40, 10]),
               time=dict(end=1.0, dt=2e-4), gravity=[0, -9.81],
               mpm=dict(shape=shape, transfer=transfer, damping=2.0, flip=0.9),
               parallel=dict(axis="x", balance_every=0))
    sc.material("steel", model="stvk", E=2e5, nu=0.3, rho=1000.0)
    sc.body(name="bar", material="steel", shape="box", min=[0.0, 0.1], max=[1.8, 0.3], ppc=2)
    sc.boundary(face="x-", type="fixed")
    sc.boundary(box=dict(min=[0.0, 0.0], max=[2.0, 0.1]), type="slip", normal=[0, -1],
                until=0.02)
    sc.load(body="bar", box=dict(min=[1.77, 0.1], max=[1.8, 0.3]), normal="x+",
            traction=[1e3, 0.0], ramp=0.01)
    sc.data.setdefault("prescribed", []).append(
        dict(body="bar", box=dict(min=[0.9, 0.1], max=[0.95, 0.3]), velocity=["free", 0.0],
             until=0.01))
    return sc


def sph_bar_1d(integrator="rk3"):
    """BENCHMARKS.md scene 8 in pure SPH (seed 000 §5.1): copper bar on [0, 1], spacing 0.05,
    h = 1.3 spacing, v(x, 0) = 0.01 c sin(10 pi x) set by the caller, Courant number 0.1."""
    sc = Scene(1, domain=dict(min=[-0.5], max=[1.5]), time=dict(end=1.0, cfl=0.1),
               sph=dict(h_factor=1.3, integrator=integrator,
                        viscosity=dict(alpha=0.0, beta=0.0)),
               parallel=dict(balance_every=0))
    sc.material("copper", model="linear_elastic", E=128e9, nu=0.3, rho=8790.0)
    sc.body(name="bar", method="sph", material="copper", shape="box", min=[0.0], max=[1.0],
            spacing=0.05)
    return sc


def sph_dam_break(dx=0.05, integrator="predictor_corrector", walls="slip", balance_every=0,
                  axis="y"):
    """The SPH dam break of cases/sph_dam_break.toml at a coarse spacing: 1 x 2 water
    column in a 4 wide tank (walls 2.5 high: the water stays below in the first 0.3 s),
    dummy-particle walls (4 layers), Tait water, alpha = 0.1. Slabs along y by default, so
    the falling column crosses the slab faces at once."""
    sc = Scene(2, domain=dict(min=[-0.3, -0.3], max=[4.3, 2.6]), gravity=[0, -9.81],
               time=dict(end=1.0, cfl=0.125),
               sph=dict(kernel="wendland", h_factor=1.3, integrator=integrator, walls=walls,
                        viscosity=dict(alpha=0.1, beta=0.0)),
               parallel=dict(axis=axis, balance_every=balance_every))
    sc.material("water", model="tait", rho=1000.0, kappa=560571.4, gamma=7.0, mu=0.0)
    sc.body(name="water", method="sph", material="water", shape="box", min=[0, 0],
            max=[1, 2], spacing=dx)
    w = 4 * dx
    for name, lo, hi in (("floor", [0, -w], [4, 0]), ("left", [-w, -w], [0, 2.5]),
                         ("right", [4, -w], [4 + w, 2.5])):
        sc.body(name=name, method="sph", wall=True, material="water", shape="box", min=lo,
                max=hi, spacing=dx)
    return sc


def tl_plate(n=21, corrected=True, eta=None, integrator="rk3", force="current",
             deformation="reference", k_h=1.4, cfl=0.3, end=1.2):
    """BENCHMARKS.md scene 12 (seed 004 §6.1): 1 x 1 mm plane-strain plate, Hartmann-Neff
    neo-Hookean mu = 1.25 MPa, k = 5.833 MPa, rho = 3, free surface, total-Lagrangian SPH
    with n x n particles (h = k_h x spacing). The caller sets v1 = 0.8 x2 (`shear_velocity`).
    With `eta`: the Maxwell body of scene 13."""
    sc = Scene(2, domain=dict(min=[-1.0, -1.0], max=[3.0, 2.0]),
               time=dict(end=end, cfl=cfl),
               sph=dict(formulation="total", correction=corrected, h_factor=k_h,
                        integrator=integrator, force=force, deformation=deformation),
               parallel=dict(axis="x", balance_every=0))
    if eta is None:
        sc.material("rubber", model="hartmann_neff", mu=1.25, k=5.833, rho=3.0)
    else:
        sc.material("rubber", model="maxwell", mu=1.25, k=5.833, rho=3.0, eta=eta)
    sc.body(name="plate", method="sph", material="rubber", shape="box", min=[0.0, 0.0],
            max=[1.0, 1.0], count=[n, n])
    return sc


def shear_velocity(sim, rate=0.8):
    """Initial simple-shear velocity v1 = rate x2, v2 = 0 (seed 004, eq. 19)."""
    p = sim.particles
    p["v"][:, 0] = rate * p["x"][:, 1]
    p["v"][:, 1] = 0.0


def coupled_bar_1d(mode="coupled", shape="gimp", integrator="verlet"):
    """Seed 000 §5 copper bar (cell 0.1, spacing 0.05) as `mode`: "coupled" (MPM in the
    outer cells [0, 0.2] and [0.8, 1], SPH inside, h = cell size), "mpm" or "sph"."""
    sc = Scene(1, grid=dict(origin=[-0.3], cell_size=0.1, cells=[16]),
               time=dict(end=1.0, cfl=0.1),
               mpm=dict(shape=shape, transfer="usl"),
               parallel=dict(balance_every=0))
    if mode != "mpm":
        sc.data["sph"] = dict(h=0.1, integrator=integrator,
                              viscosity=dict(alpha=0.0, beta=0.0))
    sc.material("copper", model="linear_elastic", E=128e9, nu=0.3, rho=8790.0)
    sc.body(name="bar", method="sph" if mode == "sph" else "mpm", material="copper",
            shape="box", min=[0.0], max=[1.0], spacing=0.05)
    if mode == "coupled":
        sc.data["regions"] = [dict(method="sph", shape="box", min=[0.2], max=[0.8])]
    return sc


def coupled_stress_bar(h=0.1, transfer="musl", alpha=0.0):
    """Seed 000 §5.2 (BENCHMARKS.md scene 9): the copper bar compressed by 1 MPa ramped over
    2 ms on its end particles (MPM, [0, 0.2] and [0.8, 1]), SPH inside, damped to rest."""
    sc = Scene(1, grid=dict(origin=[-0.2], length=[1.4], cells=[14]),
               time=dict(end=0.02, cfl=0.1),
               mpm=dict(shape="gimp", damping=2000.0, transfer=transfer),
               sph=dict(h=h, integrator="verlet", damping=2000.0,
                        viscosity=dict(alpha=alpha, beta=alpha)),
               parallel=dict(balance_every=0))
    sc.material("copper", model="linear_elastic", E=128e9, nu=0.3, rho=8790.0)
    sc.body(name="bar", material="copper", shape="box", min=[0.0], max=[1.0], spacing=0.05)
    sc.data["regions"] = [dict(method="sph", shape="box", min=[0.2], max=[0.8])]
    for lo, hi, face in ((0.0, 0.05, "x-"), (0.95, 1.0, "x+")):
        sc.load(body="bar", box=dict(min=[lo], max=[hi]), normal=face, stress=[-1e6],
                ramp=0.002)
    return sc


def handover_bar(v=50.0):
    """A copper bar on [0.3, 0.5] moving at v through the boundary x = 0.6 of an SPH region
    (MPM elsewhere) with `handover`: its particles turn from MPM to SPH as they cross."""
    sc = Scene(1, grid=dict(origin=[0.0], cell_size=0.05, cells=[30]),
               time=dict(end=0.006, cfl=0.2),
               mpm=dict(shape="gimp", transfer="musl"),
               sph=dict(integrator="verlet", viscosity=dict(alpha=0.0, beta=0.0)),
               parallel=dict(balance_every=0))
    sc.material("copper", model="linear_elastic", E=128e9, nu=0.3, rho=8790.0)
    sc.body(name="bar", material="copper", shape="box", min=[0.3], max=[0.5], spacing=0.025,
            velocity=[v])
    sc.data["regions"] = [dict(method="sph", shape="box", min=[0.6], max=[1.5])]
    sc.data["coupling"] = dict(handover=True)
    return sc
