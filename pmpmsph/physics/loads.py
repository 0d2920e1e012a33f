"""Particle loads: surface traction with a linear ramp, and prescribed particle velocities.

Traction (force per area) acts on the particles of a body inside a box, each carrying the
area vol0 / spacing_n of its lattice cell normal to the loaded face, so the total force is
traction x face area for one layer of particles: f_p(t) = min(t/ramp, 1) t A_p.
"""
import numpy as np

from ..particles import FieldSpec


def _in_region(x, region):
    lo = np.array(region.lo, float)
    hi = np.array(region.hi, float)
    return np.all((x >= lo) & (x <= hi), axis=1)


class TractionLoads:
    """Holds `fext0` (full-load force per particle); writes `fext` each step."""

    FIELDS = (FieldSpec("fext0", ("dim",)), FieldSpec("fext", ("dim",), migrate=False))

    def __init__(self, specs, particles):
        self.specs = specs
        self.ramps = [s.ramp for s in specs]
        self.particles = particles

    @staticmethod
    def seed(specs, body_index, x, vol, spacing, body_name, dim):
        """Full-load force of each new particle of one body (used while seeding).

        The traction acts on the loaded face; a particle carries it over its share of the
        face (volume / spacing along the normal), and when the region holds several
        particle layers along the normal they share it equally (seed 000 §6.1 loads "the
        first two layers": the applied stress is the surface traction, not twice it)."""
        f = np.zeros((len(x), dim))
        for s in specs:
            if s.body != body_name:
                continue
            sel = _in_region(x, s.region)
            if not np.any(sel):
                continue
            axis = "xyz".index(s.normal[0])
            layers = len(np.unique(np.round(x[sel, axis] / spacing[axis]).astype(np.int64)))
            area = vol[sel] / spacing[axis] / layers
            f[sel] += np.outer(area, np.array(s.traction))
        return f

    def update(self, time):
        ramp = max(self.ramps) if self.ramps else 0.0
        scale = 1.0 if ramp <= 0.0 else min(time / ramp, 1.0)
        p = self.particles
        n = p.n_owned
        np.multiply(p["fext0"][:n], scale, out=p["fext"][:n])


