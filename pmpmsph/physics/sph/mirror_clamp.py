"""Mirror clamps of SPH solids (`[[prescribed]] mirror = "x+"`, ...), total- and
updated-Lagrangian.

A clamp made of held particles (zero velocity) is first-order wrong at its edge: the free
particles' kernel sums straddle the kink between the held, undisplaced material and the
strained free material, so they read too small a strain there and the body is too soft, as
if the clamp ended about one smoothing length h deeper. Measured (docs/plate.md): a bar
hanging from a clamp stretched +8.9 / +4.3 % too much at 2 / 4 particles through its
thickness, a plate clamped at both ends sagged +43 / +19 / +6.9 % at 2 / 4 / 8 through.

Here the held particles within reach of the free ones are ghosts of the free body across the
clamp face (the plane of the box's face `mirror`), as the ghost particles of a Dirichlet wall
in SPH fluids: a ghost at reference position X_g, whose partner is the free particle at the
mirror image of X_g, takes the odd image of the partner's displacement,

    x_g = X_g - (x_p - X_p),        v_g = -v_p,

so a displacement field that vanishes on the face continues across it to first order (a
uniform strain exactly). The ghosts' own stress is left out (P_g = 0): the strain energy is
the free particles' alone, E = sum over free a of V_a psi(F_a), with the ghost positions
functions of the free ones. So the forces are -dE/dx: the usual pair forces on the free
particles, plus, for each partner, the force its ghost takes times the mirror's Jacobian
dx_g / dx_p = -1. The forces stay conservative (with the hourglass control too, whose pair
energy then includes the ghosts' pairs). The updated formulation reads its strain rate from
the velocities, so there the ghosts mirror them too, in the kinematics and in each
evaluation; its stress is left out through S = sigma / rho^2. There the pair forces of
a held row with other materials (water, dummy walls) are not accumulated (`sph_rates`'
`clamped` mask): the clamp takes them, so a ghost hands its partner the solid's forces alone,
as in the total formulation. Beside SPH water the updated plate also needs the quadratic
hourglass control (`[sph] hourglass_fit = "quadratic"`): without a control its columns pair
up under the water's pressure, water passes between them, and the plate sinks (39 mm at
spacing 0.01, with or without the mask; docs/plate.md).

Partners are found once, in the reference configuration, by gid (the free particle of the
same body within a quarter spacing of the image). A held particle within two smoothing
lengths of the face must have one (the face must lie halfway between two particle layers,
as a box-seeded body's clamp box ending on a layer boundary does); deeper held particles
stay at rest as before. On N ranks the partners' displacements and the ghosts' forces are
all-gathered (a few values per clamped particle, twice per evaluation).
"""
import numpy as np

from ...errors import ConfigError

#: a partner is the free particle within this fraction of the spacing of a ghost's image
MATCH = 0.25
_IDENTITY = np.eye(3)


