"""Wall-clock accounting: setup, JIT warm-up and run reported apart, plus per-phase totals."""
import time
from collections import defaultdict
from contextlib import contextmanager


class Timers:
    def __init__(self):
        self.total = defaultdict(float)

    @contextmanager
    def phase(self, name):
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.total[name] += time.perf_counter() - t0

    def add(self, name, seconds):
        self.total[name] += seconds

    def as_dict(self):
        return dict(self.total)
