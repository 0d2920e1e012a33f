"""MPM transfer schemes: the order of one step's passes, one class each (after CB-Geo MPM's
`MPMScheme` subclasses, include/solvers/mpm_scheme/). A scheme drives an `MPMStage`
through its three passes:
  stage._p2g(with_force, dt=None)        scatter mass and momentum (and the forces)
  stage._solve(dt, time, with_force)     the grid velocities (with boundary conditions)
  stage._g2p(dt, kinematics, deformation)  gather: move the particles (kinematics) and/or
                                         update F and the stress (deformation)
and returns a failed particle's row or -1. A new scheme is one class here and its line in
`TRANSFER_SCHEMES` (the case file's `[mpm] transfer` choices come from it).
Naming after Nairn (2003) and Buzzi et al. (2008); Raymond (seed 000, section 3) uses MUSL.
"""


class TransferScheme:
    """One MPM step (module docstring). Traits:
    stress_last: the stress is updated from the grid velocities of the same pass that moves
        the particles (one pass: MLS-MPM's gradient, and P2G may fold dt f into the momentum
        of a PIC/affine scheme, as Taichi's mpm88 does);
    signal_after_deformation: the deformation pass comes last, so the signal speed it
        measures is that of the final velocities (the CFL time step reads it)."""

    name = ""
    stress_last = False
    signal_after_deformation = False

    def step(self, stage, dt, time):
        raise NotImplementedError


class UpdateStressLast(TransferScheme):
    """USL: one P2G with the forces, one grid solve, one G2P that moves the particles and
    updates their stress from the same grid velocities."""

    name = "usl"
    stress_last = True

    def step(self, stage, dt, time):
        stage._p2g(True, dt)
        stage._solve(dt, time, True)
        return stage._g2p(dt, True, True)


class UpdateStressFirst(TransferScheme):
    """USF: the stress from the momentum's velocities before the forces act, then the
    forces and the motion (two P2G, two solves, two G2P)."""

    name = "usf"

    def step(self, stage, dt, time):
        stage._p2g(False)
        stage._solve(dt, time, False)
        bad = stage._g2p(dt, False, True)
        stage._p2g(True)
        stage._solve(dt, time, True)
        bad2 = stage._g2p(dt, True, False)
        return bad if bad >= 0 else bad2


class ModifiedUpdateStressLast(TransferScheme):
    """MUSL: the forces and the motion first, then the particles' new momentum scattered
    again and the stress updated from those velocities (Sulsky et al. 1994's modified
    scheme; seed 000, section 3)."""

    name = "musl"
    signal_after_deformation = True

    def step(self, stage, dt, time):
        stage._p2g(True)
        stage._solve(dt, time, True)
        bad = stage._g2p(dt, True, False)
        stage._p2g(False)
        stage._solve(dt, time, False)
        bad2 = stage._g2p(dt, False, True)
        return bad if bad >= 0 else bad2


#: `[mpm] transfer` -> scheme class
TRANSFER_SCHEMES = {cls.name: cls for cls in (UpdateStressLast, UpdateStressFirst,
                                              ModifiedUpdateStressLast)}