class MirrorClamps:
    """The mirror clamps of one scene: ghost and partner gids (`setup`, collective, before
    the first evaluation)."""

    def __init__(self, case, particles, dist, h):
        self.specs = [(j, s) for j, s in enumerate(case.prescribed) if s.mirror]
        self.case = case
        self.p = particles
        self.dist = dist
        self.h = h
        self.ghost_gid = None     # sorted
        self.partner_gid = None   # the partner of each ghost
        self.held_gid = None      # every held particle of a mirror clamp (stress left out)
        # of the evaluation under way (`place` to `restore`: no row moves in between): the
        # owned rows of the ghosts and partners, the saved ghost state, the held-row mask;
        # the rows and the mask are kept while `particles.epoch` says no row changed
        self._index = self._saved = self._held = None
        self._rows_epoch = self._held_epoch = None

    # -- set-up ---------------------------------------------------------------------------
    def _faces(self, spec):
        axis = "xyz".index(spec.mirror[0])
        plane = (spec.region.hi if spec.mirror[1] == "+" else spec.region.lo)[axis]
        return axis, plane

    def setup(self):
        """Match every held particle of a mirror clamp to its partner (collective; a held
        particle near the face without one is a ConfigError on every rank)."""
        p, n = self.p, self.p.n_owned
        X0, gid, ids, body = p["X0"][:n], p["gid"][:n], p["vpres_id"][:n], p["body"][:n]
        free = ids < 0
        names = [b.name for b in self.case.bodies]
        found_g, found_p, missing = [], [], None
        for j, spec in self.specs:
            b = names.index(spec.body)
            spacing = float(np.min(self.case.bodies[b].spacing))
            axis, plane = self._faces(spec)
            reach = 2.0 * (2.0 * self.h) + spacing  # images within the free particles' reach
            cand = free & (body == b) & (np.abs(X0[:, axis] - plane) < reach)
            every = self.dist.allgather((gid[cand], X0[cand]))
            cg = np.concatenate([e[0] for e in every])
            cx = np.concatenate([e[1] for e in every]).reshape(-1, X0.shape[1])
            for r in np.nonzero(ids == j)[0]:
                image = X0[r].copy()
                image[axis] = 2.0 * plane - image[axis]
                d = (np.linalg.norm(cx - image, axis=1) if len(cx)
                     else np.full(1, np.inf))
                k = int(np.argmin(d))
                if d[k] < MATCH * spacing:
                    found_g.append(int(gid[r]))
                    found_p.append(int(cg[k]))
                elif abs(X0[r, axis] - plane) < 2.0 * self.h and missing is None:
                    missing = (spec.key, X0[r].tolist())

        def check():
            if missing is not None:
                key, x = missing
                raise ConfigError(f"{key}.mirror", f"the held particle at {np.round(x, 6)} "
                                  "has no free particle of its body at its mirror image: the "
                                  "clamp face must lie halfway between two particle layers")

        self.dist.agree("build", check)
        held = np.isin(ids, [j for j, _ in self.specs])
        self.held_gid = np.sort(np.concatenate(self.dist.allgather(gid[held])))
        every = self.dist.allgather((found_g, found_p))
        g = np.array([x for e in every for x in e[0]], np.int64)
        q = np.array([x for e in every for x in e[1]], np.int64)
        order = np.argsort(g)
        self.ghost_gid, self.partner_gid = g[order], q[order]

    # -- each evaluation ------------------------------------------------------------------
    def _rows(self, *gid_lists):
        """Owned rows of each list of gids (-1 where not owned here), one sort of the owned
        gids for all."""
        n = self.p.n_owned
        gid = self.p["gid"][:n]
        order = np.argsort(gid)
        out = []
        for gids in gid_lists:
            rows = np.full(len(gids), -1, np.int64)
            if n and len(gids):
                at = order[np.minimum(np.searchsorted(gid[order], gids), n - 1)]
                hit = gid[at] == gids
                rows[hit] = at[hit]
            out.append(rows)
        return out

    def _evaluation_rows(self):
        """(ghosts whose partner is owned here, those partners' rows, ghosts owned here,
        their rows), as indices; kept while `particles.epoch` says no row changed."""
        p = self.p
        if self._rows_epoch != p.epoch:
            grow, prow = self._rows(self.ghost_gid, self.partner_gid)
            mine = np.nonzero(prow >= 0)[0]
            own = np.nonzero(grow >= 0)[0]
            self._index = (mine, prow[mine], own, grow[own])
            self._rows_epoch = p.epoch
        return self._index

    def _gathered(self, index, values):
        """Per ghost (in ghost-gid order), the rows of `values` given by each rank for the
        ghosts `index` (collective; one rank: no message)."""
        if self.dist.size == 1 and len(index) == len(self.ghost_gid):
            return values  # (index is every ghost, in order)
        out = np.zeros((len(self.ghost_gid),) + values.shape[1:])
        if self.dist.size == 1:
            out[index] = values
        else:
            for k, vk in self.dist.allgather((index, values)):
                out[k] = vk
        return out

    def place(self):
        """Put the owned ghosts at the odd image of their partners (before the halo
        exchange); `restore` puts them back at rest."""
        p = self.p
        mine, partners, own, rows = self._evaluation_rows()
        X0, x, v = p["X0"], p["x"], p["v"]
        d = X0.shape[1]
        state = self._gathered(mine, np.concatenate([x[partners] - X0[partners],
                                                     v[partners]], axis=1))
        self._saved = (x[rows].copy(), v[rows].copy())
        x[rows] = X0[rows] - state[own, :d]
        v[rows] = -state[own, d:]

    def restore(self):
        """The ghosts back at rest; every held row of a clamp with F = 1 and no stress, as
        the energy counts them (for output and the diagnostics)."""
        p = self.p
        rows = self._index[3]
        x, v = self._saved
        p["x"][rows] = x
        p["v"][rows] = v
        held = self.held_owned_rows()
        p["F"][held] = _IDENTITY
        p["sigma"][held] = 0.0
        p["vol"][held] = p["vol0"][held]
        p["rho"][held] = p["mass"][held] / p["vol0"][held]

    def held_rows(self):
        """Mask over the rows with halo: the held particles of the clamps (their stress is
        left out of the forces); once per evaluation, after its halo exchange."""
        p = self.p
        if self._held_epoch != p.epoch or len(self._held) != p.n_total:
            self._held = np.isin(p.with_halo("gid"), self.held_gid)
            self._held_owned = np.nonzero(self._held[:p.n_owned])[0]
            self._held_epoch = p.epoch
        return self._held

    def held_owned_rows(self):
        """The owned rows of `held_rows`, as an index (cached with it)."""
        self.held_rows()
        return self._held_owned

    def hand_back(self, acc, gravity, damping=0.0):
        """Each ghost's force (m (acc - g + damping v): without its weight and its own
        damping, before the clamp zeroes it) to its partner, with the mirror's Jacobian -1
        (collective)."""
        p = self.p
        mine, partners, own, rows = self._index
        f = p["mass"][rows, None] * (acc[rows] - gravity + damping * p["v"][rows])
        force = self._gathered(own, f)
        # in ghost-gid order: the same sums on any ranks
        np.subtract.at(acc, partners, force[mine] / p["mass"][partners, None])
