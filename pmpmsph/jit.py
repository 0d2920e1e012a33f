"""All Numba JIT options live here (PySDM style): kernels import `njit` from this module.

`NUMBA_DISABLE_JIT=1` turns every kernel into plain Python, and the test suite still passes
(slowly) that way. Importing this module points Numba's on-disk cache at a folder per source
version (`configure_numba_cache`), before any kernel is decorated.
"""
import hashlib
import os

import numba

#: where every compiled function lives (kernels may only import numpy, numba, math and these)
JIT_SOURCES = ("kernels", "materials", "jit.py")


def _source_digest():
    """Hash of the compiled sources: Numba's cache only notices changes in a kernel's own
    file, not in the kernels it calls, so the cache directory is keyed by all of them."""
    root = os.path.dirname(os.path.abspath(__file__))
    h = hashlib.sha1()
    for entry in JIT_SOURCES:
        path = os.path.join(root, entry)
        files = [path] if path.endswith(".py") else sorted(
            os.path.join(folder, name) for folder, _, names in os.walk(path)
            for name in names if name.endswith(".py"))
        for name in sorted(files):
            with open(name, "rb") as fh:
                h.update(fh.read())
    return h.hexdigest()[:12]


def configure_numba_cache():
    """Point Numba's cache at `$NUMBA_CACHE_DIR/<source digest>` (default base
    ~/.cache/pmpmsph-numba).

    Per source version, so that an edited callee never leaves a stale compiled caller behind
    (Numba only watches a kernel's own file). All ranks share it: `Simulation` compiles on
    rank 0 first and the other ranks then only read (see `warmup.compile_kernels`). Numba
    chooses a kernel's cache folder when the kernel is decorated, and reads NUMBA_CACHE_DIR
    only when numba is first imported: so this runs when this module is imported (before any
    kernel exists) and sets numba's config as well as the environment (child processes,
    mpirun's ranks). Idempotent: a child that inherits the setting keeps it.
    """
    if not os.environ.get("PMPMSPH_CACHE_SET"):
        base = os.environ.get("NUMBA_CACHE_DIR") or os.path.join(
            os.path.expanduser("~"), ".cache", "pmpmsph-numba")
        os.environ["NUMBA_CACHE_DIR"] = os.path.join(base, _source_digest())
        os.environ["PMPMSPH_CACHE_SET"] = "1"
    numba.config.CACHE_DIR = os.environ["NUMBA_CACHE_DIR"]


configure_numba_cache()

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
    a registry (materials, SPH smoothing kernels), written out as source. `missing=None`
    when no other code can occur (a set known at compile time): the last entry is then
    the `else`, and a single entry is called without a test. Inlined into its
    callers at the Numba IR level, so not cached on disk itself (the callers' cache holds
    it); compiled once per process."""
    lines = [f"def {name}(code, {args}):"]
    entries = sorted(functions.items())
    for i, (code, function) in enumerate(entries):
        if missing is None and i == len(entries) - 1:
            lines.append("    if True:" if i == 0 else "    else:")
        else:
            lines.append(f"    {'if' if i == 0 else 'elif'} code == {code}:")
        if callable(function):
            scope[f"case{code}"] = function
            lines.append(f"        return case{code}({args})")
        else:  # a constant of the registry (a number), folded into the caller
            lines.append(f"        return {function!r}")
    if missing is not None:
        lines.append(f"    {missing}")
    exec(compile("\n".join(lines), f"<generated {name}>", "exec"), scope)
    return njit(inline="always", cache=False)(scope[name])
