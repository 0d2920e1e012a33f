"""MPM-SPH coupling after Raymond, Jones & Williams (seed 000, §4).

Both methods share one particle state, so coupling is a matter of which particles take part
in which sums:
  * the MPM region is the set of grid cells that hold MPM particles (it moves with them);
    SPH particles within one cell of it (the transition zone) take part in P2G with their
    mass, momentum and stress, but are updated by SPH;
  * MPM particles within the support of SPH particles are SPH neighbours (they carry
    rho = m/V, sigma, v like any SPH particle), but are updated by MPM;
  * each particle is updated by the scheme of its own method;
  * SPH solid particles near an MPM fluid of another material (with [mpm] contact = "multi")
    take part in P2G in their own velocity field, in contact with the fluid's on the grid
    (physics/sph/solid_in_fluid.py).
Rows are kept ordered MPM | transition SPH | SPH solids in contact | other SPH (walls) so
that P2G runs over one prefix of the owned rows and G2P over a shorter one; the order is
restored only when membership changed or migration moved rows. With `handover`, a
particle that crosses a method-region boundary is relabelled (a change of `method`, nothing
else: the state is shared).

Two interfaces (`[coupling] interface`):
  * "seed" (default; seed 000 §4 as written): the transition SPH particles' stresses enter
    P2G (so they push the MPM points through the grid) and the MPM points' stresses enter
    the SPH sums (S_a + S_b). Each particle's momentum equation is then a consistent
    divergence of the stress field: a uniform stress is an exact equilibrium at the
    interface (the patch test; tests/verification/test_coupled.py). But the force that a
    particle's stress exerts on the other side is not the adjoint of the strain rate that
    particle measures from it: an SPH particle's L sees its MPM neighbours through the
    kernel while its stress pushes them through the grid, and an MPM point's L sees the
    SPH momentum on the grid while its stress pushes the SPH particles through the kernel.
    So the interface forces are neither equal and opposite (momentum) nor work-conjugate
    (energy); for a two-cell wave (scene 8, k = 10) the energy drifts by 41 %.
  * "conservative": every particle's stress acts through the discretisation of its own
    strain rate, on every particle whose velocity that strain rate reads:
      - an MPM point's L comes from the grid velocities, which hold the transition SPH
        momentum: its stress (alone in the P2G force) pushes every P2G particle through
        the grid, the transition SPH particles too (`kernels.coupling.grid_force_kick`);
        the SPH particles' stresses stay out of P2G;
      - an SPH particle's L sums over its MPM neighbours too: its stress pushes them
        through the kernel, as a pair reaction (`fcpl`, sph_rates' one-sided pairs) kicked
        straight into the MPM points' velocities (through the grid, which cannot carry a
        two-cell wave, the work would not match);
      - all particles take the same Verlet kicks: the SPH and MPM rows get their pair
        forces as half kicks before the MPM step and after the SPH evaluation, so P2G
        carries every particle's momentum at the same stage (`before_mpm`, `after_sph`).
    Momentum is conserved to round-off and energy as well as in pure MPM (scene 8), but the
    two halves of the interface traction (the MPM block's grid surface force, shared by
    mass, and the SPH pair reactions) are different discretisations that do not cancel:
    a uniform stress leaves forces on the two particles either side of the interface (up
    to 0.08 sigma with h = 1.3 spacing, 0.14 sigma with h = cell size in 1D), and under a
    sustained load their constant part accumulates in the MPM points' sub-grid (FLIP)
    velocities, which the grid cannot see: a statically loaded bar (scene 9) does not
    settle. For wave problems, not for loads.
"""
import numpy as np

from ..codes import METHOD_CODES, MPM, SPH
from ..jit import njit
from ..particles import FieldSpec
from ..scene.regions import region_methods
from .scratch import rows_at_least
from .sph.solid_in_fluid import solid_force

#: row keys: MPM, transition SPH (same material), SPH solid in contact, the rest
TRANSITION, CONTACT, REST = 1, 2, 3


