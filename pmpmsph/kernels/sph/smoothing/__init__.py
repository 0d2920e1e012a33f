"""SPH smoothing kernels, one module each, registered with `registry.register_kernel`."""
