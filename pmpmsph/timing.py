"""Wall-clock accounting: setup, JIT warm-up and run reported apart, plus per-phase totals."""
import time
from collections import defaultdict


class _Phase:
    """The context of one named phase, made once and reused (a step enters a dozen phases:
    a generator-based context manager cost about 1.3 us each)."""
    __slots__ = ("total", "name", "starts")

    def __init__(self, total, name):
        self.total = total
        self.name = name
        self.starts = []  # (a stack: a phase may be entered again inside itself)

    def __enter__(self):
        self.starts.append(time.perf_counter())

    def __exit__(self, *exc):
        self.total[self.name] += time.perf_counter() - self.starts.pop()
        return False


class Timers:
    def __init__(self):
        self.total = defaultdict(float)
        self._phases = {}

    def phase(self, name):
        """`with timers.phase("p2g"): ...` adds the block's wall time to `total["p2g"]`."""
        ph = self._phases.get(name)
        if ph is None:
            ph = self._phases[name] = _Phase(self.total, name)
        return ph

    def add(self, name, seconds):
        self.total[name] += seconds

    def as_dict(self):
        return dict(self.total)