@njit
def mark_mpm_cells(dim_tag, n, x, method, mat, material, origin, inv_dx, strides, shape,
                   mark):
    """mark[node] = 1 for the corner nodes of every cell holding an MPM row of [0, n) of
    `material`."""
    dim = len(dim_tag)
    for p in range(n):
        if method[p] != MPM or mat[p] != material:
            continue
        c0 = min(max(int(np.floor((x[p, 0] - origin[0]) * inv_dx)), 0), shape[0] - 2)
        c1 = 0
        c2 = 0
        if dim > 1:
            c1 = min(max(int(np.floor((x[p, 1] - origin[1]) * inv_dx)), 0), shape[1] - 2)
        if dim > 2:
            c2 = min(max(int(np.floor((x[p, 2] - origin[2]) * inv_dx)), 0), shape[2] - 2)
        for k in range(2 if dim > 2 else 1):
            for j in range(2 if dim > 1 else 1):
                for i in range(2):
                    idx = (c0 + i) * strides[0]
                    if dim > 1:
                        idx += (c1 + j) * strides[1]
                    if dim > 2:
                        idx += (c2 + k) * strides[2]
                    mark[idx] = 1.0


@njit
def transition_keys(dim_tag, n, x, method, mat, select, value, origin, inv_dx, strides,
                    shape, mark, key):
    """For the SPH rows of the materials with `select[mat]`: key = min(key, value) if within
    one cell of a marked cell (a marked node among the nodes of the 3^dim cells around its
    own). With value < 0 instead initialise: key = 0 for MPM rows, REST for all others."""
    dim = len(dim_tag)
    c = np.zeros(3, np.int64)
    for p in range(n):
        if value < 0:
            key[p] = 0 if method[p] == MPM else REST
            continue
        if method[p] != SPH or not select[mat[p]] or key[p] <= value:
            continue
        for a in range(dim):
            c[a] = int(np.floor((x[p, a] - origin[a]) * inv_dx))
        found = False
        for k in range(-1, 3) if dim > 2 else range(0, 1):
            for j in range(-1, 3) if dim > 1 else range(0, 1):
                for i in range(-1, 3):
                    i0 = c[0] + i
                    i1 = c[1] + j if dim > 1 else 0
                    i2 = c[2] + k if dim > 2 else 0
                    if i0 < 0 or i0 >= shape[0]:
                        continue
                    if dim > 1 and (i1 < 0 or i1 >= shape[1]):
                        continue
                    if dim > 2 and (i2 < 0 or i2 >= shape[2]):
                        continue
                    idx = i0 * strides[0]
                    if dim > 1:
                        idx += i1 * strides[1]
                    if dim > 2:
                        idx += i2 * strides[2]
                    if mark[idx] > 0.0:
                        found = True
        if found:
            key[p] = value


@njit
def is_sorted(key, n):
    for p in range(1, n):
        if key[p] < key[p - 1]:
            return False
    return True


class Uncoupled:
    """A scene of one method: every hook of the coupled step does nothing. `Simulation.step`
    and the MPM and SPH stages call the hooks of whatever interface the scene has (this one,
    `SeedInterface` or `ConservativeInterface`), never asking which it is."""

    name = "none"
    #: whether the interface keeps the owned rows in its own order (no sort by cell)
    keeps_row_order = False
    #: whether the MPM stage may fold dt f into the P2G momentum (`MPMStage.fold_force`)
    lets_mpm_fold_forces = True
    handed_over = 0
    reorders = 0

    @staticmethod
    def fields(case):
        return []

    def prepare(self):
        """Before the step: order and classify the rows (coupled scenes)."""

    def before_mpm(self, dt):
        """After `prepare`, before the MPM stage."""

    def after_mpm(self):
        """After the MPM stage, before the SPH stage."""

    def sph_step(self, sph, dt, time):
        """The SPH stage's step; returns a failed row or -1."""
        return sph.step(dt, time)

    def after_sph(self, dt):
        """After the SPH stage."""

    def p2g_parts(self, ng, ns, n, with_force):
        """Row ranges of P2G as (lo, hi, scatter the stress, scatter the forces): rows
        [0, ns) with their stress, [ns, n) (SPH solids in contact, physics/sph/solid_in_fluid.py,
        whose stress is in their SPH force `fext`) without; ng is where the rows that G2P
        updates end."""
        if ns < n:
            return ((0, ns, True, with_force), (ns, n, False, with_force))
        return ((0, n, True, with_force),)

    def after_grid_forces(self, mpm, dt):
        """In the MPM step, once the nodal forces are summed (ghosts included)."""

    def warm_up(self, sim):
        """Compile what the hooks run, on the empty rows of `warmup._dry_step`."""


