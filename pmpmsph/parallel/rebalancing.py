"""Moving the slab faces of a running `Simulation` when the work is out of balance
(DESIGN.md §4): the collective decision of `parallel.balance.LoadBalancer`, then the stages'
grids and halos rebuilt for the new slabs and the particles migrated to them."""
import logging

import numpy as np

from .migration import migrate_all

log = logging.getLogger("pmpmsph")

#: timer phases that are a rank's own work (the rest is waiting, I/O or bookkeeping)
COMPUTE_PHASES = ("p2g", "grid", "g2p", "sph", "integrate", "neighbours", "coupling")


class Rebalancing:
    """Load-balancing methods of `Simulation` (they use its decomposition, particles,
    stages, balancer, timers and step count)."""

    _busy_mark = 0.0  # compute seconds at the last load-balance check (balance_by = "time")

    def rebalance(self, force_faces=None):
        """Move slab faces if the work is out of balance (collective); True if they moved."""
        dec = self.decomposition
        cells = list(dec.spec.cells)
        nodes_per_layer = (float(np.prod([c + 1 for a, c in enumerate(cells) if a != dec.axis]))
                           if self.mpm is not None else 0.0)
        if force_faces is not None:
            faces, before, after = np.asarray(force_faces), None, None
        else:
            p = self.particles
            faces, before, after = self.balancer.propose(dec, p["x"], nodes_per_layer,
                                                         self._busy(), p["method"])
        if faces is None:
            return False
        self._apply_faces(faces)
        self.migrated += migrate_all(self.decomposition, self.particles, self.step_count)
        if self.balancer is not None:
            self.balancer.history.append((self.step_count, before, after, faces.tolist()))
        log.info("step %d: slab faces moved to %s (imbalance %s -> %s)", self.step_count,
                 faces.tolist(), f"{before:.2f}" if before is not None else "?",
                 f"{after:.2f}" if after is not None else "?")
        return True

    def _busy(self):
        """Every rank's compute seconds since the last call (balance_by = "time"), or None:
        the stages' kernel phases, not the waiting in exchanges (collective)."""
        if self.case.parallel.balance_by != "time":
            return None
        now = sum(self.timers.total.get(k, 0.0) for k in COMPUTE_PHASES)
        last, self._busy_mark = self._busy_mark, now
        if self.step_count == 0:  # nothing measured yet (the balance before step 1)
            return None
        busy = self.dist.allgather_float(now - last if now >= last else now)
        return busy if np.all(busy > 0) else None

    def _apply_faces(self, faces):
        """New slab faces for the decomposition and the stages (particles stay put)."""
        self.decomposition = self.decomposition.with_faces(faces)
        if self.mpm is not None:
            self.mpm.set_decomposition(self.decomposition)
        if self.sph is not None:
            self.sph.set_decomposition(self.decomposition)
