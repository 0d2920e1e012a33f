"""Output: HDF5 particle snapshots, their XDMF sidecar, and the diagnostics CSV table."""
from .diagnostics import DiagnosticsCSV, read_diagnostics
from .snapshot_read import list_snapshots, read_attrs, read_snapshot
from .snapshots import SnapshotWriter
from .xdmf import rebuild_xdmf_main, write_xdmf

__all__ = [
    "DiagnosticsCSV",
    "SnapshotWriter",
    "list_snapshots",
    "read_attrs",
    "read_diagnostics",
    "read_snapshot",
    "rebuild_xdmf_main",
    "write_xdmf",
]
