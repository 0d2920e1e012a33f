"""`ParticleSet`: a registry of named, contiguous struct-of-arrays fields (DESIGN.md §2).

Stages and materials *declare* the fields they need; only declared fields are allocated,
migrated, copied to halos and written. Owned particles are rows [0, n_owned); halo copies
(when a later stage asks for them) follow and are never written back.
"""
import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Optional

import numpy as np


@dataclass(frozen=True)
class FieldSpec:
    name: str
    shape: tuple = ()          # per-particle shape, e.g. (3, 3)
    dtype: object = np.float64
    migrate: bool = True       # travels with the particle between ranks
    halo: bool = False         # copied to halo particles
    output: bool = False       # written to snapshots
    fill: object = 0           # initial value ("identity" for a 3x3 identity)


#: fields every scene has (DESIGN.md §2: kinematic state shared by both methods)
CORE_FIELDS = (
    FieldSpec("gid", (), np.int64, halo=True, output=True),
    FieldSpec("method", (), np.int8, halo=True),
    FieldSpec("body", (), np.int32, halo=True, output=True),
    FieldSpec("mat", (), np.int32, halo=True),
    FieldSpec("x", ("dim",), halo=True, output=True),
    FieldSpec("v", ("dim",), halo=True, output=True),
    FieldSpec("mass", (), halo=True, output=True),
    FieldSpec("vol0", ()),
    FieldSpec("vol", (), halo=True, output=True),
    FieldSpec("sigma", (3, 3), halo=True, output=True),
)

#: the motion a particle stores: the full deformation gradient F, or, in scenes where every
#: particle is a fluid (`Case.tracks_J_only`), only J = det F: 8 bytes instead of 72, which
#: G2P reads and writes every step
F_FIELD = FieldSpec("F", (3, 3), halo=True, output=True, fill="identity")
J_FIELD = FieldSpec("J", (), halo=True, output=True, fill=1.0)


