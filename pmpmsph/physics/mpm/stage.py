"""MPMStage: one explicit MPM step over the owned MPM particles (DESIGN.md §3, step 2).

USL (thesis §7.4):  P2G(m, mv, f) -> grid solve + BCs -> G2P(v, x, L, F, sigma)
USF:                P2G(m, mv) -> grid v + BCs -> G2P(L, F, sigma) -> P2G(m, mv, f)
                    -> grid solve + BCs -> G2P(v, x)
MUSL (Sulsky):      P2G(m, mv, f) -> grid solve + BCs -> G2P(v, x) -> P2G(m, mv) with the
                    new particle velocities -> grid v + BCs -> G2P(L, F, sigma)
Multi-field contact (Bardenhagen et al. 2001) runs after every grid solve when enabled.
In a coupled scene the rows [n_stress, n_p2g) are SPH solid particles in their own velocity
fields (`physics.sph.solid_in_fluid`): they scatter mass, momentum and their SPH force (no
stress), and take back the velocity change the contact of the force solve made to their field.
PIC-USL without damping scatters p + dt f in one go (`fold_force`, mpm88's form).
`mpm.velocity_update` = "apic" / "mls": the passes that move the particles hand them v_p and
the affine matrix C_p (kernels/mpm/affine.py), and P2G scatters m_p (v_p + C_p (x_I - x_p)).
"""
from contextlib import contextmanager

import numpy as np

from ...kernels.mpm.contact import contact_normals, multi_field_contact, surface_reach
from ...kernels.coupling import add_gathered, gather_increment, grid_force_kick
from ...kernels.mpm.fbar import fbar_stress
from ...kernels.mpm.transfers import FOLDED, MOMENTUM, WITH_FORCE, g2p, grid_velocity, p2g
from ...kernels.mpm.affine import g2p_affine, p2g_affine
from ...kernels.mpm.views import (NO_AFFINE, gather_options, gather_points, material_table,
                                  scatter_points)
from ...kernels.partition import cell_keys
from ...kernels.mpm.shape_functions.registry import shape_named
from ...kernels.mpm.shapes import CPDI, cpdi_reach, static_tags
from ...materials.dispatch import material_tag
from ...particles import FieldSpec
from .boundary import GridBoundaries
from ..coupling import Uncoupled
from .grid import Grid
from ..scratch import rows_at_least
from .transfer_schemes import TRANSFER_SCHEMES
from ...parallel.decomposition import wrap_axis
from ...parallel.grid_halo import GridHalo
from ...timing import Timers

#: grids with fewer nodes reset and solve every node (`Grid.work_range` costs ~5 us a call)
TRIM_MIN_NODES = 4096