class PrescribedVelocity:
    """Particles of a body inside a region (at t = 0) with fixed velocity components.

    The reaction: the force each constraint applies to its particles to hold their velocity
    (what a load cell in the actuator of a footing reads; minus the sum of every other force
    on them: contact, internal, gravity), from the momentum it adds. In a step the particles
    start at the prescribed velocity; the solver would end it at v_free, and the constraint
    puts them back, adding sum m (v_prescribed - v_free) (MPM, whose transfers conserve
    momentum, so this is exactly the momentum injected). An SPH stage holds them within the
    step instead (`hold`), cancelling the force sum m acc of its last evaluation: the force
    the step's velocity update used with the predictor-corrector (the default) and in the
    mixed MPM-SPH step; Verlet and RK3 also use earlier evaluations, so there the impulse
    of a step is that of its last evaluation (a half-step offset for Verlet: the mean over a
    row of k steps is off by (R_end - R_start) / 2k). Summed over the steps between two
    diagnostics rows and divided by the time between them, the impulses give the mean
    reaction of `reaction_row` (tests/unit/test_reaction.py: the momentum balance of every
    row to round-off, MPM and SPH).
    """

    FIELDS = (FieldSpec("vpres_id", (), np.int32, fill=-1),)

    def __init__(self, specs, particles):
        self.specs = specs
        self.particles = particles
        self.time = 0.0  # of the step being taken (the last `apply` at a step's start)
        self.impulse = np.zeros((len(specs), 3))  # this rank's, since the last reaction row
        self.elapsed = 0.0
        self._held = np.zeros((len(specs), 3))  # the force `hold` cancelled in this step
        # a second running sum of the impulses for the force probes (io/probe_sampling.py),
        # which read at their own times; None until a probe opens it (`open_tap`)
        self.tap = None
        self.tap_elapsed = 0.0
        # per constraint: its held components, their axes and values
        self._components = [(s, np.array([a for a, val in enumerate(s.velocity)
                                          if val is not None], np.int64),
                             np.array([val for val in s.velocity if val is not None], float))
                            for s in specs]
        self._key = None  # (`_selection`)
        self._sel = []

    def columns(self, dim):
        """The diagnostics columns of the reactions: reaction{j}_x, ... per constraint j."""
        return tuple(f"reaction{j}_{c}" for j in range(len(self.specs)) for c in "xyz"[:dim])

    @staticmethod
    def seed(specs, x, body_name):
        ids = np.full(len(x), -1, np.int32)
        for j, s in enumerate(specs):
            if s.body == body_name:
                ids[_in_region(x, s.region)] = j
        return ids

    def _selection(self):
        """Per constraint: (its owned rows, their masses, the order that sorts their gids,
        the sorted gids), kept while `particles.epoch` says no row changed (a step of a
        scene that neither sorts nor migrates finds them once: on a small scene these
        searches were a tenth of the step)."""
        p = self.particles
        key = (p.epoch, p.n_owned)
        if self._key != key:
            n = p.n_owned
            ids = p["vpres_id"][:n]
            gid = p["gid"][:n]
            self._sel = []
            for j in range(len(self.specs)):
                rows = np.nonzero(ids == j)[0]
                order = np.argsort(gid[rows], kind="stable")
                self._sel.append((rows, p["mass"][rows], order, gid[rows][order]))
            self._key = key
        return self._sel

    def _active(self, time):
        """(constraint index, its rows, masses, order, sorted gids, the axes and values of
        its held components) of the constraints acting at `time` that hold any."""
        return [(j, *sel, axes, vals)
                for j, ((s, axes, vals), sel) in enumerate(zip(self._components,
                                                               self._selection()))
                if s.start <= time < s.until and len(axes)]

    def apply(self, time, dt=None, x_before=None):
        """Set the prescribed components of v; after a step (`dt`, the particles' gids and
        positions `x_before` at its start, from `positions`) also move those particles with
        that velocity rather than the grid's. The rows may have been reordered during the
        step (a coupled scene sorts them by method and cell), so the start positions are
        matched by gid: matched by row, clamped particles of a plate under MPM water traded
        places and failed at step 2 (docs/plate.md)."""
        p = self.particles
        v = p["v"]
        if x_before is None:
            self.time = time
        for j, sel, mass, order, _, axes, vals in self._active(time):
            block = (sel[:, None], axes)
            if x_before is not None:  # (a row that arrived from another rank in the step
                gids, xs, epoch = x_before[j]  # keeps the position its stage gave it)
                if epoch == self._key:  # the same rows as at the start: no search
                    moved, start = sel[order], xs
                else:
                    at = np.minimum(np.searchsorted(gids, p["gid"][sel]),
                                    max(len(gids) - 1, 0))
                    known = (gids[at] == p["gid"][sel] if len(gids)
                             else np.zeros(len(sel), bool))
                    moved, start = sel[known], xs[at[known]]
                dp = mass @ (vals - v[block]) + dt * self._held[j, axes]
                self.impulse[j, axes] += dp
                if self.tap is not None:
                    self.tap[j, axes] += dp
            v[block] = vals
            if x_before is not None:
                p.move(moved, axes, start[:, axes] + dt * vals)
        if x_before is not None:
            self.elapsed += dt
            self.tap_elapsed += dt
            self._held[:] = 0.0

    def hold(self, acc):
        """Zero the prescribed components of the owned rows' accelerations `acc` (an SPH
        stage calls this after each evaluation), so that within a step the held particles
        keep their prescribed velocity. Without it a clamped particle moved by its reaction
        force within every step and was put back after it, and an updated-Lagrangian solid
        integrated the undone motion into F: a clamped SPH plate under its own weight crept
        without end (docs/plate.md)."""
        for j, sel, mass, _, _, axes, _ in self._active(self.time):
            block = (sel[:, None], axes)
            self._held[j, axes] = -(mass @ acc[block])
            acc[block] = 0.0

    def local_impulse(self):
        """This rank's impulses since the last `reaction_row` (constraints x 3), then reset;
        the caller sums them over the ranks (with its other diagnostics, one collective)."""
        out = self.impulse.ravel().copy()
        self.impulse[:] = 0.0
        return out

    def open_tap(self):
        """Start the probes' running sum of the impulses (`take_tap`)."""
        if self.tap is None:
            self.tap = np.zeros((len(self.specs), 3))
            self.tap_elapsed = 0.0

    def take_tap(self):
        """(this rank's impulses since the last call, constraints x 3; the time they span),
        then reset: the force probes' share, apart from the diagnostics' `local_impulse`."""
        out, elapsed = self.tap.copy(), self.tap_elapsed
        self.tap[:] = 0.0
        self.tap_elapsed = 0.0
        return out, elapsed

    def reaction_row(self, impulse, dim):
        """The diagnostics columns (`columns`) from the ranks' summed `impulse`: the mean
        reaction over the time since the last row (nan before the first step)."""
        elapsed, self.elapsed = self.elapsed, 0.0
        mean = (impulse.reshape(-1, 3) / elapsed if elapsed > 0.0
                else np.full((len(self.specs), 3), np.nan))
        return dict(zip(self.columns(dim), mean[:, :dim].ravel()))

    def positions(self):
        """(gids, positions, the rows' epoch) of each constraint's particles at the start of
        a step, sorted by gid (for `apply`); only those rows are copied."""
        x = self.particles["x"]
        return [(gids, x[rows[order]], self._key)
                for rows, _, order, gids in self._selection()]
