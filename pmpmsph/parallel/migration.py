"""Particle migration between neighbouring slabs after the position update (DESIGN.md §4).

Owned particles whose cell left this rank's slab are packed, field by field, into one byte
row per particle and sent to the neighbour that owns them; only the two neighbours are
contacted. A particle that would have to cross a whole slab in one step is an error (dt or
the slab is wrong), decided collectively so no rank waits forever.
"""
import math

import numpy as np

from ..errors import RunError
from ..kernels.partition import gather_rows, max_abs_column, max_stray, slab_leavers
from .distributor import exchange_rows

TAG_DATA = 22


def _pack(particles, names, idx):
    """The rows `idx` of fields `names`, side by side in one (len(idx), bytes) array."""
    views, width = particles.byte_views(names)
    out = np.empty((len(idx), width), np.uint8)
    if len(idx):
        gather_rows(views, idx, out)
    return out


def _columns(particles, names, rows):
    """(name, the field's values in `rows` as a (n, ...) view-or-copy) of a packed array."""
    pos = 0
    n = rows.shape[0]
    for name in names:
        spec = particles.specs[name]
        shape = particles._shape(spec, n)
        width = math.prod(shape[1:]) * np.dtype(spec.dtype).itemsize
        chunk = np.ascontiguousarray(rows[:, pos:pos + width])
        yield name, chunk.view(spec.dtype).reshape(shape)
        pos += width


def _unpack(particles, names, rows):
    return dict(_columns(particles, names, rows))


def plan_migration(decomposition, particles, hop=False):
    """Local: (rows leaving this slab, the rank each goes to, those of them that would skip a
    whole slab). With `hop` (after the slab faces moved) a particle owned further away goes
    one slab towards its owner."""
    dec = decomposition
    x = particles["x"]
    leaving = slab_leavers(x, dec.axis, dec.origin, 1.0 / dec.dx, dec.ncells, dec.lo_cell,
                           dec.hi_cell)
    owner = dec.owner(x[leaving])
    if hop and dec.period is None:
        owner = np.clip(owner, dec.rank - 1, dec.rank + 1)
    elif hop:  # one slab towards the owner, the short way round the period
        step = np.where((owner - dec.rank) % dec.size <= dec.size // 2, 1, -1)
        owner = np.where(owner == dec.rank, owner, (dec.rank + step) % dec.size)
    return leaving, owner, leaving[dec.slab_distance(owner) > 1]


def migrate(decomposition, particles, step=0, hop=False, plan=None, far_anywhere=None):
    """Send owned particles to the neighbours that own them now; returns (sent, received).

    With `hop` (after the slab faces moved) a particle owned further away goes one slab
    towards its owner; call again until nothing moves (`migrate_all`). A particle that would
    skip a whole slab stops the run on every rank: decided here by an allreduce, or by the
    caller, which passes this rank's `plan` (`plan_migration`) and `far_anywhere`, the flag
    it reduced with other numbers (`Simulation` folds it into the step's one allreduce).
    """
    dec = decomposition
    if dec.size == 1:
        return 0, 0
    leaving, owner, far = plan if plan is not None else plan_migration(dec, particles, hop)
    if far_anywhere is None:
        far_anywhere = dec.dist.any(len(far) > 0)
    if far_anywhere:
        gid = int(particles["gid"][far[0]]) if len(far) else -1
        raise RunError(step, gid, "particle jumped over a whole slab in one step (dt too "
                       "large for the slab width, or the particle was thrown out)")
    names = particles.fields(migrate=True)
    width = particles.byte_views(names)[1]
    sends = []
    for nb in sorted({nb for _, nb, _ in dec.routes()}):  # (on two periodic ranks: once)
        sends.append((nb, TAG_DATA, TAG_DATA, _pack(particles, names, leaving[owner == nb])))
    recv_rows = exchange_rows(dec.dist.comm, sends, width)
    sent = len(leaving)
    migrate.bytes_sent += sum(rows.nbytes for *_, rows in sends)
    particles.remove(leaving)
    received = 0
    for buf in recv_rows:
        if buf.shape[0]:
            particles.append(_unpack(particles, names, buf))
            received += buf.shape[0]
    return sent, received


migrate.bytes_sent = 0


class MigrationSchedule:
    """When to migrate, decided collectively after every step from two global numbers that
    `Simulation` reduces in the step's one allreduce (with the failure flag and the CFL
    speed): how far any owned particle has strayed past its slab's faces along the slab
    axis, and the max |v| along that axis.

    A particle may stay with its old rank for a while after crossing a slab face, as long
    as it stays within `reach` of the face:
    - MPM: its P2G lands on ghost nodes, which `GridHalo.sum` adds into their owner, and G2P
      reads ghost velocities, as long as its stencil stays inside the ghost layers, which
      leave one cell for such moves (`parallel/decomposition.py`): reach = one cell;
    - SPH: the halo sends every owned particle within its width of a face, beyond as well
      as inside (`ParticleHalo.send_lists`), and the width holds HALO_MARGIN h beyond the
      lists' radius (physics/sph/stage.py): reach = that margin.
    Migration is due once the farthest stray plus twice the last step's move at the max
    speed (the next step's move, with room for it to grow; MUSL's second P2G and the SPH
    predictor come before migration) passes SLACK times the smallest reach of the scene's
    stages. The stray is measured, not bounded from velocities, so a move that is not v dt
    (particle shifting, a prescribed position, a particle thrown out) counts too. A slow
    scene migrates every tens to thousands of steps instead of every step.
    """
    SLACK = 0.9

    def __init__(self, dist, lazy, reach=1.0):
        self.dist = dist
        self.lazy = lazy and dist.size > 1
        #: several ranks and no laziness: migration after every step
        self.every_step = dist.size > 1 and not self.lazy
        self.reach = float(reach)

    def local_state(self, particles, dec):
        """(max |v| along the slab axis, farthest stray past this slab's faces) over this
        rank's owned particles, or (None, None) when not lazy."""
        if not self.lazy:
            return None, None
        n, axis = particles.n_owned, dec.axis
        lo = dec.origin + dec.lo_cell * dec.dx
        hi = dec.origin + dec.hi_cell * dec.dx
        return (max_abs_column(particles["v"], axis, n),
                max_stray(particles["x"], axis, lo, hi, n))

    def due(self, speed, stray, dt):
        """Migrate after this step? `speed`, `stray`: the global maxima of `local_state`."""
        if not self.lazy:
            return self.dist.size > 1
        return not (stray + 2.0 * dt * speed <= self.SLACK * self.reach)  # NaN: migrate


def migrate_all(decomposition, particles, step=0):
    """Migrate with hops until every particle is on its owner (after faces moved)."""
    total = 0
    for _ in range(decomposition.size):
        sent, _ = migrate(decomposition, particles, step, hop=True)
        total += sent
        if not decomposition.dist.any(sent > 0):
            break
    return total
