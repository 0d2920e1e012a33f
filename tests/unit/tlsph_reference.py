"""Reference values for the corrected-kernel tests (seed 004, eqs. 1-4): the corrected
kernel W~_b at any point, by dense sums over every particle, and its finite-difference
gradient, which `pmpmsph.kernels.sph.tlsph.kernel_correction` must reproduce."""
import numpy as np

from pmpmsph.jit import njit
from pmpmsph.kernels.sph.kernel_functions import kernel_w
from pmpmsph.materials.tensor import block_inverse


@njit
def corrected_kernel_values(xe, x, vol, h, kind, dim, corrected, out):
    """W~_b(xe) (eqs. 1-3) for every particle b at one evaluation point xe (dense, O(n)).

    out[b] for all rows b of x; the correction sums run over all particles within 2h of xe.
    For `fd_kernel_gradient`; the solver's path is `kernel_correction`."""
    n = x.shape[0]
    M = np.zeros((3, 3))
    Minv = np.zeros((3, 3))
    m1 = np.zeros(3)
    m0 = 0.0
    r = np.zeros(3)
    for b in range(n):
        rn2 = 0.0
        for i in range(dim):
            r[i] = xe[i] - x[b, i]
            rn2 += r[i] * r[i]
        w = kernel_w(kind, dim, np.sqrt(rn2), h)
        out[b] = w
        if w != 0.0:
            w *= vol[b]
            m0 += w
            for i in range(dim):
                m1[i] += w * r[i]
                for j in range(dim):
                    M[i, j] += w * r[i] * r[j]
    if not corrected:
        return
    block_inverse(M, dim, Minv)
    beta = np.zeros(3)
    A = m0
    for i in range(dim):
        for j in range(dim):
            beta[i] -= Minv[i, j] * m1[j]
        A += beta[i] * m1[i]
    alpha = 1.0 / A
    for b in range(n):
        if out[b] != 0.0:
            c = 1.0
            for i in range(dim):
                c += beta[i] * (xe[i] - x[b, i])
            out[b] *= alpha * c


def fd_kernel_gradient(x, vol, a, h, kind, dim, corrected=True, dh=1e-7, central=False):
    """Finite-difference gradient of eq. 4: row b is grad_x W~_b(x) at x = x_a, (n, dim).

    ``[W~_b(x_a + dh e_j) - W~_b(x_a)] / dh`` as in the seed (``central=True``: the central
    difference). The particles stay where they are; only the evaluation point moves."""
    x = np.ascontiguousarray(x, dtype=np.float64)
    vol = np.ascontiguousarray(vol, dtype=np.float64)
    n = x.shape[0]
    base = np.empty(n)
    plus = np.empty(n)
    minus = np.empty(n)
    xa = x[a].copy()
    corrected_kernel_values(xa, x, vol, h, kind, dim, corrected, base)
    g = np.empty((n, dim))
    for j in range(dim):
        xe = xa.copy()
        xe[j] += dh
        corrected_kernel_values(xe, x, vol, h, kind, dim, corrected, plus)
        if central:
            xe[j] = xa[j] - dh
            corrected_kernel_values(xe, x, vol, h, kind, dim, corrected, minus)
            g[:, j] = (plus - minus) / (2.0 * dh)
        else:
            g[:, j] = (plus - base) / dh
    return g
