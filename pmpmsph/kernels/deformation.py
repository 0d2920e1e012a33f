"""Reading a particle's stored motion: the deformation gradient F (n, 3, 3), or, in a scene of
fluids only, its determinant J (n,) alone (`particles.J_FIELD`, `Case.tracks_J_only`).

A fluid's stress depends on J and the velocity gradient only (seed 003, eqs. 49-50), so such
a scene keeps 8 bytes per particle instead of 72. The kernels that need J or a 3x3 F take
whichever array the scene stores and read it through these helpers, which Numba resolves by
the array's rank while typing the caller (no branch at run time). The plain Python bodies
are what runs under NUMBA_DISABLE_JIT=1.
"""
from numba.extending import overload

from ..jit import njit
from ..materials.tensor import det3


def _stores_J(D):
    """True for J storage (rank 1), while Numba types a caller (D a type) or in Python."""
    return D.ndim == 1


def _J_stored(D, p):
    return D[p]


def _J_of_F(D, p):
    return det3(D[p])


def jacobian(D, p):
    """J = det F of particle p, from F (rank 3) or from J itself (rank 1)."""
    return _J_stored(D, p) if _stores_J(D) else _J_of_F(D, p)


def _matrix_of_J(D, p, scratch):
    scratch[0, 0] = D[p]
    return scratch


def _matrix_of_F(D, p, scratch):
    return D[p]


def deformation_matrix(D, p, scratch):
    """A 3x3 deformation gradient for particle p: F[p] itself, or (J storage) `scratch` with
    J on its first diagonal entry. The caller sets `scratch` to the identity once: a matrix
    diag(J, 1, 1) has det J, and J is all a fluid's stress and energy read (`det_minus_one`
    gives J - 1 exactly for it)."""
    return (_matrix_of_J if _stores_J(D) else _matrix_of_F)(D, p, scratch)


def advance(D, p, dim, dt, L, Fn):
    """Move particle p's stored motion over one step with velocity gradient L (3x3) and return
    the new J; `Fn` receives the new 3x3 F (J storage: diag(J, 1, 1), its other entries left
    as the identity the caller set).

    F storage: F <- (I + dt L) F (seed 003, eq. 82); in 1D/2D the out-of-plane rows and
    columns of F stay as stored. J storage: J <- det(I + dt L) J, the determinant of the same
    update (det AB = det A det B)."""
    return (_advance_J if _stores_J(D) else _advance_F)(D, p, dim, dt, L, Fn)


def _advance_J(D, p, dim, dt, L, Fn):
    J = D[p] * _det_identity_plus(dim, dt, L)
    D[p] = J
    Fn[0, 0] = J
    return J


def _advance_F(D, p, dim, dt, L, Fn):
    # on scalars: no aliasing between the small arrays and F
    for b in range(dim):
        f0 = D[p, 0, b]
        f1 = D[p, 1, b]
        f2 = D[p, 2, b]
        n0 = f0 + dt * (L[0, 0] * f0 + L[0, 1] * f1 + L[0, 2] * f2)
        n1 = f1 + dt * (L[1, 0] * f0 + L[1, 1] * f1 + L[1, 2] * f2)
        n2 = f2 + dt * (L[2, 0] * f0 + L[2, 1] * f1 + L[2, 2] * f2)
        D[p, 0, b] = n0
        Fn[0, b] = n0
        if dim > 1:
            D[p, 1, b] = n1
            Fn[1, b] = n1
        if dim > 2:
            D[p, 2, b] = n2
            Fn[2, b] = n2
    if dim < 3:
        for a in range(3):
            for b in range(dim, 3):
                Fn[a, b] = D[p, a, b]
                Fn[b, a] = D[p, b, a]
    return det3(Fn)


@njit(inline="always")
def _det_identity_plus(dim, dt, L):
    """det(I + dt L) over the first `dim` rows and columns (the others of L are 0 in 1D/2D;
    `dim` is a compile-time constant, and x * 0 is not folded away under our fastmath flags,
    so the full 3x3 formula would multiply them out)."""
    a00 = 1.0 + dt * L[0, 0]
    if dim == 1:
        return a00
    a11 = 1.0 + dt * L[1, 1]
    a01 = dt * L[0, 1]
    a10 = dt * L[1, 0]
    if dim == 2:
        return a00 * a11 - a01 * a10
    a22 = 1.0 + dt * L[2, 2]
    a02 = dt * L[0, 2]
    a12 = dt * L[1, 2]
    a20 = dt * L[2, 0]
    a21 = dt * L[2, 1]
    return (a00 * (a11 * a22 - a12 * a21) - a01 * (a10 * a22 - a12 * a20)
            + a02 * (a10 * a21 - a11 * a20))


@overload(jacobian, inline="always")
def _jacobian_typed(D, p):
    return _J_stored if _stores_J(D) else _J_of_F


@overload(deformation_matrix, inline="always")
def _deformation_matrix_typed(D, p, scratch):
    return _matrix_of_J if _stores_J(D) else _matrix_of_F


@overload(advance, inline="always")
def _advance_typed(D, p, dim, dt, L, Fn):
    return _advance_J if _stores_J(D) else _advance_F