class SeedInterface(Uncoupled):
    """Seed 000 §4's interface: keeps the owned rows ordered for the coupled step, hands
    particles over, and lets every P2G row scatter its stress (module docstring)."""

    name = "seed"
    keeps_row_order = True

    @staticmethod
    def fields(case):
        out = [FieldSpec("fsi", ("dim",)), FieldSpec("fext", ("dim",), migrate=False)]
        if case.coupling.interface == "conservative":
            out.append(FieldSpec("fcpl", ("dim",)))
        return out

    def __init__(self, case, particles, mpm, sph, timers):
        self.case = case
        self.p = particles
        self.mpm = mpm
        self.sph = sph
        self.timers = timers
        self.dim_tag = (0,) * case.dim
        self.handover = case.coupling.handover
        self.key = np.zeros(0, np.int8)
        self.loads = bool(case.loads)
        names = list(case.materials)
        self.mpm_materials = sorted({names.index(b.material) for b in case.bodies
                                     if b.method == "mpm" or case.regions})
        fluid = np.array([m.fluid for m in case.materials.values()])
        # the materials SPH rows can have: those of the SPH bodies, or with method regions
        # any (a particle's method follows its region)
        sph = np.zeros(len(names), bool)
        for b in case.bodies:
            sph[names.index(b.material)] |= bool(case.regions) or (b.method == "sph"
                                                                   and not b.wall)
        # per MPM material: the materials whose SPH rows join its P2G, and how; a join no
        # SPH row can take is left out (with its marks and their exchange between ranks)
        self._joins = []
        for material in self.mpm_materials:
            same = np.arange(len(names)) == material
            if sph[material]:
                self._joins.append((material, same, TRANSITION))
            solids = ~fluid & ~same & sph
            if fluid[material] and case.mpm.contact == "multi" and solids.any():
                self._joins.append((material, solids, CONTACT))
        self.gravity = np.array(case.gravity, float)
        self.reorders = 0
        self.handed_over = 0
        self._mark_buffers = {}  # (`_marks`)

    def _marks(self, material):
        g = self.mpm.grid
        # one array per material, reused: the grid halo keeps its exchange plan per array
        mark = self._mark_buffers.get(material)
        if mark is None or mark.shape[1] != g.n_nodes:
            mark = self._mark_buffers[material] = np.zeros((1, g.n_nodes))
        else:
            mark[...] = 0.0
        p = self.p
        shape = np.array(g.shape, np.int64)
        mark_mpm_cells(self.dim_tag, p.n_owned, p["x"], p["method"], p["mat"], material,
                       g.origin, g.inv_dx, g.strides, shape, mark[0])
        if self.mpm.halo_enabled:  # (the coupling's exchange: timed as one)
            with self.timers.phase("halo"):
                self.mpm.halo.sum([mark])
        g.fold_periodic([mark])  # a cell at one end of a periodic axis borders the other
        return mark[0], shape

    def prepare(self):
        """Order rows MPM | transition SPH | SPH solids in contact | rest; tell the MPM stage
        its three prefixes."""
        with self.timers.phase("coupling"):
            self._prepare()

    def _prepare(self):
        p = self.p
        n = p.n_owned
        p.drop_halo()
        if self.handover:
            self._hand_over()
        self.key = rows_at_least(self.key, n)
        key = self.key[:n]
        g = self.mpm.grid
        shape = np.array(g.shape, np.int64)
        transition_keys(self.dim_tag, n, p["x"], p["method"], p["mat"], np.zeros(1, np.bool_),
                        -1, g.origin, g.inv_dx, g.strides, shape, np.zeros(1), key)
        # the transition zone joins SPH particles to MPM ones of the same material (seed
        # 000: one continuum, two discretisations); different materials meet through the
        # SPH pair forces and their reactions instead (`fsi`), and an SPH solid near an MPM
        # fluid also through the grid contact of its own velocity field (sph_solid.py)
        marks = {}
        for material, select, value in self._joins:
            if material not in marks:
                marks[material] = self._marks(material)
            mark, shape = marks[material]
            transition_keys(self.dim_tag, n, p["x"], p["method"], p["mat"], select, value,
                            g.origin, g.inv_dx, g.strides, shape, mark, key)
        if not is_sorted(key, n):
            order = np.argsort(key, kind="stable")
            p.take(order)
            key[:] = key[order]
            self.reorders += 1
            if self.sph is not None:
                self.sph.invalidate()
        counts = np.cumsum(np.bincount(key, minlength=REST + 1))
        self.mpm.n_g2p = int(counts[0])
        self.mpm.n_stress = int(counts[TRANSITION])
        self.mpm.n_p2g = int(counts[CONTACT])
        # the reactions of the SPH pair forces on MPM points act as external forces in P2G
        m = self.mpm.n_g2p
        if self.loads:
            p["fext"][:m] += p["fsi"][:m]
        else:
            p["fext"][:m] = p["fsi"][:m]
        p["fext"][m:n] = 0.0
        lo, hi = self.mpm.n_stress, self.mpm.n_p2g
        if hi > lo:
            solid_force(p, lo, hi, self.gravity)

    def after_mpm(self):
        """MPM rows are SPH neighbours: give them the SPH density rho = m/V."""
        p = self.p
        n = self.mpm.n_g2p
        p["rho"][:n] = p["mass"][:n] / p["vol"][:n]

    def _hand_over(self):
        """Relabel particles whose method region changed (walls never change)."""
        p = self.p
        meth = p["method"]
        want = region_methods(self.case, p["x"], meth)
        change = np.nonzero((want != meth) & (meth != METHOD_CODES["wall"]))[0]
        if len(change):
            to_sph = change[want[change] == SPH]
            # an MPM particle entering SPH starts from its MPM density; F and sigma carry on
            p["rho"][to_sph] = p["mass"][to_sph] / p["vol"][to_sph]
            if "u" in p:  # the hourglass control's displacement, which MPM does not carry
                p["u"][to_sph] = p["x"][to_sph] - p["X0"][to_sph]
            meth[change] = want[change]
            self.handed_over += len(change)
            if self.sph is not None:
                self.sph.invalidate()

    def warm_up(self, sim):
        with self.mpm.detached():
            self._prepare()
        self.mpm.n_p2g = self.mpm.n_g2p = self.mpm.n_stress = None


