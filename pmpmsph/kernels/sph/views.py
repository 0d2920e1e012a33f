"""The bundles the SPH kernels take instead of long argument lists.

A bundle is a plain tuple that a kernel unpacks on entry (free in the machine code), built by
one of the functions below, which name its members in order. Plain tuples rather than
`NamedTuple`s: Numba types a plain tuple of arrays in its C dispatcher (0.3 us), a
`NamedTuple` through Python (1-1.4 us each; with four of them G2P's call cost 3.6 us more a
step, a tenth of a 10-particle scene's step). A tuple tag's length stays a compile-time
constant inside a bundle, so `dim` and the kernel code still vanish from the machine code.
A term a scene does not use is an empty array, tested once per call or per pair: Numba
prunes a branch on `None` only for a function's own arguments, not for a tuple's members.
Every pair kernel takes `(smoothing, pairs, ...)`.
"""
import numpy as np

from .liu import COEF


def smoothing_of(dim_tag, kern_tag, h):
    """(dim_tag, kern_tag, h): `len(dim_tag)` is the dimension, `len(kern_tag) - 1` the
    smoothing kernel's code (`static_tags`), h the smoothing length."""
    return (dim_tag, kern_tag, h)


def pair_lists(n_query, start, index):
    """(n_query, start, index): the half neighbour lists of the owned rows [0, n_query)
    (kernels/neighbours.py): row a's partners are index[start[a]:start[a + 1]], each pair
    once."""
    return (n_query, start, index)


def pair_rows(x, v, vg, mass, rho, S, cs, method, mat):
    """What `sph_rates` reads of every row, owned then halo (`ParticleSet.with_halo`):
    position, velocity, the velocity a pair sees (a wall's ghost velocity, else v), mass,
    density, S = sigma / rho^2 (symmetric 6-vector), sound speed, method and material."""
    return (x, v, vg, mass, rho, S, cs, method, mat)


def sph_state(x, v, rho, F):
    """What an integrator stage advances: position, velocity, density and deformation
    gradient (the current rows, or their copies at the step's start)."""
    return (x, v, rho, F)


def shift_fields(gradc, lam, gradv):
    """Particle shifting's per-row state (kernels/sph/shifting.py): the concentration
    gradient grad C, the smallest eigenvalue of the renormalisation matrix (the free-surface
    indicator) and the renormalised velocity gradient."""
    return (gradc, lam, gradv)


def rate_options(corr_tag, fluid, gravity, damping, av_alpha, av_beta, want_force, want_L,
                 want_fsi, split):
    """The equations' switches and constants of `sph_rates`: `corr_tag` non-empty for the
    kernel gradient correction (compile time), `fluid` the per-material fluid trait, gravity,
    the velocity damping, the artificial viscosity's alpha and beta, which outputs to form
    (the force, the velocity gradient, the reactions on MPM points), and whether the
    delta-SPH diffusion is Fourtakas' splitting."""
    return (corr_tag, fluid, gravity, float(damping), float(av_alpha), float(av_beta),
            bool(want_force), bool(want_L), bool(want_fsi), bool(split))


#: the empty arrays that stand for absent terms (never written; made once, not per call)
_NO_ROWS6, _NO_MATRICES, _NO_LIU = np.zeros((0, 6)), np.zeros((0, 3, 3)), np.zeros((0, COEF))
_NO_VALUES, _NO_VECTORS, _NO_FLAGS = np.zeros(0), np.zeros((0, 3)), np.zeros(0, np.bool_)
#: no contact walls (kernels/sph/contact.py): (Coulomb coefficient by body, the rows' body)
NO_CONTACT = (_NO_VALUES, np.zeros(0, np.int32))


def rate_terms(R=None, as_n=1.0, w_dp=1.0, B=None, liu=None, dcoef=None, gradrho=None,
               morris_mu=None, pw=None, clamped=None, pws=None, contact=None):
    """The optional terms of `sph_rates`, empty arrays where a scene lacks them: artificial
    stress R (rows x 6) with its exponent and W(dp); Bonet-Lok's B or Liu's coefficients;
    delta-SPH's coefficient per material and the rows' density gradients; Morris' viscosity
    per material; the fluid pressure at solid points; the rows held by mirror clamps; the
    dummy walls' pressure towards solids; the contact walls (`kernels.sph.contact`): the
    Coulomb coefficient by body (< 0: a plain dummy wall) and the rows' bodies."""
    return (_NO_ROWS6 if R is None else R, float(as_n), float(w_dp),
            _NO_MATRICES if B is None else B, _NO_LIU if liu is None else liu,
            _NO_VALUES if dcoef is None else dcoef, _NO_VECTORS if gradrho is None else gradrho,
            _NO_VALUES if morris_mu is None else morris_mu, _NO_VALUES if pw is None else pw,
            _NO_FLAGS if clamped is None else clamped, _NO_VALUES if pws is None else pws,
            NO_CONTACT if contact is None else contact)


def rates(acc, drho, L, fsi=None, fcpl=None):
    """The outputs of `sph_rates`: dv/dt, drho/dt, the velocity gradient L, and the
    reactions of SPH pairs on MPM points (fsi: fluid-structure; fcpl: the conservative
    coupling; empty without)."""
    dim = acc.shape[1]
    return (acc, drho, L, np.zeros((0, dim)) if fsi is None else fsi,
            np.zeros((0, dim)) if fcpl is None else fcpl)
