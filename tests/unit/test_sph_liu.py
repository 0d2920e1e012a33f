"""Liu's corrected kernel split into rows and pairs (kernels/sph/liu.py): the coefficients
summed over half neighbour lists give, pair by pair, the gradients the total formulation's
`kernel_correction` computes over full lists, to round-off, in 2D and 3D, interior and
surface rows alike (and for a row whose neighbours are collinear, Shepard's fallback)."""
import numpy as np
import pytest

from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.views import pair_lists, smoothing_of
from pmpmsph.kernels.sph.liu import COEF, liu_coefficients, liu_gradient
from pmpmsph.kernels.sph.tlsph import kernel_correction


@pytest.mark.parametrize("dim", [2, 3])
def test_half_list_coefficients_match_the_full_list_correction(dim):
    rng = np.random.default_rng(3)
    dp, h = 0.1, 0.13
    g = np.arange(5) * dp
    grids = np.meshgrid(*([g] * dim), indexing="ij")
    x = np.stack([c.ravel() for c in grids], axis=1)
    x = np.ascontiguousarray(x + 0.1 * dp * rng.standard_normal(x.shape))
    n = len(x)
    mass = np.full(n, 1000.0 * dp ** dim) * (1 + 0.1 * rng.random(n))
    rho = np.full(n, 1000.0)
    vol = mass / rho
    start, index = neighbour_lists(x, n, 2 * h)
    gw, wt = np.empty((len(index), dim)), np.empty(len(index))
    kernel_correction(x, vol, start, index, h, 0, dim, True, wt, gw)
    hs, hi = neighbour_lists(x, n, 2 * h, half=True)
    coef = np.zeros((n, COEF))
    liu_coefficients(smoothing_of((0,) * dim, (0,), h), pair_lists(n, hs, hi), x, mass, rho,
                     np.ones(n, np.int8), np.zeros(n, np.int32), np.ones(n, np.bool_),
                     np.zeros((n, 52)), coef)
    from pmpmsph.kernels.sph.kernel_functions import kernel_dwdr, kernel_w

    out, r = np.zeros(3), np.zeros(3)
    worst = 0.0
    for a in range(n):
        for k in range(start[a], start[a + 1]):
            b = index[k]
            r[:dim] = x[a] - x[b]
            rn = np.linalg.norm(r)
            w = kernel_w(0, dim, rn, h)
            dw = kernel_dwdr(0, dim, rn, h) / rn if rn > 0 else 0.0
            wk = liu_gradient(dim, coef[a], r, w, dw, out)
            worst = max(worst, np.abs(out[:dim] - gw[k]).max() * h ** (dim + 1),
                        abs(wk - wt[k]) * h ** dim)
    assert worst < 1e-12
