"""The output folder of a run: is it usable, and making it (DESIGN.md §7: output already
present is not overwritten unless asked; a folder that cannot be written is bad input).

Both run on rank 0 only, inside `Distributor.agree`, so every rank stops with the same
message (a check on rank 0 alone that raised there would leave the other ranks waiting).
"""
import os

from ..errors import ConfigError

#: the files whose presence means "a run is already here"
RUN_FILES = ("particles.h5", "diagnostics.csv", "probes.csv")


def check_output_folder(path, overwrite, key="--out"):
    """Raise ConfigError(key) if `path` cannot take a run's output: it (or the nearest part
    of it that exists) is a file, or a folder this process cannot write in, or it already
    holds a run and `overwrite` is false. Creates nothing. Messages name the path as given."""
    if os.path.exists(path) and not os.path.isdir(path):
        raise ConfigError(key, f"{path} is a file, not a folder")
    probe = os.path.abspath(path)
    while not os.path.exists(probe):
        parent = os.path.dirname(probe)
        if parent == probe:
            break
        probe = parent
    if not os.path.isdir(probe):
        raise ConfigError(key, f"cannot make {path}: {probe} is a file, not a folder")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise ConfigError(key, f"cannot write in {probe}: permission denied")
    present = [f for f in RUN_FILES if os.path.exists(os.path.join(path, f))]
    if present and not overwrite:
        raise ConfigError(key, f"output already present in {path} ({', '.join(present)}); "
                          "pass --overwrite to replace it")


def make_output_folder(path, key="--out"):
    """Create `path` (and its parents); an OS refusal is bad input naming `key`."""
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise ConfigError(key, f"cannot make the output folder {path}: {reason}") from None
