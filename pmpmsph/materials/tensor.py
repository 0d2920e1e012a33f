"""Allocation-free 3x3 helpers for the constitutive kernels.

Symmetric tensors travel as 6-tuples of scalars in the order (xx, yy, zz, xy, yz, xz),
the same order as the Maxwell state vector.  Everything is written out component by
component so that the compiled code needs no temporary arrays.

The energy helpers (and the ``energy_*`` functions of the models) are compiled with
``fastmath=False``: they are written in cancellation-free forms (J - 1 from the invariants of
F - I, log1p/expm1/sinh) that reassociation would undo, and they are only used for
diagnostics.
"""
import math

import numpy as np

from ..jit import njit
from .eigen import sym_eigen

@njit(inline="always")
def det3(A):
    """Determinant of a general 3x3 array."""
    return (A[0, 0] * (A[1, 1] * A[2, 2] - A[1, 2] * A[2, 1])
            - A[0, 1] * (A[1, 0] * A[2, 2] - A[1, 2] * A[2, 0])
            + A[0, 2] * (A[1, 0] * A[2, 1] - A[1, 1] * A[2, 0]))


@njit(inline="always")
def cofactor3(f):
    """The cofactor matrix cof(F) = det(F) F^-T of a 3x3 array, row by row (9 scalars)."""
    return (f[1, 1] * f[2, 2] - f[1, 2] * f[2, 1],
            f[1, 2] * f[2, 0] - f[1, 0] * f[2, 2],
            f[1, 0] * f[2, 1] - f[1, 1] * f[2, 0],
            f[0, 2] * f[2, 1] - f[0, 1] * f[2, 2],
            f[0, 0] * f[2, 2] - f[0, 2] * f[2, 0],
            f[0, 1] * f[2, 0] - f[0, 0] * f[2, 1],
            f[0, 1] * f[1, 2] - f[0, 2] * f[1, 1],
            f[0, 2] * f[1, 0] - f[0, 0] * f[1, 2],
            f[0, 0] * f[1, 1] - f[0, 1] * f[1, 0])


@njit(inline="always")
def block_inverse(M, dim, Minv):
    """Inverse of the leading dim x dim block of M into Minv (left untouched when the
    determinant is 0); returns the determinant."""
    if dim == 1:
        d = M[0, 0]
        if d != 0.0:
            Minv[0, 0] = 1.0 / d
        return d
    if dim == 2:
        d = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
        if d != 0.0:
            s = 1.0 / d
            Minv[0, 0] = M[1, 1] * s
            Minv[1, 1] = M[0, 0] * s
            Minv[0, 1] = -M[0, 1] * s
            Minv[1, 0] = -M[1, 0] * s
        return d
    d = det3(M)
    if d != 0.0:
        s = 1.0 / d
        Minv[0, 0] = (M[1, 1] * M[2, 2] - M[1, 2] * M[2, 1]) * s
        Minv[0, 1] = (M[0, 2] * M[2, 1] - M[0, 1] * M[2, 2]) * s
        Minv[0, 2] = (M[0, 1] * M[1, 2] - M[0, 2] * M[1, 1]) * s
        Minv[1, 0] = (M[1, 2] * M[2, 0] - M[1, 0] * M[2, 2]) * s
        Minv[1, 1] = (M[0, 0] * M[2, 2] - M[0, 2] * M[2, 0]) * s
        Minv[1, 2] = (M[0, 2] * M[1, 0] - M[0, 0] * M[1, 2]) * s
        Minv[2, 0] = (M[1, 0] * M[2, 1] - M[1, 1] * M[2, 0]) * s
        Minv[2, 1] = (M[0, 1] * M[2, 0] - M[0, 0] * M[2, 1]) * s
        Minv[2, 2] = (M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]) * s
    return d


@njit(fastmath=False, inline="always")
def det_minus_one(F):
    """J - 1 = det(F) - 1 without cancellation: with H = F - I,
    det(I + H) - 1 = tr H + I2(H) + det H (I2: sum of the principal 2x2 minors)."""
    h00 = F[0, 0] - 1.0
    h11 = F[1, 1] - 1.0
    h22 = F[2, 2] - 1.0
    i2 = (h00 * h11 + h11 * h22 + h00 * h22
          - F[0, 1] * F[1, 0] - F[1, 2] * F[2, 1] - F[0, 2] * F[2, 0])
    i3 = (h00 * (h11 * h22 - F[1, 2] * F[2, 1])
          - F[0, 1] * (F[1, 0] * h22 - F[1, 2] * F[2, 0])
          + F[0, 2] * (F[1, 0] * F[2, 1] - h11 * F[2, 0]))
    return (h00 + h11 + h22) + i2 + i3


