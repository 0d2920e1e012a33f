"""The per-particle state of the plasticity models (materials/von_mises.py) unpacked, for the
tests of von_mises and drucker_prager."""
import numpy as np


def elastic_b(state):
    """be (3 x 3) from state[0:6] (xx, yy, zz, xy, yz, xz)."""
    c = state[:6]
    return np.array([[c[0], c[3], c[5]], [c[3], c[1], c[4]], [c[5], c[4], c[2]]])


def stored_F(state):
    """The F the state was stored at (state[8:17], row-major)."""
    return state[8:17].reshape(3, 3)


def random_rotation(rng):
    """A proper rotation drawn from `rng` (QR of a Gaussian matrix, signs fixed)."""
    q, r = np.linalg.qr(rng.standard_normal((3, 3)))
    Q = q * np.sign(np.diag(r))
    if np.linalg.det(Q) < 0:
        Q[:, 0] *= -1
    return Q


def assert_rotated(s2, s1, Q, tol=1e-12):
    """s2 is s1 under a superposed rotation Q: be -> Q be Q^T, Fn -> Q Fn, alpha and the
    flag unchanged."""
    assert np.abs(elastic_b(s2) - Q @ elastic_b(s1) @ Q.T).max() < tol
    assert np.abs(stored_F(s2) - Q @ stored_F(s1)).max() < tol * np.abs(stored_F(s1)).max()
    assert abs(s2[6] - s1[6]) < tol and s2[7] == s1[7]
