"""The hydrostatic initial state of Tait fluid bodies, for SPH and MPM alike.

Integrating dp/dz = rho(p) |g| with the Tait law rho = rho0 (1 + p/kappa)^(1/gamma) (seed 003,
eq. 50) from p = 0 at the top gives, at depth z,
    rho = rho0 (1 + (gamma - 1)/gamma rho0 |g| z/kappa)^(1/(gamma - 1)),
and rho = rho0 exp(rho0 |g| z/kappa) for gamma = 1 (the limit). The top is a body's highest
particle plus half a spacing (a flat surface). Without it a column seeded at rho0 drops by its
compression and rings (cases/sph_hydrostatic.toml).
"""
import numpy as np

from ..codes import METHOD_CODES
from ..materials.fluid import TAIT_FLUID
from ..materials.fluid import tait_pressure


def tait_hydrostatic_density(rho0, kappa, gamma, g, depth):
    """rho at `depth` below the surface (module doc)."""
    s = rho0 * g * depth / kappa
    if gamma == 1.0:
        return rho0 * np.exp(s)
    return rho0 * np.exp(np.log1p((gamma - 1.0) / gamma * s) / (gamma - 1.0))


def fluid_columns(case, particles, materials, gravity, method, half_spacing, dist=None):
    """For every Tait body of `method` ("sph" or "mpm", walls left out): (its owned rows as a
    mask, their hydrostatic density, the material's row). `half_spacing(body, up)` is half
    the body's particle spacing along the upward direction. Collective when `dist` spans
    several ranks (the top is a global maximum); nothing without gravity."""
    mtypes, mparams = materials
    p = particles
    n = p.n_owned
    gravity = np.asarray(gravity, float)
    g = float(np.linalg.norm(gravity))
    if g == 0.0:
        return
    up = -gravity / g
    height = p["x"][:n] @ up
    names = list(case.materials)
    for i, b in enumerate(case.bodies):
        mi = names.index(b.material)
        if b.wall or b.method != method or mtypes[mi] != TAIT_FLUID:
            continue
        mine = (p["body"][:n] == i) & (p["method"][:n] == METHOD_CODES[method])
        top = float(height[mine].max()) if mine.any() else -np.inf
        if dist is not None and dist.size > 1:
            top = dist.max(top)
        if not np.isfinite(top):
            continue
        top += half_spacing(b, up)
        kappa, gamma, rho0 = mparams[mi, 0], mparams[mi, 1], mparams[mi, 2]
        yield mine, tait_hydrostatic_density(rho0, kappa, gamma, g, top - height[mine]), mi


def hydrostatic_mpm(case, particles, materials, gravity, dist=None):
    """MPM fluid (Tait) bodies at rest in the hydrostatic state below their top, as
    `SPHStage.hydrostatic_start` does for SPH ones (`fluid_columns`): J = rho0/rho
    (F = diag(J, 1, 1): the Tait stress depends on J alone), vol = J vol0, sigma = -p I with
    the Tait pressure p = kappa (J^-gamma - 1) (`materials.fluid.tait_pressure`). The top
    is the body's highest point plus half its spacing. Collective when parallel (the top is
    a global maximum)."""
    p = particles
    n = p.n_owned
    dim = len(gravity)
    mparams = materials[1]

    def half_spacing(b, up):
        if b.spacing is not None:
            return 0.5 * float(np.abs(up) @ np.broadcast_to(np.asarray(b.spacing, float), dim))
        return 0.5 * float(np.abs(up) @ (np.asarray(case.grid.cell_size, float) / b.ppc))

    for mine, rho, mi in fluid_columns(case, p, materials, gravity, "mpm", half_spacing,
                                       dist):
        kappa, gamma, rho0 = mparams[mi, 0], mparams[mi, 1], mparams[mi, 2]
        J = rho0 / rho
        rows = np.nonzero(mine)[0]
        D = p.deformation(n)
        if D.ndim == 1:
            D[rows] = J
        else:
            D[rows] = np.eye(3)
            D[rows, 0, 0] = J
        p["vol"][rows] = J * p["vol0"][rows]
        if "rho" in p:
            p["rho"][rows] = rho
        pressure = tait_pressure(J - 1.0, kappa, gamma)
        p["sigma"][rows] = 0.0
        for a in range(3):
            p["sigma"][rows, a, a] = -pressure
