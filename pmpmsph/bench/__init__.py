"""Benchmarks: throughput against peers, scaling, speed against error.

Run as `python -m pmpmsph.bench`."""
