"""MPM kernels: shape functions (`shapes`), the particle-grid transfers P2G/G2P of the
standard and the affine schemes (`transfers`, `affine`), and the multi-field contact on the
grid (`contact`)."""