@njit(fastmath=False)
def trace_C_minus_three(F):
    """tr(F^T F) - 3 = |F - I|^2 + 2 tr(F - I), accurate for small strain."""
    s = 0.0
    for i in range(3):
        for j in range(3):
            h = F[i, j] - 1.0 if i == j else F[i, j]
            s += h * h
    return s + 2.0 * ((F[0, 0] - 1.0) + (F[1, 1] - 1.0) + (F[2, 2] - 1.0))


@njit(inline="always")
def sym_det(xx, yy, zz, xy, yz, xz):
    """Determinant of a symmetric tensor given by its 6 components."""
    return (xx * yy * zz + 2.0 * xy * yz * xz
            - xx * yz * yz - yy * xz * xz - zz * xy * xy)


@njit(inline="always")
def sym_inv(xx, yy, zz, xy, yz, xz):
    """Inverse of a symmetric tensor (6-tuple in, 6-tuple out) via the adjugate."""
    cxx = yy * zz - yz * yz
    cyy = xx * zz - xz * xz
    czz = xx * yy - xy * xy
    cxy = yz * xz - xy * zz
    cyz = xy * xz - xx * yz
    cxz = xy * yz - yy * xz
    d = xx * cxx + xy * cxy + xz * cxz
    r = 1.0 / d
    return cxx * r, cyy * r, czz * r, cxy * r, cyz * r, cxz * r


@njit(inline="always")
def right_cauchy_green(F):
    """C = F^T F as a 6-tuple."""
    cxx = F[0, 0] * F[0, 0] + F[1, 0] * F[1, 0] + F[2, 0] * F[2, 0]
    cyy = F[0, 1] * F[0, 1] + F[1, 1] * F[1, 1] + F[2, 1] * F[2, 1]
    czz = F[0, 2] * F[0, 2] + F[1, 2] * F[1, 2] + F[2, 2] * F[2, 2]
    cxy = F[0, 0] * F[0, 1] + F[1, 0] * F[1, 1] + F[2, 0] * F[2, 1]
    cyz = F[0, 1] * F[0, 2] + F[1, 1] * F[1, 2] + F[2, 1] * F[2, 2]
    cxz = F[0, 0] * F[0, 2] + F[1, 0] * F[1, 2] + F[2, 0] * F[2, 2]
    return cxx, cyy, czz, cxy, cyz, cxz


@njit(inline="always")
def left_cauchy_green(F):
    """B = F F^T as a 6-tuple."""
    bxx = F[0, 0] * F[0, 0] + F[0, 1] * F[0, 1] + F[0, 2] * F[0, 2]
    byy = F[1, 0] * F[1, 0] + F[1, 1] * F[1, 1] + F[1, 2] * F[1, 2]
    bzz = F[2, 0] * F[2, 0] + F[2, 1] * F[2, 1] + F[2, 2] * F[2, 2]
    bxy = F[0, 0] * F[1, 0] + F[0, 1] * F[1, 1] + F[0, 2] * F[1, 2]
    byz = F[1, 0] * F[2, 0] + F[1, 1] * F[2, 1] + F[1, 2] * F[2, 2]
    bxz = F[0, 0] * F[2, 0] + F[0, 1] * F[2, 1] + F[0, 2] * F[2, 2]
    return bxx, byy, bzz, bxy, byz, bxz


@njit(inline="always")
def push_forward_sym(F, sxx, syy, szz, sxy, syz, sxz):
    """F S F^T for a symmetric S (6-tuple in, 6-tuple out)."""
    # rows of G = F S
    g00 = F[0, 0] * sxx + F[0, 1] * sxy + F[0, 2] * sxz
    g01 = F[0, 0] * sxy + F[0, 1] * syy + F[0, 2] * syz
    g02 = F[0, 0] * sxz + F[0, 1] * syz + F[0, 2] * szz
    g10 = F[1, 0] * sxx + F[1, 1] * sxy + F[1, 2] * sxz
    g11 = F[1, 0] * sxy + F[1, 1] * syy + F[1, 2] * syz
    g12 = F[1, 0] * sxz + F[1, 1] * syz + F[1, 2] * szz
    g20 = F[2, 0] * sxx + F[2, 1] * sxy + F[2, 2] * sxz
    g21 = F[2, 0] * sxy + F[2, 1] * syy + F[2, 2] * syz
    g22 = F[2, 0] * sxz + F[2, 1] * syz + F[2, 2] * szz
    # G F^T (symmetric)
    xx = g00 * F[0, 0] + g01 * F[0, 1] + g02 * F[0, 2]
    yy = g10 * F[1, 0] + g11 * F[1, 1] + g12 * F[1, 2]
    zz = g20 * F[2, 0] + g21 * F[2, 1] + g22 * F[2, 2]
    xy = g00 * F[1, 0] + g01 * F[1, 1] + g02 * F[1, 2]
    yz = g10 * F[2, 0] + g11 * F[2, 1] + g12 * F[2, 2]
    xz = g00 * F[2, 0] + g01 * F[2, 1] + g02 * F[2, 2]
    return xx, yy, zz, xy, yz, xz


