"""MPM shape functions against closed forms: partition of unity, linear completeness of the
gradient (sum_I grad N_I = 0 and sum_I x_I grad N_I = identity), derivative consistency."""
import numpy as np
import pytest

from pmpmsph.kernels.mpm.shapes import CUBIC, GIMP, LINEAR, QUADRATIC, STENCIL_WIDTH, weights_1d

KINDS = [LINEAR, GIMP, QUADRATIC, CUBIC]


def _weights(kind, X, lp=0.25):
    base, w, dw = weights_1d(kind, X, lp)
    ns = STENCIL_WIDTH[kind]
    return base, np.array(w[:ns]), np.array(dw[:ns])


@pytest.mark.parametrize("kind", KINDS)
def test_partition_of_unity_and_linear_reproduction(kind):
    rng = np.random.default_rng(1)
    for X in rng.uniform(3.0, 9.0, 200):
        base, w, dw = _weights(kind, X)
        nodes = base + np.arange(len(w))
        assert w.sum() == pytest.approx(1.0, abs=1e-14)
        assert np.all(w >= -1e-15)
        assert dw.sum() == pytest.approx(0.0, abs=1e-13)
        # sum_I N_I x_I = x (linear reproduction) and sum_I dN_I x_I = 1
        assert np.dot(w, nodes) == pytest.approx(X, abs=1e-12)
        assert np.dot(dw, nodes) == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("kind", KINDS)
def test_derivative_is_the_derivative(kind):
    """dw equals the central finite difference of w, node by node (away from kinks)."""
    rng = np.random.default_rng(2)
    eps = 1e-6
    for X in rng.uniform(3.0, 9.0, 100):
        base, _, dw = _weights(kind, X)
        bp, wp, _ = _weights(kind, X + eps)
        bm, wm, _ = _weights(kind, X - eps)
        if bp != base or bm != base:
            continue  # the stencil shifts inside the difference interval
        fd = (wp - wm) / (2 * eps)
        if kind == LINEAR and np.any(np.abs(X - np.round(X)) < 2 * eps):
            continue
        np.testing.assert_allclose(dw, fd, atol=2e-6)


def test_known_values():
    # quadratic B-spline at a node: 1/8, 3/4, 1/8; cubic at a node: 1/6, 2/3, 1/6, 0
    _, w, _ = _weights(QUADRATIC, 5.0)
    np.testing.assert_allclose(w, [0.125, 0.75, 0.125], atol=1e-15)
    _, w, _ = _weights(CUBIC, 5.0)
    np.testing.assert_allclose(w, [1 / 6, 2 / 3, 1 / 6, 0.0], atol=1e-15)
    # GIMP with lp -> 0 tends to the linear hat
    _, w, _ = _weights(GIMP, 5.3, lp=1e-9)
    assert w[1] == pytest.approx(0.7, abs=1e-8) and w[2] == pytest.approx(0.3, abs=1e-8)
