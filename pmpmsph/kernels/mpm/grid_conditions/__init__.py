"""Grid boundary conditions of MPM, one module each, registered with
`registry.register_condition`."""
