"""Benchmarks: throughput against peers, scaling, speed against error (`python -m pmpmsph.bench`)."""
