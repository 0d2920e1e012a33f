"""CPDI1, convected particle domain interpolation (Sadeghirad, Brannon & Burghardt 2011):
the particle's domain is the parallelogram (parallelepiped) of half-edges r_a = F lp_a e_a,
and its weight and gradient are averages of linear hats over that domain, evaluated from its
2^dim corners (`kernels.mpm.shapes.corner_stencil`, `cpdi_domain`). Half-widths lp <= 1 cell
at the start; the grid's ghost layers follow `mpm.cpdi_reach`."""
from .linear import weights_linear
from .registry import ShapeFunction, register_shape

#: (the corner stencils are CPDI's alone: `kernels.mpm.shapes` tests this code)
CPDI = 4

register_shape(ShapeFunction("cpdi", CPDI, weights_linear, width=2, support=1.5,
                             half_width=1.0, corners=True))
