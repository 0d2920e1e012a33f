"""Integer type codes and array sizes shared by the registry and the compiled kernels.

Plain Python (no numba import) so that the configuration layer can use it cheaply.
The kernels branch on these codes in `pmpmsph.materials.dispatch`.
"""

LINEAR_ELASTIC = 0
STVK = 1
NEO_HOOKEAN = 2
HARTMANN_NEFF = 3
MAXWELL = 4
TAIT_FLUID = 5

#: length of every material parameter vector (`Material.params(dim)`)
NPAR = 8

#: index of the reference density rho0 in every parameter vector
PAR_RHO0 = 2

#: largest internal-state length of any model (Maxwell: symmetric C_i, 6 entries)
MAX_STATE_SIZE = 6

#: type code -> canonical model name
TYPE_NAMES = {
    LINEAR_ELASTIC: "linear_elastic",
    STVK: "stvk",
    NEO_HOOKEAN: "neo_hookean",
    HARTMANN_NEFF: "hartmann_neff",
    MAXWELL: "maxwell",
    TAIT_FLUID: "tait_fluid",
}
