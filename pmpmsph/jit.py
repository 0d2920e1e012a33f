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


def code_switch(name, args, functions, missing, **scope):
    """A compiled `def name(code, args)` that returns `functions[code](args)` (or the
    number `functions[code]` itself, for a table of constants), and runs the
    statement `missing` (with the names in `scope`) for any other code: the `if` chain over
    a registry (materials, SPH smoothing kernels), written out as source. Inlined into its
    callers at the Numba IR level, so not cached on disk itself (the callers' cache holds
    it); compiled once per process."""
    lines = [f"def {name}(code, {args}):"]
    for i, (code, function) in enumerate(sorted(functions.items())):
        lines.append(f"    {'if' if i == 0 else 'elif'} code == {code}:")
        if callable(function):
            scope[f"case{code}"] = function
            lines.append(f"        return case{code}({args})")
        else:  # a constant of the registry (a number), folded into the caller
            lines.append(f"        return {function!r}")
    lines.append(f"    {missing}")
    exec(compile("\n".join(lines), f"<generated {name}>", "exec"), scope)
    return njit(inline="always", cache=False)(scope[name])
