"""The closed-form eigen-pairs of a symmetric 3x3 matrix (`sym_eigen`), for the trial
state of the plasticity models (`tensor.hencky_trial`; docs/plasticity.md, "Cost per
particle-step"), and the 2x2 Jacobi rotation it is built from."""
import math

from ..jit import njit


@njit(inline="always")
def _rotation(app, aqq, apq):
    """(c, s, a_pp', a_qq') of the Jacobi rotation that zeroes a_pq (Numerical Recipes,
    section 11.1, eqs. 11.1.8-11.1.14): the closed-form eigen-pairs of the symmetric 2x2
    [[app, apq], [apq, aqq]], eigenvalue a_pp' with vector (c, -s), a_qq' with (s, c)."""
    if apq == 0.0:
        return 1.0, 0.0, app, aqq
    theta = (aqq - app) / (2.0 * apq)
    t = math.copysign(1.0 / (abs(theta) + math.sqrt(theta * theta + 1.0)), theta)
    c = 1.0 / math.sqrt(t * t + 1.0)
    return c, t * c, app - t * apq, aqq + t * apq


#: g(h) = 2 cos(acos(h) / 3) on [0, 1] ~ _G0 + _G1 h + _G2 h^2 (through h = 0, 1/2, 1)
_G0 = math.sqrt(3.0)
_G2 = 2.0 * (2.0 - 4.0 * math.cos(math.pi / 9.0) + _G0)
_G1 = 2.0 - _G0 - _G2


@njit(inline="always")
def _cross(a0, a1, a2, b0, b1, b2):
    """a x b."""
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@njit(inline="always")
def _sym_times(c00, c11, c22, c01, c12, c02, u0, u1, u2):
    """C u for the symmetric C."""
    return (c00 * u0 + c01 * u1 + c02 * u2, c01 * u0 + c11 * u1 + c12 * u2,
            c02 * u0 + c12 * u1 + c22 * u2)


@njit(inline="always")
def _longer(x0, x1, x2, n, y0, y1, y2):
    """(y, |y|^2) if |y|^2 > n = |x|^2, else (x, n), by arithmetic, not a branch (exact:
    one of the two products is 0)."""
    ny = y0 * y0 + y1 * y1 + y2 * y2
    big = 0.5 + math.copysign(0.5, ny - n)
    small = 1.0 - big
    return (big * y0 + small * x0, big * y1 + small * x1, big * y2 + small * x2,
            big * ny + small * n)


