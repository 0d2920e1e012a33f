"""An SPH solid in an MPM fluid: the reverse of the float of cases/coupled_float.toml
(issue 5; seed 000 §4 couples one material across the methods, this a solid and a fluid).
The scene: cases/coupled_sph_solid_float.toml; the test: tests/verification/
test_coupled_sph_solid.py (numbers below at its spacing 0.01, T = 2 s).

The rule, automatic in a coupled scene; (2) needs one velocity field per body
(`[mpm] contact = "multi"`):

  1. Pressure (kernels/sph/rates.py, `sph_rates`). The MPM fluid's points within the support of
     the SPH solid's particles are SPH neighbours of the solid, as in seed 000. A fluid-solid
     pair is the mirror pair of the forward float (the fluid's own pressure on both ends,
     twice the solid's volume); its force pushes the solid particle and its reaction acts
     on the fluid point as an external force in P2G (`fsi`). The solid's own kinematics
     (continuity drho/dt and velocity gradient L, hence F and its stress) sum over its own
     material only: a fluid neighbour acts on it by pressure alone. With the water's
     velocities summed into the ice's L the ice was sheared by the water's flow: the total
     energy rose from 83 to 967 J by t = 0.2 s and a particle left the grid at t = 0.41 s
     (without the contact of (2): 480 J by t = 0.15 s, failed at t = 0.32 s; and started
     at rho0, without (2) or (3): 223 J by t = 0.05 s, failed at t = 0.09 s).
  2. Impenetrability (the MPM grid). The fluid's grid does not see the solid, and a
     pressure-only pair force has no stiffness against the solid closing in on the fluid
     (the pair's kernel-gradient sum peaks at a gap of about h/2 and falls to zero at
     contact): with (1) alone the block, released 4 mm above its equilibrium, closed in on
     the water row below it at a steady 1 mm/s (the row came within 0.04 of a spacing by
     t = 3.6 s). So the SPH solid particles near the fluid (within one cell of the fluid's
     cells, as seed 000's transition zone) take part in P2G, in their own velocity field
     (their body's), with their mass, momentum and SPH force m (a - g) (their last SPH
     acceleration; the grid adds gravity back, and their stress is in that force, so it is
     not scattered again): that field's nodal velocity is then the solid's own prediction
     for the end of the step. The frictionless multi-field contact of Bardenhagen et al.
     (kernels/mpm/contact.py) removes the approach of the fluid's field towards it, so the
     solid's motion compresses the fluid on the grid as it would a fluid MPM body; the change
     dv_c the contact made to the solid's field is gathered back to its SPH particles,
     v_p += sum_I N_I dv_c,I (kernels/coupling.py, `gather_increment`), so the fluid's loss
     of momentum is exactly the solid's gain (sum_p N_Ip m_p = m_I). The fluid's field holds
     the fluid only: the two never mix velocities on the grid. The contact acts where the two
     bodies' particle surfaces meet at a node (kernels/mpm/contact.py). Until 2026-11-26 it
     acted where the fields' nodal centres of mass came within a multiple of their touching
     separation: at 1 (Nairn's check) only once the lattices overlapped, and the water row
     below the block closed in on the block's bottom row (to 0.04 spacing by t = 4.8 s)
     while the block crept past Archimedes (0.1142 at t = 4.8 s, still sinking); the case
     took 1.5, found by trial.
     Measured (spacing 0.01, the centre-of-mass check at 1.5): the block sinks from a draft
     of 0.110 and settles at 0.1135-0.1136 over t = 5-6 s, Archimedes for the seeded lattice
     0.1137 (-0.1 %; with the surface check 0.1140-0.1141, +0.3 %); the nearest water point
     stays 0.90 spacing from the block's particles; the
     contact carries about 20 % of the block's weight (the rest is the pressure pairs); the
     total energy rises by 0.2 J (0.25 %) in the first 0.5 s, the contact's work, and falls
     below its start by t = 4 s (83.37 -> 83.15 J at t = 6). With (2) alone (no
     pressure pairs) the block sinks at 3 mm/s, past Archimedes by t = 1 s, with 24 water
     points inside its lattice by t = 1.8 s (the centre-of-mass check at 1). (Started at
     rho0, without (3), it runs to the end with or without (2): drafts 0.108 and 0.107 at
     t = 1.8 s, -5 %.)
  3. Initial state. With `[sph] hydrostatic = true` the MPM fluid bodies start hydrostatic
     as the SPH ones (physics/hydrostatic.py): J = rho0/rho(z), volume, density and pressure
     (the water of scene 7, kappa = 2e3, is 11 % denser at its floor than at its surface:
     seeded at rho0 it falls by its compression first).
Still open: the approach to equilibrium is slow. PIC (`mpm.flip = 0`, the case's) slows
every flow of the water by its dissipation (the ice's wave speed and the SPH h set a step
about 10 times below the one the water alone would take on this grid): the block needs
about 5 s to settle, and released on the surface (the thesis' start; the check at 1) it sinks
at 1 cm/s, to a draft of only 0.05 by t = 1.8 s. With FLIP (the check at 1) the block drops
and bobs at the right pace but overshoots: flip = 0.9 reaches Archimedes' draft at t = 0.8 s
and goes on sinking (0.1152 at t = 1.8 s), flip = 0.99 0.1193 (+5 %), flip = 1 rings
(kinetic energy 0.6 J at t = 1.8 s); with the check at 1.5, flip = 0.9 passes Archimedes at
t = 2.7 s and sinks on (0.1143 at t = 3), flip = 0.99 reaches it at t = 1.8 s and bobs about
it (0.1132-0.1138 over t = 1.8-3 s) while the water closes in to 0.49 spacing.
"""


def solid_force(p, lo, hi, gravity):
    """fext = m (a - g) for the SPH solid rows [lo, hi) in contact: P2G scatters it into
    their field, whose grid solve adds m g back (their stress is inside `a`)."""
    dim = len(gravity)
    p["fext"][lo:hi] = p["mass"][lo:hi, None] * (p["acc"][lo:hi, :dim] - gravity[None, :])
