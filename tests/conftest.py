"""Test set-up. The Numba cache is keyed by source version, as for real runs: importing
pmpmsph (its `jit` module) configures it."""
import pmpmsph  # noqa: F401
