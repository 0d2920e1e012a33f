"""Benchmarks: throughput against peers, scaling, speed against error.

Run as `python -m pmpmsph.bench`."""
import csv
import json
import os


def write_rows(out, filename, rows):
    """A bench's table as `<out>/<filename>`: one column per key any row has (sorted)."""
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, filename)
    with open(path, "w", newline="") as fh:
        table = csv.DictWriter(fh, fieldnames=sorted({k for r in rows for k in r}))
        table.writeheader()
        table.writerows(rows)
    print(f"written {path}")


def write_json(out, filename, data):
    """A bench's results as `<out>/<filename>` (indented JSON)."""
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, filename)
    with open(path, "w") as fh:
        json.dump(data, fh, indent=1)
    print(f"written {path}")
