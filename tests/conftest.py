"""Test set-up. The Numba cache is keyed by source version, as for real runs: importing
pmpmsph (its `jit` module) configures it.

With `PMPMSPH_COMPILE_LOG=FILE` set, every process appends to FILE, at its end, the time it
spent compiling each kernel (exclusive of the kernels compiled inside it) and the compile
time of each test: what a cold Numba cache costs, and where (see docs/performance.md)."""
import os
import time

import pmpmsph  # noqa: F401

_LOG = os.environ.get("PMPMSPH_COMPILE_LOG")

if _LOG:
    from collections import defaultdict

    from numba.core import event

    class _CompileTimes(event.Listener):
        """Exclusive compile seconds per kernel signature, nested compiles subtracted."""

        def __init__(self):
            self.stack = []
            self.by_kernel = defaultdict(float)
            self.total = 0.0

        def on_start(self, ev):
            self.stack.append([time.perf_counter(), 0.0])

        def on_end(self, ev):
            start, inner = self.stack.pop()
            spent = time.perf_counter() - start
            d = ev.data["dispatcher"]
            name = f"{d.py_func.__module__}.{d.py_func.__qualname__}"
            self.by_kernel[name] += spent - inner
            if self.stack:
                self.stack[-1][1] += spent
            else:
                self.total += spent

    _times = _CompileTimes()
    event.register("numba:compile", _times)
    _by_test = {}

    def pytest_runtest_setup(item):
        item._compile_before = _times.total

    def pytest_runtest_teardown(item):
        before = getattr(item, "_compile_before", None)
        if before is not None and _times.total > before:
            _by_test[item.nodeid] = _times.total - before

    def pytest_sessionfinish(session):
        rank = os.environ.get("OMPI_COMM_WORLD_RANK", "-")
        worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
        with open(_LOG, "a") as fh:
            for name, s in _times.by_kernel.items():
                fh.write(f"kernel\t{worker}\t{rank}\t{s:.2f}\t{name}\n")
            for node, s in _by_test.items():
                fh.write(f"test\t{worker}\t{rank}\t{s:.2f}\t{node}\n")
