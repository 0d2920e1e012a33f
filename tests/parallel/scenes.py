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
