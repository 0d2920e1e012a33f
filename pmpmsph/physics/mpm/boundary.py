"""Grid boundary conditions and gates: case boundaries -> flat per-node arrays for the kernel.

A boundary with `until = t` is a gate: it acts while time < t and is then removed (thesis
§8.4, dam break). The node arrays are rebuilt only when the set of active boundaries changes.
"""
import numpy as np

from ...kernels.mpm.grid_bc import apply_grid_bc, mirror_grid_bc
from ...kernels.mpm.grid_conditions.registry import condition_named


class GridBoundaries:
    def __init__(self, specs, grid):
        self.grid = grid
        self.specs = specs
        dim = grid.dim
        self.parts = []
        for spec in specs:
            if spec.region.face:
                nodes = grid.nodes_on_face(spec.region.face)
            else:
                nodes = grid.nodes_in_box(spec.region.lo, spec.region.hi)
            normal = np.zeros(3)
            normal[:dim] = spec.normal if spec.normal else 0.0
            wall = np.zeros(3)
            wall[:dim] = spec.velocity if spec.velocity else 0.0
            self.parts.append((nodes, condition_named(spec.kind).code, normal, spec.friction,
                               wall))
        # faces whose condition mirrors (fixed, slip) set the nodes beyond them too (see
        # `mirror_grid_bc`); one-sided friction walls let material leave, so they do not
        self.mirrors = [grid.mirror_pairs(spec.region.face)
                        if spec.region.face and condition_named(spec.kind).mirror is not None
                        else None for spec in specs]
        self.active_key = None
        self._arrays = None
        self._until = sorted({s.until for s in specs})  # the times the active set changes
        self._prev_time = np.inf  # the active set holds for _prev_time <= time < _valid_until
        self._valid_until = -np.inf

    def _build(self, active):
        nodes, kinds, normals, mus, walls = [], [], [], [], []
        for j in active:
            nd, kind, normal, mu, wall = self.parts[j]
            nodes.append(nd)
            kinds.append(np.full(len(nd), kind, np.int64))
            normals.append(np.tile(normal, (len(nd), 1)))
            mus.append(np.full(len(nd), mu))
            walls.append(np.tile(wall, (len(nd), 1)))
        if not nodes:
            return (np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros((0, 3)), np.zeros(0),
                    np.zeros((0, 3)))
        return (np.concatenate(nodes), np.concatenate(kinds), np.concatenate(normals),
                np.concatenate(mus), np.concatenate(walls))

    def apply(self, time, vel, dv):
        if not (self._prev_time <= time < self._valid_until):  # the gates' times crossed
            active = tuple(j for j, s in enumerate(self.specs) if time < s.until)
            if active != self.active_key:
                self._arrays = self._build(active)
                self.active_key = active
            self._prev_time = time
            self._valid_until = min((u for u in self._until if u > time), default=np.inf)
        active = self.active_key
        node, kind, normal, mu, wall = self._arrays
        if len(node):
            apply_grid_bc(self.grid.dim, node, kind, normal, mu, wall, vel, dv)
        for j in active:
            if self.mirrors[j] is not None and len(self.mirrors[j][0]):
                _, code, normal, _, wall = self.parts[j]
                mirror_grid_bc(self.grid.dim, *self.mirrors[j], code, normal, wall, vel, dv)
