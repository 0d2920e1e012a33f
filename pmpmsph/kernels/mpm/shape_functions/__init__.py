"""MPM shape functions, one module each, registered with `registry.register_shape`."""
