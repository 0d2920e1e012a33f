"""Stages: they own no data, call kernels, and ask the decomposition for exchanges."""
