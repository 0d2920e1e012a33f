"""The MPM stage: its grid, grid boundary conditions and transfer schemes."""