class ParticleSet:
    """Named arrays with a shared row capacity; rows [0, n_owned) are owned particles and
    [n_owned, n_total) halo copies. Arrays are allocated with spare capacity so migration
    appends and removes a few rows in O(moved) time instead of copying every field."""

    GROWTH = 1.5

    def __init__(self, dim: int, capacity: int = 0) -> None:
        self.dim = dim
        self.specs = {}
        self.arrays = {}
        self.n_owned = 0
        self.n_total = 0
        self.capacity = int(capacity)
        self._byte_views = {}  # (`byte_views`)
        #: counts the changes of which particle a row holds (rows added, removed, reordered,
        #: the halo dropped): a cache of rows found by gid is valid while it is unchanged
        self.epoch = 0
        for spec in CORE_FIELDS:
            self.declare(spec)

    # -- declaration ----------------------------------------------------------------------
    def _shape(self, spec, n):
        return (n,) + tuple(self.dim if s == "dim" else s for s in spec.shape)

    def declare(self, spec: FieldSpec) -> None:
        """Add a field (idempotent for an identical spec)."""
        if spec.name in self.specs:
            if self.specs[spec.name] != spec:
                raise ValueError(f"field {spec.name!r} declared twice with different specs")
            return
        self.specs[spec.name] = spec
        arr = np.zeros(self._shape(spec, self.capacity), dtype=spec.dtype)
        self._fill(spec, arr)
        self.arrays[spec.name] = arr
        self._byte_views = {}

    def byte_views(self, names):
        """(views, bytes per row): the fields `names` each as a (capacity, bytes per row)
        uint8 view of its whole array, for packing rows into messages
        (`kernels.partition.gather_rows`); made again only after the arrays were
        reallocated (`reserve`, `declare`)."""
        key = tuple(names)
        hit = self._byte_views.get(key)
        if hit is None:
            views = tuple(self.arrays[n].reshape(
                self.capacity, math.prod(self.arrays[n].shape[1:])).view(np.uint8) for n in key)
            hit = self._byte_views[key] = (views, sum(v.shape[1] for v in views))
        return hit

    @staticmethod
    def _fill(spec, arr):
        if spec.fill == "identity":
            arr[...] = np.eye(arr.shape[-1])
        elif spec.fill:
            arr[...] = spec.fill

    def copy_to_halo(self, name: str) -> None:
        """Also copy an already declared field to halo particles (e.g. vol0 for
        total-Lagrangian SPH, whose neighbours sum reference volumes)."""
        self.specs[name] = replace(self.specs[name], halo=True)

    def deformation(self, n: Optional[int] = None) -> np.ndarray:
        """F (n, 3, 3) or, in a J-only scene, J (n,) over the rows [0, n) (default: owned);
        the kernels that read either take this array (see `kernels.deformation`)."""
        arr = self.arrays["F"] if "F" in self.arrays else self.arrays["J"]
        return arr[: self.n_owned if n is None else n]

    def __contains__(self, name: str) -> bool:
        return name in self.arrays

    def __getitem__(self, name: str) -> np.ndarray:
        """The owned rows of a field (a view)."""
        return self.arrays[name][: self.n_owned]

    def with_halo(self, name: str) -> np.ndarray:
        """Owned rows followed by the halo copies (a view)."""
        return self.arrays[name][: self.n_total]

    def move(self, rows: np.ndarray, axes, to: np.ndarray) -> None:
        """Set the components `axes` (one axis or a sequence) of the owned positions x[rows]
        to `to` (rows x axes, or a vector for one axis), for a mover other than the stages'
        own drifts (a prescribed velocity). Fields that follow positions move with them:
        the SPH hourglass control's displacement u, integrated beside x rather than taken
        as x - X0 (kernels/sph/hourglass.py), by the same amount."""
        x = self["x"]
        axes = np.atleast_1d(axes)
        block = (np.asarray(rows)[:, None], axes)
        to = np.reshape(to, (len(rows), len(axes)))
        if "u" in self.arrays:
            self["u"][block] += to - x[block]
        x[block] = to

    # -- size changes -----------------------------------------------------------------------
    def reserve(self, capacity: int) -> None:
        if capacity <= self.capacity:
            return
        capacity = max(int(capacity), int(self.capacity * self.GROWTH) + 16)
        for name, spec in self.specs.items():
            new = np.zeros(self._shape(spec, capacity), dtype=spec.dtype)
            self._fill(spec, new[self.n_total:])
            new[: self.n_total] = self.arrays[name][: self.n_total]
            self.arrays[name] = new
        self.capacity = capacity
        self._byte_views = {}

    def append(self, values: Mapping[str, np.ndarray]) -> None:
        """Append owned particles given as a dict of arrays (fields not given get defaults)."""
        unknown = set(values) - set(self.specs)
        if unknown:
            raise KeyError(f"undeclared particle fields {sorted(unknown)}")
        n_new = len(next(iter(values.values())))
        if self.n_total != self.n_owned:
            raise RuntimeError("drop halo particles before appending owned ones")
        self.n_owned = self.n_total = self._write_rows(values, n_new)

    def remove(self, index: np.ndarray) -> None:
        """Drop owned rows `index`, filling the holes from the end (order is not kept)."""
        index = np.unique(np.asarray(index, dtype=np.int64))
        if len(index) == 0:
            return
        if self.n_total != self.n_owned:
            raise RuntimeError("drop halo particles before removing owned ones")
        n = self.n_owned
        k = len(index)
        tail = np.arange(n - k, n)
        movers = np.setdiff1d(tail, index, assume_unique=True)   # survivors in the tail
        holes = index[index < n - k]                              # holes before the tail
        for arr in self.arrays.values():
            arr[holes] = arr[movers]
        self.n_owned = self.n_total = n - k
        self.epoch += 1

    def take(self, index: np.ndarray) -> None:
        """Keep only the owned rows `index`, in that order (sorting, rebuilding)."""
        index = np.asarray(index, dtype=np.int64)
        for arr in self.arrays.values():
            arr[: len(index)] = arr[index]
        self.n_owned = self.n_total = len(index)
        self.epoch += 1

    def append_halo(self, values: Mapping[str, np.ndarray]) -> None:
        """Append halo copies (rows after the owned ones); fields not given get defaults."""
        n_new = len(next(iter(values.values()))) if values else 0
        self.n_total = self._write_rows(values, n_new)

    def _write_rows(self, values, n_new):
        """Write n_new rows after row n_total (defaults where `values` lacks a field)."""
        self.reserve(self.n_total + n_new)
        self.epoch += 1
        lo, hi = self.n_total, self.n_total + n_new
        for name, spec in self.specs.items():
            arr = self.arrays[name]
            if name in values:
                arr[lo:hi] = values[name]
            else:
                self._fill(spec, arr[lo:hi])
        return hi

    def drop_halo(self) -> None:
        if self.n_total != self.n_owned:
            self.epoch += 1
        self.n_total = self.n_owned

    def fields(self, *, migrate: Optional[bool] = None, halo: Optional[bool] = None,
               output: Optional[bool] = None) -> list[str]:
        out = []
        for name, spec in self.specs.items():
            if migrate is not None and spec.migrate != migrate:
                continue
            if halo is not None and spec.halo != halo:
                continue
            if output is not None and spec.output != output:
                continue
            out.append(name)
        return out
