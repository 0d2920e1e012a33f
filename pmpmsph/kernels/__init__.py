"""Pure @njit kernels over plain arrays. They import only numpy, numba and math (DESIGN.md §1)."""
