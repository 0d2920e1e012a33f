"""Test set-up: the Numba cache is keyed by source version and rank, as for real runs."""
from pmpmsph.parallel.distributor import configure_numba_cache

configure_numba_cache()
