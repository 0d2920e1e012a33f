"""Sizes shared by the material configuration classes and the compiled kernels.

Plain Python (no numba import). The type codes themselves belong to each law (its
configuration class's `type_code`, registered in `pmpmsph.materials.registry`).
"""

#: length of every material parameter vector (`Material.params(dim)`)
NPAR = 8

#: index of the reference density rho0 in every parameter vector
PAR_RHO0 = 2
