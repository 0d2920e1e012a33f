"""Rank-aware logging: rank 0 speaks at INFO, other ranks only at WARNING and above, each
line prefixed with the rank when more than one runs."""
import logging
import sys


def setup_logging(rank, size, level=logging.INFO):
    logger = logging.getLogger("pmpmsph")
    logger.handlers.clear()
    handler = logging.StreamHandler(sys.stderr if rank else sys.stdout)
    prefix = f"[rank {rank}] " if size > 1 else ""
    handler.setFormatter(logging.Formatter(prefix + "%(message)s"))
    logger.addHandler(handler)
    logger.setLevel(level if rank == 0 else logging.WARNING)
    logger.propagate = False
    return logger
