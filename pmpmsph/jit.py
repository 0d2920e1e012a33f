"""All Numba JIT options live here (PySDM style): kernels import `njit` from this module.

`NUMBA_DISABLE_JIT=1` turns every kernel into plain Python, and the test suite still passes
(slowly) that way. The on-disk cache is per rank when several ranks compile at once
(see `pmpmsph.parallel.distributor.configure_numba_cache`).
"""
import numba

#: options for every compiled kernel: fastmath without `nnan`/`ninf` so NaN checks still work
JIT_OPTIONS = dict(
    cache=True,
    nogil=True,
    error_model="numpy",
    boundscheck=False,
    fastmath={"nsz", "arcp", "contract", "afn", "reassoc"},
)


def njit(*args, **kwargs):
    """`numba.njit` with the project's options (keyword arguments override them)."""
    opts = dict(JIT_OPTIONS)
    opts.update(kwargs)
    if args and callable(args[0]):
        return numba.njit(**opts)(args[0])
    return numba.njit(*args, **opts)
