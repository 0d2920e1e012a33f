"""CPDI1 (Sadeghirad et al. 2011) through the P2G kernel: for one particle with an arbitrary
deformed domain F diag(lp), the nodal sums must reproduce what the exact domain average of
linear shape functions gives in closed form:

  sum_I N_I = 1,  sum_I N_I x_I = x_p                      (mass, mass-weighted position)
  sum_I f_I = 0,  sum_I f_I (x) x_I = -V sigma              (f_I = -V sigma . grad N_I)

the last one because sum_I x_I (x) grad N_I = F diag(lp) (F diag(lp))^-1 = I for any F."""
import numpy as np
import pytest

from pmpmsph.kernels.mpm.transfers import p2g
from pmpmsph.kernels.mpm.shapes import CPDI, static_tags
from pmpmsph.kernels.mpm.views import NO_AFFINE, grid_layout, scatter_points


def one_particle_p2g(dim, F, lp_cells, sigma, x_p, dx=0.1, nodes=16):
    strides = np.array([nodes ** (dim - 1 - a) for a in range(dim)], np.int64)
    node0 = np.zeros(dim)
    gmass = np.zeros((1, nodes ** dim))
    gmom = np.zeros((1, nodes ** dim, dim))
    gforce = np.zeros((1, nodes ** dim, dim))
    m, vol = 2.5, 0.3
    layout = grid_layout(node0, np.zeros(dim, np.int64), 1.0 / dx, strides, node0, node0)
    p2g(static_tags(dim, CPDI),
        scatter_points(x_p[None, :], np.zeros((1, dim)), np.array([m]), np.array([vol]),
                      sigma[None], NO_AFFINE), layout, gmass, gmom,
        lp=np.array([lp_cells]), F=F[None], gforce=gforce)
    xs = np.stack(np.meshgrid(*[np.arange(nodes) * dx] * dim, indexing="ij"), -1).reshape(-1, dim)
    return m, vol, gmass[0], gforce[0], xs


@pytest.mark.parametrize("dim", [1, 2, 3])
def test_cpdi_sums_reproduce_closed_forms(dim):
    rng = np.random.default_rng(7 + dim)
    for _ in range(20):
        F = np.eye(3)
        A = np.eye(dim) + 0.6 * rng.uniform(-1, 1, (dim, dim))  # stretch, shear, rotation
        if np.linalg.det(A) < 0.2:
            continue
        F[:dim, :dim] = A
        lp = rng.uniform(0.2, 0.6, dim)
        S = rng.uniform(-1, 1, (3, 3))
        S = S + S.T
        x_p = 0.8 + rng.uniform(0, 0.1, dim)
        m, vol, gm, gf, xs = one_particle_p2g(dim, F, lp, S, x_p)
        assert gm.sum() == pytest.approx(m, rel=1e-13)
        np.testing.assert_allclose(gm @ xs, m * x_p, rtol=1e-13)
        np.testing.assert_allclose(gf.sum(axis=0), 0.0, atol=1e-12)
        np.testing.assert_allclose(gf.T @ xs, -vol * S[:dim, :dim], atol=1e-12)


def test_cpdi_domain_follows_the_stretch():
    """A domain stretched 4x along y reaches nodes 4x as far: the nodes with mass span the
    deformed domain (half-extent F_yy lp = 1.6 cells) plus the corners' linear hats."""
    F = np.diag([1.0, 4.0, 1.0])
    _, _, gm, _, xs = one_particle_p2g(2, F, np.array([0.4, 0.4]), np.zeros((3, 3)),
                                       np.array([0.8, 0.8]))
    ys = xs[gm > 0, 1]
    assert ys.min() == pytest.approx(0.6) and ys.max() == pytest.approx(1.0)
