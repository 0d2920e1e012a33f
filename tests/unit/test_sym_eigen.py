"""The closed-form symmetric 3x3 eigen-solve of the plasticity models
(pmpmsph/materials/tensor.py, `sym_eigen`) against numpy.linalg.eigh: random matrices at
several scales, repeated and nearly repeated eigenvalues, block-diagonal (plane strain) and
diagonal ones, to 1e-12 relative."""
import numpy as np
import pytest

from pmpmsph.materials.eigen import sym_eigen

TOL = 1e-12


def solve(A):
    w, v = sym_eigen(A[0, 0], A[1, 1], A[2, 2], A[0, 1], A[1, 2], A[0, 2])
    return np.array(w), np.array(v).reshape(3, 3)


def random_rotation(rng):
    q, r = np.linalg.qr(rng.standard_normal((3, 3)))
    return q * np.sign(np.diag(r))


def check(A):
    """Eigenvalues as eigh's, V orthonormal, V diag(w) V^T = A, and the vectors of the
    eigenvalues separated from the others by more than 1e-3 |A| as eigh's (up to sign):
    closer ones span a plane in which any orthonormal pair is an answer."""
    w, V = solve(A)
    scale = np.abs(A).max()
    we, Ve = np.linalg.eigh(A)
    order = np.argsort(w)
    w, V = w[order], V[:, order]
    assert np.abs(w - we).max() <= TOL * scale
    assert np.abs(V.T @ V - np.eye(3)).max() <= TOL
    assert np.abs(V @ np.diag(w) @ V.T - A).max() <= TOL * scale
    for i in range(3):
        gap = min(abs(we[i] - we[j]) for j in range(3) if j != i)
        if gap > 1e-3 * scale:
            assert min(np.abs(V[:, i] - Ve[:, i]).max(),
                       np.abs(V[:, i] + Ve[:, i]).max()) <= TOL * scale / gap


@pytest.mark.parametrize("scale", [1.0, 1e-9, 1e6])
def test_random_symmetric(scale):
    rng = np.random.default_rng(3)
    for _ in range(2000):
        A = rng.standard_normal((3, 3))
        check(scale * (A + A.T))


def test_near_the_identity():
    """be of a step: the identity plus a small symmetric part (1e-2 to 1e-14)."""
    rng = np.random.default_rng(4)
    for amp in (1e-2, 1e-5, 1e-8, 1e-11, 1e-14):
        for _ in range(300):
            E = amp * rng.standard_normal((3, 3))
            check(np.eye(3) + E + E.T)


@pytest.mark.parametrize("split", [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3])
def test_repeated_and_nearly_repeated(split):
    """Q diag(l, l + split, l3) Q^T with the double pair above or below the third, and a
    nearly triple one."""
    rng = np.random.default_rng(5)
    for _ in range(300):
        Q = random_rotation(rng)
        l, l3 = rng.uniform(0.5, 2.0, 2)
        for diag in ((l, l + split, l3), (l, l * (1 + split), l * (1 - split))):
            check(Q @ np.diag(diag) @ Q.T)


def test_block_diagonal_and_diagonal():
    rng = np.random.default_rng(6)
    for _ in range(500):
        A = np.zeros((3, 3))
        B = rng.standard_normal((2, 2))
        A[:2, :2] = B + B.T
        A[2, 2] = rng.standard_normal()
        check(A)
        check(np.diag(rng.standard_normal(3)))
        check(np.diag([1.0, 1.0, rng.standard_normal()]))
    # other planes than x-y go through the general branch
    for _ in range(500):
        A = rng.standard_normal((3, 3))
        A = A + A.T
        A[0, 1] = A[1, 0] = 0.0
        A[1, 2] = A[2, 1] = 0.0
        check(A)


def test_multiples_of_the_identity_keep_the_frame():
    for v in (2.0, 1.0, -3.0, 0.0):
        w, V = sym_eigen(v, v, v, 0.0, 0.0, 0.0)
        assert w == (v, v, v) and V == (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