@njit(inline="always")
def store_sym(sigma, xx, yy, zz, xy, yz, xz):
    """Write a symmetric tensor (6 scalars) into the 3x3 array `sigma`."""
    sigma[0, 0] = xx
    sigma[1, 1] = yy
    sigma[2, 2] = zz
    sigma[0, 1] = xy
    sigma[1, 0] = xy
    sigma[1, 2] = yz
    sigma[2, 1] = yz
    sigma[0, 2] = xz
    sigma[2, 0] = xz


@njit(inline="always")
def inv_cbrt_sq(J):
    """J^(-2/3), defined through the real cube root (finite also for J < 0)."""
    return 1.0 / np.cbrt(J * J)


@njit(inline="always")
def hartmann_neff_cauchy(bxx, byy, bzz, bxy, byz, bxz, J, mu, k, sigma):
    """sigma = [mu dev(b) + k/10 (J^5 - J^-5) 1] / J for a unimodular b
    (Shutov & Klyuchantsev, seed 004, eq. 11; used with b = B-bar by the
    hyperelastic model and with b = B-bar_e by the Maxwell model)."""
    tr3 = (bxx + byy + bzz) * (1.0 / 3.0)
    J2 = J * J
    J5 = J2 * J2 * J
    vol = 0.1 * k * (J5 - 1.0 / J5)
    rJ = 1.0 / J
    store_sym(sigma,
              (mu * (bxx - tr3) + vol) * rJ,
              (mu * (byy - tr3) + vol) * rJ,
              (mu * (bzz - tr3) + vol) * rJ,
              mu * bxy * rJ, mu * byz * rJ, mu * bxz * rJ)


@njit(fastmath=False)
def hartmann_neff_volumetric_energy(lnJ, k):
    """k/50 (J^5 + J^-5 - 2) (seed 004, eq. 12), evaluated as the identical
    k/50 (2 sinh(5/2 ln J))^2, which has no cancellation near J = 1."""
    s = np.sinh(2.5 * lnJ)
    return 0.08 * k * s * s


@njit
def max_keep_nan(a, b):
    """max(a, b) that returns NaN if b is NaN (so an invalid J is not masked)."""
    return a if a >= b else b


#: added to the half-gap R of a plane x-y block before 1/R (`hencky_trial`)
_R0 = 1e-300


@njit(inline="always")
def congruence(a, s):
    """A S A^T as (xx, yy, zz, xy, yz, xz) for A a row-major 9-tuple and S symmetric
    (xx, yy, zz, xy, yz, xz)."""
    sxx, syy, szz, sxy, syz, sxz = s
    m00 = a[0] * sxx + a[1] * sxy + a[2] * sxz
    m01 = a[0] * sxy + a[1] * syy + a[2] * syz
    m02 = a[0] * sxz + a[1] * syz + a[2] * szz
    m10 = a[3] * sxx + a[4] * sxy + a[5] * sxz
    m11 = a[3] * sxy + a[4] * syy + a[5] * syz
    m12 = a[3] * sxz + a[4] * syz + a[5] * szz
    m20 = a[6] * sxx + a[7] * sxy + a[8] * sxz
    m21 = a[6] * sxy + a[7] * syy + a[8] * syz
    m22 = a[6] * sxz + a[7] * syz + a[8] * szz
    return (m00 * a[0] + m01 * a[1] + m02 * a[2],
            m10 * a[3] + m11 * a[4] + m12 * a[5],
            m20 * a[6] + m21 * a[7] + m22 * a[8],
            m00 * a[3] + m01 * a[4] + m02 * a[5],
            m10 * a[6] + m11 * a[7] + m12 * a[8],
            m00 * a[6] + m01 * a[7] + m02 * a[8])


