"""P2G and G2P (kernels/mpm/transfers.py, thesis eqs. 65 and 80-82) against the transfer written
out node by node: N_I = prod_a w_a, grad N_I = (dw_0 w_1 w_2, w_0 dw_1 w_2, w_0 w_1 dw_2) / dx
from the 1D weights of `kernels.mpm.shapes.weights_1d`. The kernels build the same sums one axis
at a time (sum factorisation), so they must agree to rounding for every tensor-product shape
function in 1D, 2D and 3D (CPDI's corners: tests/unit/test_cpdi.py's closed forms)."""
import itertools

import numpy as np
import pytest

from pmpmsph.kernels.mpm.transfers import g2p, p2g
from pmpmsph.kernels.mpm.views import (NO_AFFINE, gather_options, gather_points, grid_layout,
                                      material_table, scatter_points)
from pmpmsph.kernels.mpm.shapes import CUBIC, GIMP, LINEAR, QUADRATIC, static_tags, weights_1d
from pmpmsph.materials import material_from_table
from pmpmsph.materials.dispatch import material_tag

NODES = 12      # per axis
DX = 0.1
LP = 0.25       # GIMP half-width (cells)
SHAPES = {"linear": LINEAR, "gimp": GIMP, "quadratic": QUADRATIC, "cubic": CUBIC}


def _layout(origin, offset, strides):
    """The grid of `_grid` as the kernels' bundle (no particle leaves its box)."""
    return grid_layout(origin, offset, 1.0 / DX, strides, np.full(3, -1e9), np.full(3, 1e9))


def _grid(dim):
    strides = np.array([NODES ** (dim - 1 - a) for a in range(dim)], np.int64)
    return strides, np.zeros(dim), np.zeros(dim, np.int64)


def _particles(dim, n, rng):
    x = 0.45 + rng.uniform(0.0, 0.3, (n, dim))  # well inside: every stencil on the grid
    S = rng.uniform(-1.0, 1.0, (n, 3, 3))
    return x, rng.uniform(-1, 1, (n, dim)), rng.uniform(1, 2, n), rng.uniform(0.5, 1, n), \
        S + S.transpose(0, 2, 1), rng.uniform(-1, 1, (n, dim))


def _stencil(kind, dim, xp, strides):
    """[(node, N, grad N)] of one particle, node by node."""
    axes = [weights_1d(kind, xp[a] / DX, LP) for a in range(dim)]
    width = {LINEAR: 2, GIMP: 3, QUADRATIC: 3, CUBIC: 4}[kind]
    out = []
    for idx in itertools.product(range(width), repeat=dim):
        w = [axes[a][1][idx[a]] for a in range(dim)]
        dw = [axes[a][2][idx[a]] for a in range(dim)]
        node = sum((axes[a][0] + idx[a]) * strides[a] for a in range(dim))
        grad = np.array([dw[a] * np.prod([w[b] for b in range(dim) if b != a])
                         for a in range(dim)]) / DX
        out.append((node, np.prod(w), grad))
    return out


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("fold", [False, True])
def test_p2g_equals_the_node_by_node_sums(dim, shape, fold):
    kind = SHAPES[shape]
    rng = np.random.default_rng(dim * 10 + kind)
    x, v, m, vol, S, fe = _particles(dim, 7, rng)
    strides, origin, offset = _grid(dim)
    nn = NODES ** dim
    gmass, gmom, gforce = np.zeros((1, nn)), np.zeros((1, nn, dim)), np.zeros((1, nn, dim))
    dt = 0.37
    lp = np.full((len(x), dim), LP) if kind == GIMP else None
    p2g(static_tags(dim, kind), scatter_points(x, v, m, vol, S, NO_AFFINE),
        _layout(origin, offset, strides), gmass, gmom, fext=fe, lp=lp,
        gforce=None if fold else gforce, force_dt=dt if fold else None)
    ref_m, ref_p, ref_f = np.zeros(nn), np.zeros((nn, dim)), np.zeros((nn, dim))
    for p in range(len(x)):
        for node, N, grad in _stencil(kind, dim, x[p], strides):
            ref_m[node] += N * m[p]
            ref_p[node] += N * m[p] * v[p]
            ref_f[node] += N * fe[p] - vol[p] * S[p, :dim, :dim] @ grad
    if fold:  # p + dt f in one scatter (mpm88's form)
        ref_p += dt * ref_f
    np.testing.assert_allclose(gmass[0], ref_m, rtol=0, atol=1e-13 * ref_m.max())
    np.testing.assert_allclose(gmom[0], ref_p, rtol=0, atol=1e-12 * np.abs(ref_p).max())
    if not fold:
        np.testing.assert_allclose(gforce[0], ref_f, rtol=0, atol=1e-12 * np.abs(ref_f).max())
    assert ref_m.sum() == pytest.approx(m.sum(), rel=1e-12)  # the reference is a partition


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("dim", [1, 2, 3])
def test_g2p_equals_the_node_by_node_sums(dim, shape):
    """PIC: v_p = sum N v_I, x_p += dt v_p; F = I and dt = 1 leave F = I + L with
    L = sum v_I (x) grad N."""
    kind = SHAPES[shape]
    rng = np.random.default_rng(100 + dim * 10 + kind)
    x, _, _, vol, _, _ = _particles(dim, 7, rng)
    strides, origin, offset = _grid(dim)
    gvel = rng.uniform(-1, 1, (1, NODES ** dim, dim))
    n = len(x)
    lp = np.full((n, dim), LP) if kind == GIMP else None
    mat = material_from_table({"model": "linear_elastic", "E": 1.0, "nu": 0.3, "rho": 1.0},
                              "m", dim)
    mtypes = np.array([mat.type_code], np.int64)
    mparams = np.array([mat.params(dim)])
    F = np.tile(np.eye(3), (n, 1, 1))
    x0 = x.copy()
    v = np.zeros((n, dim))
    dt = 1.0
    g2p(static_tags(dim, kind),
        gather_points(x, v, np.zeros((n, 3, 3)), vol.copy(), vol, np.zeros(n, np.int32),
                     np.empty((n, 0))),
        material_table(material_tag(mtypes), mtypes, mparams), _layout(origin, offset, strides),
        gather_options(dt, flip=0.0, pic_tag=(0,), max_reach=1e9, want_signal=False), gvel,
        gdv=np.zeros_like(gvel), F=F, lp=lp)
    for p in range(n):
        vp, L = np.zeros(dim), np.zeros((dim, dim))
        for node, N, grad in _stencil(kind, dim, x0[p], strides):
            vp += N * gvel[0, node]
            L += np.outer(gvel[0, node], grad)
        np.testing.assert_allclose(v[p], vp, rtol=0, atol=1e-13)
        np.testing.assert_allclose(x[p], x0[p] + dt * vp, rtol=0, atol=1e-13)
        np.testing.assert_allclose(F[p, :dim, :dim], np.eye(dim) + L, rtol=0,
                                   atol=1e-12 * max(np.abs(L).max(), 1.0))
