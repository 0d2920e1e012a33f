"""Monaghan's artificial stress against the tensile instability of SPH solids (Gray, Monaghan
& Swift 2001): the per-particle stress R_a from the tensile principal stresses, which the
pair loop of `kernels.sph.rates.sph_rates` adds as eps f^n (R_a + R_b); with the 3x3 Jacobi
eigen-solver it needs."""
import numpy as np

from ...jit import njit


@njit
def sym_eig3(A):
    """Eigenvalues w and eigenvectors (columns of V) of a symmetric 3x3 matrix by cyclic
    Jacobi rotations (no LAPACK needed; converges to round-off in a few sweeps)."""
    M = np.empty((3, 3))
    V = np.eye(3)
    for i in range(3):
        for j in range(3):
            M[i, j] = 0.5 * (A[i, j] + A[j, i])
    for _sweep in range(30):
        off = M[0, 1] ** 2 + M[0, 2] ** 2 + M[1, 2] ** 2
        scale = M[0, 0] ** 2 + M[1, 1] ** 2 + M[2, 2] ** 2
        if off <= 1e-30 * scale or off == 0.0:
            break
        for p in range(2):
            for q in range(p + 1, 3):
                if M[p, q] == 0.0:
                    continue
                theta = 0.5 * np.arctan2(2.0 * M[p, q], M[q, q] - M[p, p])
                c = np.cos(theta)
                s = np.sin(theta)
                for k in range(3):  # M <- M J
                    mkp = M[k, p]
                    mkq = M[k, q]
                    M[k, p] = c * mkp - s * mkq
                    M[k, q] = s * mkp + c * mkq
                for k in range(3):  # M <- J^T M
                    mpk = M[p, k]
                    mqk = M[q, k]
                    M[p, k] = c * mpk - s * mqk
                    M[q, k] = s * mpk + c * mqk
                for k in range(3):
                    vkp = V[k, p]
                    vkq = V[k, q]
                    V[k, p] = c * vkp - s * vkq
                    V[k, q] = s * vkp + c * vkq
    w = np.empty(3)
    for i in range(3):
        w[i] = M[i, i]
    return w, V


@njit
def artificial_stress(dim, n, sigma, rho, eps, R):
    """R_a = -eps sigma'_ii / rho^2 on the tensile principal stresses, rotated back
    (Gray, Monaghan & Swift 2001, eqs. 23-25); zero for compressive ones. R is stored as
    the symmetric 6-vector (xx, yy, zz, xy, yz, xz)."""
    for a in range(n):
        for i in range(6):
            R[a, i] = 0.0
        s = -eps / (rho[a] * rho[a])
        if dim == 1:
            if sigma[a, 0, 0] > 0.0:
                R[a, 0] = s * sigma[a, 0, 0]
            continue
        if dim == 2:
            sxx = sigma[a, 0, 0]
            syy = sigma[a, 1, 1]
            sxy = sigma[a, 0, 1]
            theta = 0.5 * np.arctan2(2.0 * sxy, sxx - syy)
            c = np.cos(theta)
            sn = np.sin(theta)
            s1 = c * c * sxx + 2.0 * c * sn * sxy + sn * sn * syy
            s2 = sn * sn * sxx - 2.0 * c * sn * sxy + c * c * syy
            r1 = s * s1 if s1 > 0.0 else 0.0
            r2 = s * s2 if s2 > 0.0 else 0.0
            R[a, 0] = c * c * r1 + sn * sn * r2
            R[a, 1] = sn * sn * r1 + c * c * r2
            R[a, 3] = c * sn * (r1 - r2)
            continue
        w, V = sym_eig3(sigma[a])
        for k in range(3):
            if w[k] > 0.0:
                rk = s * w[k]
                R[a, 0] += rk * V[0, k] * V[0, k]
                R[a, 1] += rk * V[1, k] * V[1, k]
                R[a, 2] += rk * V[2, k] * V[2, k]
                R[a, 3] += rk * V[0, k] * V[1, k]
                R[a, 4] += rk * V[1, k] * V[2, k]
                R[a, 5] += rk * V[0, k] * V[2, k]
