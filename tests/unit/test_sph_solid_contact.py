"""The grid contact of an SPH solid with an MPM fluid (physics/sph/solid_in_fluid.py): the velocity
change the contact makes to the solid's field, gathered back to its particles
(kernels/coupling.py's gather_increment), gives them exactly the momentum the fluid's field
lost, and it stops their approach."""
import numpy as np

from pmpmsph.config.case import GridSpec
from pmpmsph.kernels.mpm.contact import contact_normals, multi_field_contact, surface_reach
from pmpmsph.kernels.mpm.transfers import WITH_FORCE, grid_velocity, p2g
from pmpmsph.kernels.mpm.shapes import GIMP, static_tags
from pmpmsph.kernels.mpm.views import NO_AFFINE, scatter_points
from pmpmsph.kernels.coupling import gather_increment
from pmpmsph.physics.mpm.grid import Grid


def _scene(seed):
    """Fluid points (field 0) below y = 0.5, solid particles (field 1) above, spacing 0.025
    on cells of 0.1, jittered; the two bodies move towards each other."""
    rng = np.random.default_rng(seed)
    dp = 0.025
    g = np.arange(dp / 2, 1.0, dp)
    X, Y = np.meshgrid(g, g, indexing="ij")
    x = np.stack([X.ravel(), Y.ravel()], axis=1)
    x += rng.uniform(-0.05, 0.05, x.shape) * dp
    solid = x[:, 1] > 0.5
    order = np.argsort(solid, kind="stable")  # fluid rows first, as the coupling orders them
    x, solid = x[order], solid[order]
    n = len(x)
    v = rng.normal(0.0, 0.05, (n, 2))
    v[:, 1] += np.where(solid, -0.5, 0.5)
    mass = np.where(solid, 917.0, 997.0) * dp * dp
    field = solid.astype(np.int64)
    lp = np.full((n, 2), 0.5 * dp / 0.1)
    return x, v, mass, field, lp, solid


def test_gathered_contact_momentum_balances_the_fluid_field():
    x, v, mass, field, lp, solid = _scene(3)
    n = len(x)
    grid = Grid(GridSpec((0.0, 0.0), (0.1, 0.1), (10, 10)), nfields=2, with_normals=True)
    tags = static_tags(2, GIMP)
    grid.reset()
    p2g(tags, scatter_points(x, v, mass, np.full(n, 0.025**2), np.zeros((n, 3, 3)), NO_AFFINE),
        grid.layout, grid.mass, grid.mom, lp=lp, pfield=field, gforce=grid.force,
        gmgrad=grid.mgrad)
    grid_velocity(2, grid.mass, grid.mom, grid.force, grid.vel, grid.dv, 1e-4, np.zeros(3),
                  0.0, 1e-12, WITH_FORCE, 0, grid.n_nodes)

    contact_normals(2, grid.mass, grid.mgrad, np.array([True, False]), 1e-12, grid.normals,
                    grid.reach)
    surface_reach(2, x, np.full(n, 0.025**2), field, lp, grid.node0, grid.offset, grid.inv_dx,
                  grid.strides, 1.25, grid.normals, grid.reach)
    before = grid.vel.copy()
    multi_field_contact(2, grid.mass, grid.normals, grid.reach, grid.vel, grid.dv, 0.0, 1e-12,
                        1e-4)
    dvc = grid.vel - before
    assert np.abs(dvc[0]).max() > 0.1       # the contact acted on the approaching fields
    fluid_change = np.einsum("i,ia->a", grid.mass[0], dvc[0])
    s = np.nonzero(solid)[0]
    v1 = v.copy()
    gather_increment(tags, s[0], n, x, v1, grid.layout, dvc, lp=lp, pfield=field)
    assert np.all(v1[~solid] == v[~solid])   # the fluid rows are left to G2P
    solid_change = (mass[solid, None] * (v1[solid] - v[solid])).sum(axis=0)
    scale = np.abs(mass[:, None] * v).sum()
    assert np.all(np.abs(solid_change + fluid_change) < 1e-12 * scale)
    # the solid's particles within two rows of the interface stop approaching the fluid
    # (downwards); the contact acts only at the nodes where the surfaces meet (measured:
    # -0.50 -> -0.13)
    near = solid & (x[:, 1] < 0.55)
    assert v[near, 1].mean() < -0.4 and v1[near, 1].mean() > 0.5 * v[near, 1].mean()
