"""The `method` field's codes: which scheme updates a particle (seed 000 §4). The bottom of
the package: every layer that tests a particle's method (kernels, physics, the builder)
reads them from here."""

#: an MPM material point (updated through the grid)
MPM = 0
#: an SPH particle (updated by the kernel sums)
SPH = 1
#: a dummy wall particle of the SPH walls (not updated; Adami et al. 2012)
WALL = 2
#: the case's names for them (`bodies[].method`, `wall = true`)
METHOD_CODES = {"mpm": MPM, "sph": SPH, "wall": WALL}