class ConservativeInterface(SeedInterface):
    """Every particle's stress acts through the discretisation of its own strain rate
    (module docstring): the transition SPH rows scatter no stress into P2G and take their
    share of the nodal forces afterwards; the SPH pair reactions on the MPM rows (`fcpl`)
    and the SPH rates are given as the two half kicks of one Verlet step."""

    name = "conservative"
    # (the nodal forces are needed apart from the momentum: `after_grid_forces`)
    lets_mpm_fold_forces = False

    def before_mpm(self, dt):
        """The first half kick of the Verlet step, for the SPH rows (their rates) and the
        MPM rows (the reactions `fcpl` of their SPH pairs), before the MPM step, so that its
        P2G carries every particle's momentum at the same stage."""
        self.after_mpm()  # (the first SPH evaluation needs rho of the MPM rows)
        self.sph.kick(dt)
        self._kick_mpm(dt)

    def sph_step(self, sph, dt, time):
        return sph.step(dt, time, kicked=True)

    def after_sph(self, dt):
        """The MPM rows' second half kick with the reactions of the step's last SPH
        evaluation (at the new state), as the SPH rows get theirs."""
        self._kick_mpm(dt)

    def _kick_mpm(self, dt):
        p = self.p
        m = self.mpm.n_g2p
        p["v"][:m] += (0.5 * dt) * p["fcpl"][:m] / p["mass"][:m, None]

    def p2g_parts(self, ng, ns, n, with_force):
        """MPM rows with their stress; transition SPH rows with neither stress nor force
        (they take the grid force afterwards, `after_grid_forces`); SPH solids in contact."""
        return ((0, ng, True, with_force), (ng, ns, False, False), (ns, n, False, with_force))

    def after_grid_forces(self, mpm, dt):
        """The transition SPH rows take their share of the nodal forces
        (`kernels.coupling.grid_force_kick`)."""
        if mpm.n_p2g > mpm.n_g2p:
            mpm.grid_force_kick(dt)

    def warm_up(self, sim):
        with sim.mpm.detached():
            sim.mpm.grid_force_kick(1e-30)  # (its rows are empty in the dry step)
        super().warm_up(sim)


#: the interfaces by `[coupling] interface`
INTERFACES = {"seed": SeedInterface, "conservative": ConservativeInterface}


def coupling_fields(case):
    """The fields the scene's interface needs (none without coupling)."""
    return SeedInterface.fields(case) if case.coupled else []


def interface_for(case, particles, mpm, sph, timers):
    """The scene's interface: `Uncoupled` for one method, else `[coupling] interface`'s."""
    if not case.coupled:
        return Uncoupled()
    return INTERFACES[case.coupling.interface](case, particles, mpm, sph, timers)
