"""Everything MPI: the Distributor, slab decomposition, ghost nodes, halos, migration, balance.

The only package that calls mpi4py point-to-point routines (DESIGN.md §1)."""
