"""The SPH stages (updated and total Lagrangian), their time integrators and the SPH solid
in an MPM fluid."""