@njit(inline="always")
def hencky_trial(F, state):
    """The trial state of the multiplicative plasticity models (materials/von_mises.py,
    materials/drucker_prager.py): the elastic left Cauchy-Green tensor of the last stored
    state, be (state[0:6], xx, yy, zz, xy, yz, xz), pushed forward by the relative
    deformation f = F Fn^-1 since it was stored (Fn, state[8:17] row-major): the trial
    be_t = f be f^T (Simo 1992, eq. 4.4). Returns the principal logarithmic strains
    e_i = ln(lambda_i)/2 of be_t, their directions V (row-major 9-tuple, eigenvectors as
    columns), be_t itself and whether the step is plane (below).

    Why the relative form, not be = F Cp^-1 F^T from the plastic Cp^-1: after long shear F
    and Cp^-1 grow without bound while be stays near the identity, and the product loses
    every digit (a sheared Drucker-Prager block reached entries of 1e3 in F, 1e6 in Cp^-1,
    and NaN); f is near the identity every step and Fn^-1 is formed once, from a matrix of
    determinant J.

    Plane (F, Fn and be without xz, yz coupling: every particle of a 2D run, tested entry
    by entry, so a 3D particle that happens to be plane takes it too): the same formulas
    on the x-y blocks, f_zz = F_zz / Fn_zz, and the eigenvalues of the x-y block
    mean +- R in closed form; V then holds (cos 2 phi, sin 2 phi) of the first direction
    in V[0], V[1] (what `store_return` reads when `plane`), not the vectors. A third of
    the arithmetic of the 3D path."""
    if (F[0, 2] == 0.0 and F[1, 2] == 0.0 and F[2, 0] == 0.0 and F[2, 1] == 0.0
            and state[4] == 0.0 and state[5] == 0.0 and state[10] == 0.0
            and state[13] == 0.0 and state[14] == 0.0 and state[15] == 0.0):
        n00, n01, n10, n11, n22 = state[8], state[9], state[11], state[12], state[16]
        d = n00 * n11 - n01 * n10
        r = 1.0 / (d * n22)  # one division for 1/d and 1/n22
        rd = r * n22
        f00 = rd * (F[0, 0] * n11 - F[0, 1] * n10)
        f01 = rd * (F[0, 1] * n00 - F[0, 0] * n01)
        f10 = rd * (F[1, 0] * n11 - F[1, 1] * n10)
        f11 = rd * (F[1, 1] * n00 - F[1, 0] * n01)
        f22 = F[2, 2] * (r * d)
        bxx, byy, bxy = state[0], state[1], state[3]
        g00 = f00 * bxx + f01 * bxy
        g01 = f00 * bxy + f01 * byy
        g10 = f10 * bxx + f11 * bxy
        g11 = f10 * bxy + f11 * byy
        xx = g00 * f00 + g01 * f01
        yy = g10 * f10 + g11 * f11
        xy = g00 * f10 + g01 * f11
        zz = f22 * f22 * state[2]
        # eigen-pairs of the x-y block in the double angle 2 phi of its first direction
        # (cos phi, sin phi): block = mean 1 + R [[cos 2phi, sin 2phi], [sin 2phi,
        # -cos 2phi]]; one square root and one division (the tiny R0 keeps 0/0 out at
        # R = 0, where the two strains are equal and the angle is not used)
        h = 0.5 * (xx - yy)
        R = math.sqrt(h * h + xy * xy)
        mean = 0.5 * (xx + yy)
        rR = 1.0 / (R + _R0)
        return ((0.5 * math.log(mean + R), 0.5 * math.log(mean - R), 0.5 * math.log(zz)),
                (h * rR, xy * rR, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0),
                (xx, yy, zz, xy, 0.0, 0.0), True)
    n00, n01, n02 = state[8], state[9], state[10]
    n10, n11, n12 = state[11], state[12], state[13]
    n20, n21, n22 = state[14], state[15], state[16]
    c00 = n11 * n22 - n12 * n21  # cofactors of Fn: Fn^-1 = cof(Fn)^T / det Fn
    c01 = n12 * n20 - n10 * n22
    c02 = n10 * n21 - n11 * n20
    c10 = n02 * n21 - n01 * n22
    c11 = n00 * n22 - n02 * n20
    c12 = n01 * n20 - n00 * n21
    c20 = n01 * n12 - n02 * n11
    c21 = n02 * n10 - n00 * n12
    c22 = n00 * n11 - n01 * n10
    r = 1.0 / (n00 * c00 + n01 * c01 + n02 * c02)
    f = (r * (F[0, 0] * c00 + F[0, 1] * c01 + F[0, 2] * c02),
         r * (F[0, 0] * c10 + F[0, 1] * c11 + F[0, 2] * c12),
         r * (F[0, 0] * c20 + F[0, 1] * c21 + F[0, 2] * c22),
         r * (F[1, 0] * c00 + F[1, 1] * c01 + F[1, 2] * c02),
         r * (F[1, 0] * c10 + F[1, 1] * c11 + F[1, 2] * c12),
         r * (F[1, 0] * c20 + F[1, 1] * c21 + F[1, 2] * c22),
         r * (F[2, 0] * c00 + F[2, 1] * c01 + F[2, 2] * c02),
         r * (F[2, 0] * c10 + F[2, 1] * c11 + F[2, 2] * c12),
         r * (F[2, 0] * c20 + F[2, 1] * c21 + F[2, 2] * c22))
    be = congruence(f, (state[0], state[1], state[2], state[3], state[4], state[5]))
    w, V = sym_eigen(be[0], be[1], be[2], be[3], be[4], be[5])
    return (0.5 * math.log(w[0]), 0.5 * math.log(w[1]), 0.5 * math.log(w[2])), V, be, False


