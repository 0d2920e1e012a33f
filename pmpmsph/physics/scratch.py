"""Scratch arrays a stage reuses from step to step (no allocation per step)."""
import numpy as np


def rows_at_least(buf, n):
    """`buf` if it has n rows or more, else a zeroed array of the same row shape with room
    to grow (twice the old rows, at least n): scratch that is reallocated O(log n) times."""
    if len(buf) >= n:
        return buf
    return np.zeros((max(n, 2 * len(buf)),) + buf.shape[1:], dtype=buf.dtype)
