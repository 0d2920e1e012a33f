"""What walls and solids next to a fluid add to an updated-Lagrangian SPH evaluation
(`SPHStage.evaluate`), in the order it needs them:

1. `derive`, before the pair loop: the dummy walls' state (their ghost velocity and their
   pressures towards fluids and towards solids, Adami, Hu & Adams 2012:
   `kernels.sph.walls.wall_state`) and the fluid pressure extrapolated to the solid rows a
   fluid meets (`kernels.sph.walls.mirror_pressure`), then refreshed in the halo;
2. the pair loop (`kernels.sph.rates.sph_rates`) reads them through `rate_terms`;
3. `contact`, after every other force: the contact walls' push and Coulomb friction on the
   SPH solids (`kernels.sph.contact`);
4. `move`, at the end of a step: walls that move with their velocity (`bodies[].moving`).
"""
import numpy as np

from ...kernels.sph.contact import wall_contact, wall_gaps
from ...kernels.sph.stress import sync_ghost_velocity
from ...kernels.sph.views import NO_CONTACT
from ...kernels.sph.walls import mirror_pressure, wall_state
from ...particles import FieldSpec
from ..scratch import rows_at_least

#: no rows held by mirror clamps (`wall_contact` without clamps)
_NO_HELD = np.zeros(0, np.bool_)


def fluid_meets_solid(case):
    """Whether an SPH fluid (a Tait body, not a wall) can meet a solid of another material in
    the SPH sums (an SPH solid or wall, or an MPM body in a coupled scene): the mirror pair of
    `kernels.sph.rates.sph_rates`, whose solid rows then carry the fluid pressure `pw`."""
    def fluid(b):
        return case.materials[b.material].fluid

    return (case.sph.formulation == "updated"
            and any(b.method == "sph" and not b.wall and fluid(b) for b in case.bodies)
            and any(not fluid(b) and (b.method == "sph" or case.coupled)
                    for b in case.bodies))


class WallTerms:
    """The walls' and mirrored solids' part of one SPH stage (module doc). `fluid`: per
    material, whether it is a Tait fluid; `gravity`: a 3-vector."""

    def __init__(self, case, materials, fluid, gravity):
        self.dim = case.dim
        self.materials = materials
        self.fluid = fluid
        self.gravity = gravity
        self.no_slip = case.sph.wall_no_slip
        # contact walls: the Coulomb coefficient of each body (< 0: a plain dummy wall, or
        # not a wall), the solid rows' gaps to them (scratch); the friction's stick limit
        # needs the step's dt (`SPHStage.step` sets `dt`)
        self.wall_mu = np.array([-1.0 if b.friction is None else b.friction
                                 for b in case.bodies])
        self.with_contact = bool(np.any(self.wall_mu >= 0.0))
        self._gaps = np.zeros((0, 5))
        self.dt = 0.0
        # walls that move with their velocity (bodies[].moving), by body index
        self.moving = np.array([i for i, b in enumerate(case.bodies) if b.moving], np.int32)

    @staticmethod
    def fields(case):
        """The fields these terms need (DESIGN.md §2): none without walls or mirrors."""
        out = []
        if any(b.wall for b in case.bodies):
            out.append(FieldSpec("vg", ("dim",), migrate=False, halo=True))
            # the walls' pressure towards SPH solids (kernels/sph/walls.py wall_state)
            out.append(FieldSpec("pws", (), migrate=False, halo=True))
        if fluid_meets_solid(case):  # the fluid pressure at solid rows (mirror pairs)
            out.append(FieldSpec("pw", (), migrate=False, halo=True))
        return out

    #: the fields `derive` computes and refreshes itself (the evaluation's first halo
    #: refresh leaves them out)
    DERIVED = ("vg", "pws", "pw")

    def derive(self, p, smoothing, pairs, halo, timers):
        """Step 1 of the module doc over owned and halo rows; `halo` None: no refresh (the
        kernels' warm-up)."""
        x = p.with_halo("x")
        if "vg" in p:
            with timers.phase("sph"):
                sync_ghost_velocity(p.n_total, p.with_halo("method"), p.with_halo("v"),
                                    p.with_halo("vg"))
                wall_state(smoothing, pairs, x, p.with_halo("v"), p.with_halo("rho"),
                           p.with_halo("sigma"), p.with_halo("method"), p.with_halo("mat"),
                           self.materials, self.fluid, self.gravity, self.no_slip,
                           p.with_halo("vg"), p.with_halo("pws"))
        if "pw" in p:  # (after the walls: a wall of a solid material is a solid row too)
            with timers.phase("sph"):
                mirror_pressure(smoothing, pairs, x, p.with_halo("rho"), p.with_halo("sigma"),
                                p.with_halo("method"), p.with_halo("mat"), self.fluid,
                                self.gravity, p.with_halo("pw"))
        derived = ((("rho", "sigma", "vg", "pws") if "vg" in p else ())
                   + (("pw",) if "pw" in p else ()))
        if derived and halo is not None:
            with timers.phase("halo"):
                halo.refresh(derived)

    def rate_terms(self, p):
        """(pws, contact) of `rate_terms`: the walls' pressure towards solids (None without
        walls) and the contact walls (`NO_CONTACT` without)."""
        return (p.with_halo("pws") if "pws" in p else None,
                (self.wall_mu, p.with_halo("body")) if self.with_contact else NO_CONTACT)

    def contact(self, p, n, start, index, held):
        """Step 3 of the module doc on the owned rows [0, n), added to `acc`; `held`: the
        rows of mirror clamps (None without)."""
        if not self.with_contact:
            return
        rho = p.with_halo("rho")
        self._gaps = rows_at_least(self._gaps, n)
        wall_gaps(self.dim, n, start, index,
                  p.with_halo("x"), p.with_halo("mass"), rho, p.with_halo("method"),
                  p.with_halo("mat"), self.fluid, self.wall_mu, p.with_halo("body"),
                  self._gaps)
        wall_contact((0,) * self.dim, n, self._gaps, p.with_halo("v"),
                     p.with_halo("mass"), rho, p.with_halo("cs"), self.wall_mu,
                     p.with_halo("body"), _NO_HELD if held is None else held, self.dt,
                     p.with_halo("acc"))

    def move(self, p, n, dt):
        """Step 4 of the module doc: x += dt v of the owned rows of moving walls."""
        if len(self.moving):
            moving = np.isin(p["body"][:n], self.moving)
            p["x"][:n][moving] += dt * p["v"][:n][moving]