@njit
def sym_eigen(xx, yy, zz, xy, yz, xz):
    """Eigenvalues (w0, w1, w2) and eigenvectors (the columns of V, row-major 9-tuple) of a
    symmetric 3x3 matrix in closed form, to round-off (no ordering).

    Block-diagonal (yz = xz = 0: plane strain in x-y, and every diagonal matrix): the 2x2
    block by one Jacobi rotation, which diagonalises a 2x2 exactly (Numerical Recipes,
    section 11.1, eqs. 11.1.8-11.1.14: the stable tangent t = sgn(theta) / (|theta| +
    sqrt(theta^2 + 1)); the eigenvalues a_pp - t a_pq, a_qq + t a_pq without cancellation);
    zz is the third eigenvalue, e_z its vector. A multiple of the identity keeps the
    identity frame exactly.

    Otherwise (Smith 1961, "Eigenvalues of a symmetric 3x3 matrix", CACM 4(4) 168; the
    order of the steps after Eberly 2014, "A robust eigensolver for 3x3 symmetric
    matrices", Geometric Tools): with m = tr A / 3, p = sqrt(tr (A - m 1)^2 / 6) and
    C = (A - m 1) / p (tr C = 0, tr C^2 = 6), the eigenvalues of C are the roots of
    beta^3 - 3 beta - 2 h = 0, h = det C / 2 in [-1, 1], i.e. 2 cos(phi + 2 pi k / 3),
    phi = acos(h) / 3. Only the eigenvalue farthest from the other two is taken from
    this (the largest if h >= 0, else the smallest; solved by Newton's method, see
    below): its error is round-off for every h, while the two others lose half the
    digits when they nearly coincide (d acos / dh is unbounded at h = +-1). Its
    eigenvector is the largest cross product of two rows of C - beta 1 (their rank is 2:
    the gap from beta to the nearer other eigenvalue is 2 sqrt 3 sin(phi + 2 pi / 3) >=
    sqrt 3 for the one chosen, so the vector is accurate to round-off), and the
    other two pairs come from the 2x2 matrix of C on the plane orthogonal to it, by the
    Jacobi rotation above: accurate even for a double eigenvalue, where the 2x2 is a
    multiple of the identity and any orthonormal pair in that plane is an answer.

    A plain call, not inlined at Numba's IR level: its size, inlined into every model of
    the kernels that switch over all of them at run time (SPH's stress, MPM's F-bar), made
    their compilation exceed ten minutes (scalars in, a tuple out: no reference counting).

    Jacobi sweeps (the former method here) cost 2-3x as much in 3D (4-5 sweeps of three
    rotations, each with two square roots and two divisions in a dependent chain)."""
    if yz == 0.0 and xz == 0.0:
        c, s, w0, w1 = _rotation(xx, yy, xy)
        return (w0, w1, zz), (c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0)
    m = (xx + yy + zz) * (1.0 / 3.0)
    b00 = xx - m
    b11 = yy - m
    b22 = zz - m
    p2 = (b00 * b00 + b11 * b11 + b22 * b22
          + 2.0 * (xy * xy + yz * yz + xz * xz)) * (1.0 / 6.0)
    if not p2 > 0.0:  # off-diagonals below 1e-154 (their squares underflow), or NaN
        return (xx, yy, zz), (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    p = math.sqrt(p2)
    r = 1.0 / p
    c00 = b00 * r
    c11 = b11 * r
    c22 = b22 * r
    c01 = xy * r
    c12 = yz * r
    c02 = xz * r
    h = 0.5 * (c00 * (c11 * c22 - c12 * c12) - c01 * (c01 * c22 - c12 * c02)
               + c02 * (c01 * c12 - c11 * c02))
    # the separated root beta of beta^3 - 3 beta - 2 h = 0 (the characteristic polynomial
    # of C): +-g(|h|), g the largest root for |h|, by three Newton steps from a quadratic
    # fit of g = 2 cos(acos(|h|) / 3) (error 1.0e-3, then 8.6e-7, 6e-13, round-off: the
    # derivative 3 (g^2 - 1) >= 6 on [sqrt 3, 2]); acos and cos cost 5x as much
    ha = abs(h)
    beta = _G0 + ha * (_G1 + ha * _G2)
    for _ in range(3):
        b2 = beta * beta
        beta -= (beta * (b2 - 3.0) - 2.0 * ha) / (3.0 * (b2 - 1.0))
    beta = math.copysign(beta, h)  # h >= 0: the largest eigenvalue, else the smallest
    # eigenvector: the longest cross product of two rows of C - beta 1
    d00 = c00 - beta
    d11 = c11 - beta
    d22 = c22 - beta
    # (selected without a branch: a mispredicted branch here, behind the dependent chain of
    # divisions above, cost more than all the arithmetic of this function)
    x0, x1, x2 = _cross(d00, c01, c02, c01, d11, c12)
    n = x0 * x0 + x1 * x1 + x2 * x2
    y0, y1, y2 = _cross(d00, c01, c02, c02, c12, d22)
    x0, x1, x2, n = _longer(x0, x1, x2, n, y0, y1, y2)
    y0, y1, y2 = _cross(c01, d11, c12, c02, c12, d22)
    x0, x1, x2, n = _longer(x0, x1, x2, n, y0, y1, y2)
    k = 1.0 / math.sqrt(n)
    v0 = x0 * k
    v1 = x1 * k
    v2 = x2 * k
    # an orthonormal pair (u, w) orthogonal to the unit v, without a branch (Duff et al.
    # 2017, "Building an orthonormal basis, revisited", JCGT 6(1), listing 3)
    sg = math.copysign(1.0, v2)
    a = -1.0 / (sg + v2)
    b = v0 * v1 * a
    u0, u1, u2 = 1.0 + sg * v0 * v0 * a, sg * b, -sg * v0
    t0, t1, t2 = b, sg + v1 * v1 * a, -v1
    # C u and C w, then the 2x2 [[u.Cu, u.Cw], [u.Cw, w.Cw]]
    cu0, cu1, cu2 = _sym_times(c00, c11, c22, c01, c12, c02, u0, u1, u2)
    cw0, cw1, cw2 = _sym_times(c00, c11, c22, c01, c12, c02, t0, t1, t2)
    c, s, mu1, mu2 = _rotation(u0 * cu0 + u1 * cu1 + u2 * cu2,
                               t0 * cw0 + t1 * cw1 + t2 * cw2,
                               u0 * cw0 + u1 * cw1 + u2 * cw2)
    # the rotated pair (columns c u - s w and s u + c w, as the 2x2 case above)
    return ((m + p * beta, m + p * mu1, m + p * mu2),
            (v0, c * u0 - s * t0, s * u0 + c * t0,
             v1, c * u1 - s * t1, s * u1 + c * t1,
             v2, c * u2 - s * t2, s * u2 + c * t2))