@njit(inline="always")
def hencky_split(e):
    """(tr e, tr e / 3, the deviatoric parts d0, d1, d2) of principal strains e."""
    ev = e[0] + e[1] + e[2]
    m = ev * (1.0 / 3.0)
    return ev, m, e[0] - m, e[1] - m, e[2] - m


@njit(inline="always")
def _principal_plane(c2, s2, t0, t1, t2):
    """sum t_i n_i n_i^T with n_0 = (cos phi, sin phi, 0), n_1 = (-sin phi, cos phi, 0),
    n_2 = e_z, from (c2, s2) = (cos 2 phi, sin 2 phi) (the plane case of `hencky_trial`),
    as (xx, yy, zz, xy, yz, xz)."""
    mean = 0.5 * (t0 + t1)
    half = 0.5 * (t0 - t1)
    return mean + half * c2, mean - half * c2, t2, half * s2, 0.0, 0.0


@njit(inline="always")
def store_return(F, V, be, plane, p, G, m, d0, d1, d2, plastic, state, sigma):
    """The end of a return of the plasticity models: sigma = tau / J with the Kirchhoff stress
    tau = p 1 + 2 G dev e (principal deviatoric strains d_i in the directions V), and the
    state the next call starts from: be (the trial `be` after an elastic step; after plastic
    flow V diag(exp(2 (m + d_i))) V^T, the returned elastic strains), Fn = F, and
    state[7] = 1 after plastic flow, else 0 (the `yielding` output field). `plane`: V and
    F as in the plane case of `hencky_trial` (V the double angle; zeros not multiplied
    out)."""
    t0 = p + 2.0 * G * d0
    t1 = p + 2.0 * G * d1
    t2 = p + 2.0 * G * d2
    if plane:
        rJ = 1.0 / ((F[0, 0] * F[1, 1] - F[0, 1] * F[1, 0]) * F[2, 2])
        sg = _principal_plane(V[0], V[1], rJ * t0, rJ * t1, rJ * t2)
        if plastic:
            be = _principal_plane(V[0], V[1], math.exp(2.0 * (m + d0)),
                                  math.exp(2.0 * (m + d1)), math.exp(2.0 * (m + d2)))
    else:
        rJ = 1.0 / det3(F)
        sg = congruence(V, (rJ * t0, rJ * t1, rJ * t2, 0.0, 0.0, 0.0))
        if plastic:
            be = congruence(V, (math.exp(2.0 * (m + d0)), math.exp(2.0 * (m + d1)),
                                math.exp(2.0 * (m + d2)), 0.0, 0.0, 0.0))
    store_sym(sigma, sg[0], sg[1], sg[2], sg[3], sg[4], sg[5])
    # written out: a tuple indexed by a loop variable compiles to a switch per entry (this
    # store cost as much as the rest of the return)
    state[0] = be[0]
    state[1] = be[1]
    state[2] = be[2]
    state[3] = be[3]
    state[4] = be[4]
    state[5] = be[5]
    state[7] = 1.0 if plastic else 0.0
    state[8] = F[0, 0]
    state[9] = F[0, 1]
    state[10] = F[0, 2]
    state[11] = F[1, 0]
    state[12] = F[1, 1]
    state[13] = F[1, 2]
    state[14] = F[2, 0]
    state[15] = F[2, 1]
    state[16] = F[2, 2]