class MPMStage:
    def __init__(self, case, particles, materials, decomposition, timers=None):
        self.case = case
        self.p = particles
        spec = case.mpm
        self.dim = case.dim
        self.shape = shape_named(spec.shape)
        self.kind = self.shape.code
        self.tags = static_tags(self.dim, self.kind)
        self.transfer = spec.transfer
        self.scheme = TRANSFER_SCHEMES[spec.transfer]()  # the order of the passes
        self.flip = spec.flip
        self.affine = spec.velocity_update in ("apic", "mls")  # particles carry C
        self.mls = spec.velocity_update == "mls"
        self.damping = spec.damping
        self.mass_cutoff = spec.mass_cutoff
        self.multi = spec.contact == "multi"
        self.friction = spec.friction
        nfields = len(case.bodies) if self.multi else 1
        self.nfields = nfields
        #: per velocity field (one per body with multi-field contact): a fluid's?
        self._fluid_field = np.array([case.materials[b.material].fluid for b in case.bodies]
                                     if self.multi else [False])
        # how far a particle reaches nodes for the contact (cells per axis): GIMP 1 + its own
        # half-width, CPDI's deformed domain the bound the grid keeps for it, the other
        # shapes their support
        self._reach_by_lp = self.shape.half_width > 0.0 and not self.shape.corners
        self._reach_support = (float(spec.cpdi_reach) + 1.0 if self.shape.corners
                               else self.shape.support)
        self.halo_enabled = True
        self._warming = False  # (`detached`)
        #: how far an owned point may stray past its slab face before it must migrate
        #: (`MigrationSchedule`): the ghost layers leave one cell for such moves
        self.stray_reach = float(case.grid.cell_size[0])
        self.timers = timers if timers is not None else Timers()
        self.set_decomposition(decomposition)
        self.gravity = np.zeros(3)
        self.gravity[: self.dim] = case.gravity
        self.mtypes, self.mparams = materials
        used = {list(case.materials).index(b.material) for b in case.bodies
                if b.method == "mpm" or case.regions}
        self.mat_tag = material_tag(self.mtypes[sorted(used)])
        self.materials = material_table(self.mat_tag, self.mtypes, self.mparams)
        self.max_reach = float(case.mpm.cpdi_reach)  # (CPDI's largest domain, in cells)
        self.pic_tag = (0,) if self.flip == 0.0 else ()  # PIC, for `kernels.mpm.transfers.g2p`
        # PIC-USL without damping needs only the updated nodal velocity, so P2G scatters
        # p + dt f into the momentum (one scatter instead of two, as Taichi's mpm88 does)
        # (an interface that needs the nodal forces apart forbids it: `attach`)
        self.fold_force = (self.scheme.stress_last and (self.flip == 0.0 or self.affine)
                           and self.damping == 0.0 and not self.multi)
        self.interface = Uncoupled()  # the coupling's hooks in the step (`attach`)
        # rows [0, n_p2g) take part in P2G and [0, n_g2p) are updated by G2P; None: all
        # owned rows (a coupled scene puts MPM rows first, then the SPH transition zone;
        # which of them scatter their stress is the interface's `p2g_parts`)
        self.n_p2g = self.n_g2p = self.n_stress = None
        self.signal = None  # max (c + |v|) after the last step, from G2P (see `step`)
        self._dvc = np.zeros((0, 0, 0))  # scratch: `_contact_change`, `_zero_stress`
        self._zeros = np.zeros((0, 3, 3))
        self._grad = np.zeros((0, 3, 3))
        # only a CFL time step reads it (`Simulation.signal_speed`); a sqrt per particle else
        self.want_signal = case.time.cfl is not None
        # F-bar (`[mpm] fbar`, kernels/mpm/fbar.py): which materials' J is averaged; scratch
        self.averaged = (np.array([m.plastic for m in case.materials.values()])
                         if spec.fbar else None)
        self._fbar_rows = np.zeros((0, self.dim))
        self._fbar_weight = np.zeros(0)
        self._fbar_nodes = ()

    @property
    def n_p2g(self):
        return self.p.n_owned if self._n_p2g is None else self._n_p2g

    @n_p2g.setter
    def n_p2g(self, value):
        self._n_p2g = value

    @property
    def n_stress(self):
        """Rows [0, n_stress) scatter their stress; [n_stress, n_p2g) are SPH solids in
        contact (physics.sph.solid_in_fluid)."""
        return self.n_p2g if self._n_stress is None else self._n_stress

    @n_stress.setter
    def n_stress(self, value):
        self._n_stress = value

    @property
    def n_g2p(self):
        return self.p.n_owned if self._n_g2p is None else self._n_g2p

    @n_g2p.setter
    def n_g2p(self, value):
        self._n_g2p = value

    def set_decomposition(self, decomposition):
        """(Re)build the local grid, its boundary conditions and ghost-node plan for a slab."""
        self.dec = decomposition
        lo, hi = decomposition.local_nodes()
        folded = tuple(a for a in self.case.grid.periodic
                       if not (decomposition.wraps and a == decomposition.axis))
        self.grid = Grid(self.case.grid, nfields=self.nfields, with_normals=self.multi,
                         node_range=(decomposition.axis, lo, hi), folded=folded)
        self.bcs = GridBoundaries(self.case.boundaries, self.grid)
        sent = self.halo.bytes_sent if hasattr(self, "halo") else 0  # a run's total
        self.halo = GridHalo(decomposition, self.grid)
        self.halo.bytes_sent = sent
        # the node layers P2G may touch (`Grid.work_range`): a stencil and a cell of drift
        # around the particles, plus the layers shared with neighbours along axis 0; along
        # another slab axis those layers are not contiguous, so the whole grid is kept
        ghost = int(self.case.grid.ghost)
        self._margin = ghost + 1
        shared = 2 * ghost + 1  # a neighbour's ghosts and ours (`GridHalo.sum`), and one more
        every = self.grid.shape[0]
        self._keep = ((shared if decomposition.left is not None else 0,
                       shared if decomposition.right is not None else 0)
                      if decomposition.axis == 0 else (every, every))
        self._span = (0, self.grid.n_nodes)
        # a small grid (a 1D bar, a few cells) is not worth the range's Python work per step;
        # a periodic grid folds its end layers, which must be reset every step
        self._trim = self.grid.n_nodes >= TRIM_MIN_NODES and not self.case.grid.periodic

    @contextmanager
    def detached(self):
        """No ghost-node exchanges inside (the JIT warm-up runs on one rank at a time), and
        the transfers run on zero rows too (which compiles them; a step skips them)."""
        self.halo_enabled = False
        self._warming = True
        try:
            yield
        finally:
            self.halo_enabled = True
            self._warming = False

    @staticmethod
    def fields(case):
        """Fields this stage needs beyond the core ones."""
        out = []
        if shape_named(case.mpm.shape).half_width > 0.0:  # (GIMP, CPDI)
            out.append(FieldSpec("lp", ("dim",)))
        if any(b.stress for b in case.bodies):
            out.append(FieldSpec("prestress", (3, 3)))
        if case.mpm.velocity_update in ("apic", "mls"):
            out.append(FieldSpec("C", (3, 3)))  # the affine velocity (kernels/mpm/affine.py)
        return out

    # -- the loops ------------------------------------------------------------------------------
    def _optional(self, n=None):
        """The optional per-particle inputs of the kernels over the rows [0, n): an array,
        or None if absent."""
        p = self.p
        n = p.n_owned if n is None else n
        lp = p["lp"][:n] if "lp" in p else None
        fext = p["fext"][:n] if "fext" in p else None
        pfield = p["body"][:n] if self.multi else None
        pre = p["prestress"][:n] if "prestress" in p else None
        mstate = p["mstate"][:n] if "mstate" in p else np.empty((n, 0))
        return n, lp, fext, pfield, pre, mstate

    def _domain_F(self, n):
        """F over the rows [0, n) when it shapes the particle domains (CPDI), else None."""
        return self.p["F"][:n] if self.kind == CPDI else None

    def domain_failure(self, row):
        """Why row's particle failed if its CPDI domain outgrew the stored nodes, else None."""
        if self.kind != CPDI:
            return None
        reach = cpdi_reach(self.dim, self.p["F"][row], self.p["lp"], row)
        limit = self.case.mpm.cpdi_reach
        if reach <= limit:
            return None
        return (f"its CPDI domain reaches {reach:.3f} cells from its centre, beyond "
                f"mpm.cpdi_reach = {limit}; raise it or seed more particles per cell")

    def _p2g(self, with_force, dt=None):
        """P2G; with `fold_force` (and forces) the momentum receives p + dt f."""
        g, p = self.grid, self.p
        n, lp, fext, pfield, _, _ = self._optional(self.n_p2g)
        t = self.timers
        fold = with_force and self.fold_force
        ns = min(self.n_stress, n)
        ng = min(self.n_g2p, ns)
        F = self._domain_F(n)
        # (rows, scatter their stress, scatter forces), as the interface has them
        parts = self.interface.p2g_parts(ng, ns, n, with_force)
        with t.phase("p2g"):
            if self._trim:
                self._span = g.work_range(p["x"], n, self._margin, *self._keep)
            g.reset(*self._span)
            for lo, hi, stress, force in parts:
                # no rows: nothing to scatter (a rank whose slab holds no MPM points pays
                # no kernel calls), but the warm-up compiles the first part's kernel on them
                if hi == lo and (lo > 0 or not self._warming):
                    continue
                sigma = p["sigma"][lo:hi] if stress else self._zero_stress(hi - lo)
                affine = stress and self.affine  # (the MPM rows: the rows that carry C)
                points = scatter_points(p["x"][lo:hi], p["v"][lo:hi], p["mass"][lo:hi],
                                       p["vol"][lo:hi], sigma,
                                       p["C"][lo:hi] if affine else NO_AFFINE)
                # the optional inputs, positionally (fext, lp, F, pfield, gforce, gmgrad,
                # force_dt): None where the scene has none
                optional = (None if fext is None else fext[lo:hi],
                            None if lp is None else lp[lo:hi],
                            None if F is None else F[lo:hi],
                            None if pfield is None else pfield[lo:hi],
                            g.force if force and not fold else None,
                            g.mgrad if self.multi else None,
                            dt if fold and force else None)
                if affine:
                    p2g_affine(self.tags, self.mls, points, g.layout, g.mass, g.mom, *optional)
                else:
                    p2g(self.tags, points, g.layout, g.mass, g.mom, *optional)
        sums = [g.mass, g.mom] + ([g.force] if with_force and not fold else [])
        if self.multi:
            sums.append(g.mgrad)
        if self.halo_enabled:  # ghosts get the full sums too, so no broadcast after the solve
            with t.phase("halo"):
                self.halo.sum(sums)
        if g.folded:
            with t.phase("halo"):
                g.fold_periodic(sums)

    def _solve(self, dt, time, with_force):
        g = self.grid
        with self.timers.phase("grid"):
            mode = ((FOLDED if self.fold_force else WITH_FORCE) if with_force else MOMENTUM)
            grid_velocity(self.dim, g.mass, g.mom, g.force, g.vel, g.dv, dt, self.gravity,
                          self.damping, self.mass_cutoff, mode, *self._span)
            # the SPH solids in contact take the contact's change of their fields, once a
            # step (the solve with forces)
            gather = with_force and self.multi and self.n_p2g > self.n_stress
            if gather:  # the velocities before contact, over the nodes particles can reach
                lo, hi = self._span
                dvc = self._contact_change()
                dvc[:, lo:hi] = g.vel[:, lo:hi]
            if self.multi:
                self._contact(dt)
            if gather:  # (outside the span dvc is stale, but no particle's stencil is there)
                np.subtract(g.vel[:, lo:hi], dvc[:, lo:hi], out=dvc[:, lo:hi])
            # node-local: ghost nodes, holding the full sums (`GridHalo.sum`), get the
            # owners' velocities (and contact changes) bit for bit
            self.bcs.apply(time, g.vel, g.dv)
        if gather:
            p = self.p
            with self.timers.phase("g2p"):
                gather_increment(self.tags, self.n_stress, self.n_p2g, p["x"], p["v"],
                                 g.layout, dvc, lp=p["lp"] if "lp" in p else None,
                                 pfield=p["body"])
        # (the ghosts hold the full nodal mass and force too, from `GridHalo.sum`)
        if with_force:
            self.interface.after_grid_forces(self, dt)

    def _contact(self, dt):
        """Multi-field contact on the solved velocities (kernels/mpm/contact.py): normals
        from the summed mass gradients, each field's reach from its particles (the largest
        over ranks and periodic images), then the contact itself."""
        g, p = self.grid, self.p
        contact_normals(self.dim, g.mass, g.mgrad, self._fluid_field, self.mass_cutoff,
                        g.normals, g.reach)
        n = self.n_p2g
        lp = p["lp"][:n] if self._reach_by_lp else None
        surface_reach(self.dim, p["x"][:n], p["vol"][:n], p["body"][:n], lp, g.node0,
                      g.offset, g.inv_dx, g.strides, self._reach_support, g.normals, g.reach)
        if self.halo_enabled:  # (inside the "grid" phase)
            self.halo.maximum([g.reach])
        if g.folded:
            g.fold_periodic([g.reach], np.fmax)
        multi_field_contact(self.dim, g.mass, g.normals, g.reach, g.vel, g.dv, self.friction,
                            self.mass_cutoff, dt)

    def _gradients(self, n):
        """A reused (n, 3, 3) array for the velocity gradients of an affine G2P."""
        self._grad = rows_at_least(self._grad, n)
        return self._grad[:n]

    def _contact_change(self):
        """A reused array shaped like the grid velocities, for the contact's change."""
        if self._dvc.shape != self.grid.vel.shape:
            self._dvc = np.zeros_like(self.grid.vel)
        return self._dvc

    def _zero_stress(self, n):
        """n rows of zero stress (reused) for the P2G rows that scatter none."""
        self._zeros = rows_at_least(self._zeros, n)
        return self._zeros[:n]

    def attach(self, interface):
        """Take the coupling interface's hooks (physics/coupling.py)."""
        self.interface = interface
        self.fold_force = self.fold_force and interface.lets_mpm_fold_forces

    def grid_force_kick(self, dt):
        """The rows [n_g2p, n_p2g) take their share of the nodal forces (the conservative
        interface's transition SPH rows; `kernels.coupling.grid_force_kick`)."""
        g, p = self.grid, self.p
        a, b = self.n_g2p, self.n_p2g
        _, lp, _, pfield, _, _ = self._optional(b)
        Fd = self._domain_F(b)
        with self.timers.phase("g2p"):
            grid_force_kick(self.tags, p["x"][a:b], p["v"][a:b], g.layout, g.mass, g.force,
                            dt, self.mass_cutoff, lp=lp[a:b] if lp is not None else None,
                            Fdom=Fd[a:b] if Fd is not None else None,
                            pfield=pfield[a:b] if pfield is not None else None)

    def _g2p(self, dt, kinematics, deformation):
        g, p = self.grid, self.p
        n, lp, _, pfield, pre, mstate = self._optional(self.n_g2p)
        bad, signal, Lp = -1, None, None
        blend = kinematics and not self.affine  # the PIC/FLIP kinematics of `g2p`
        if n == 0 and not self._warming:  # no rows (the warm-up compiles on zero rows)
            if deformation and (kinematics or self.scheme.signal_after_deformation):
                self.signal = 0.0
            if deformation and self.averaged is not None:  # (its ghost-node sum is
                self._fbar(dt, 0, lp, pfield, pre, mstate)  # collective: every rank joins)
            return bad
        with self.timers.phase("g2p"):
            if kinematics and self.affine:  # v, C, x (and for USL the gradient L)
                Lp = self._gradients(n) if deformation else None
                bad = g2p_affine(self.tags, self.mls, p["x"][:n], p["v"][:n], p["C"][:n],
                                 g.layout, g.vel, dt, lp, self._domain_F(n), pfield, Lp)
            if deformation or blend:  # (with Lp, F and sigma from it: the grid is not read)
                bad2, signal = g2p(
                    self.tags,
                    gather_points(p["x"][:n], p["v"][:n], p["sigma"][:n], p["vol"][:n],
                                 p["vol0"][:n], p["mat"][:n], mstate),
                    self.materials, g.layout,
                    gather_options(dt, self.flip, self.pic_tag, self.max_reach,
                                  self.want_signal),
                    g.vel, gdv=g.dv if blend else None,
                    F=p.deformation(n) if deformation else None, lp=lp,
                    Fdom=self._domain_F(n), pfield=pfield, prestress=pre, Lp=Lp,
                    stress_later=self.averaged if deformation else None)
                bad = bad if bad >= 0 else bad2
            if deformation and self.averaged is not None:
                bad2 = self._fbar(dt, n, lp, pfield, pre, mstate)
                bad = bad if bad >= 0 else bad2
        # max (c + |v|) of the owned rows, valid when this pass has the final velocities
        # too: USL's single pass and MUSL's second; after USF's first pass v changes again
        if deformation and (kinematics or self.scheme.signal_after_deformation):
            self.signal = signal
        return bad

    def _fbar(self, dt, n, lp, pfield, pre, mstate):
        """F-bar for the plastic rows after G2P updated their F (kernels/mpm/fbar.py): a
        P2G of weights vol0 and vol0 J, their ghost-node sums, the nodal average gathered
        back, then F scaled to it and the stress. Returns a failed row or -1."""
        g, p = self.grid, self.p
        self._fbar_rows = rows_at_least(self._fbar_rows, n)
        self._fbar_weight = rows_at_least(self._fbar_weight, n)
        rows = self._fbar_rows[:n]  # J (as a "velocity"), then the gathered J_bar
        weight = self._fbar_weight[:n]
        vol, vol0, mat = p["vol"][:n], p["vol0"][:n], p["mat"][:n]
        np.multiply(vol0, self.averaged[mat], out=weight)
        np.divide(vol, vol0, out=rows[:, 0])  # J (no temporary)
        if len(self._fbar_nodes) == 0 or self._fbar_nodes[0].shape != g.mass.shape:
            self._fbar_nodes = (np.zeros_like(g.mass), np.zeros_like(g.mom))
        wmass, wj = self._fbar_nodes
        wmass.fill(0.0)
        wj.fill(0.0)
        Fdom = self._domain_F(n)
        if n or self._warming:
            points = scatter_points(p["x"][:n], rows, weight, vol, self._zero_stress(n))
            p2g(self.tags, points, g.layout, wmass, wj, None, lp, Fdom, pfield)
        if self.halo_enabled:  # on every rank, rows or none (the neighbours wait for it)
            with self.timers.phase("halo"):
                self.halo.sum([wmass, wj])
        if g.folded:
            g.fold_periodic([wmass, wj])
        if n == 0 and not self._warming:
            return -1
        rows[:] = 0.0
        add_gathered(self.tags, 0, n, p["x"][:n], rows, g.layout, wj, 1.0, wmass, 0.0, lp,
                     Fdom, pfield)
        return fbar_stress(self.dim, self.averaged, self.materials, mat, p["F"][:n], vol,
                           vol0, rows, dt, mstate, p["sigma"][:n], pre)

    def sort_by_cell(self):
        """Reorder owned particles by grid cell so P2G/G2P walk memory in grid order."""
        g, p = self.grid, self.p
        keys = cell_keys(p["x"], g.origin, g.inv_dx, g.strides)
        p.take(np.argsort(keys, kind="stable"))

    def step(self, dt, time):
        """Advance owned MPM particles by dt; returns the index of a failed particle or -1.
        Leaves `signal` = max (c + |v|) over the owned particles after the step (or None)."""
        bad = self._step(dt, time)
        self._wrap_periodic()
        return bad

    def _wrap_periodic(self):
        """Particles that crossed an end of a periodic axis folded in this rank's grid
        re-enter at the other end (across the wrap of a slab axis they stay beyond it, near
        the slab face, until `Simulation.step` wraps them just before they migrate)."""
        spec = self.case.grid
        if not self.grid.folded:
            return
        x = self.p["x"][: self.n_g2p]
        for a in self.grid.folded:
            wrap_axis(x, a, spec.origin[a], spec.cells[a] * spec.cell_size[a])

    def _step(self, dt, time):
        self.signal = None
        return self.scheme.step(self, dt, time)
