"""SPH kernels: the kernel functions (`kernel_functions`), the updated-Lagrangian rates
(`rates`) with their corrections, diffusion, walls, shifting, hourglass control and
artificial stress, the time integration (`integrate`), and the total-Lagrangian form
(`tlsph`)."""
