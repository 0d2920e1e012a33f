"""Contact walls: dummy wall bodies that declare a Coulomb coefficient (`[[bodies]]
friction`, 0 for a smooth wall) hold the SPH solids on them by a unilateral penalty on
each solid row's overlap with the wall's surface, and brake them by Coulomb's law (issue 21,
item 2: the rough walls granular flows need). Part of the SPH kernels (`kernels.sph.rates`).

Why not the plain dummy wall: a solid meets that wall through the pair forces of its mean
pressure and the artificial viscosity of the pairs, along particle-centre lines over a
bumpy lattice, and its kinematics leave the wall out; measured, it brakes a block sliding
down a 30 deg incline like a friction coefficient of about 0.35 and lets a resting block
sink more than a spacing (docs/sph.md, "Walls and solids"). Coupling the solid's
kinematics to the wall instead holds the block, but is bilateral (the wall then pulls too:
it glued an SPH plate to the side walls over its clamps, and a braked block rocked until
the friction took 3.6 times its weight as load); clamped to compression, that kinematic
contact ratcheted a block off a side wall. A penalty on the overlap is a function of the
positions alone (its damping aside): it pushes only, and cannot ratchet. The overlap is measured
to the wall's surface, the union of its particles' lattice cells, not to each wall
particle's plane: a plane per particle needs a normal per particle, and at a wall's corners
and ends those tilt, so a block standing in a corner overlapped them by a tenth of a
spacing at rest and was blown apart (the penalty is as stiff as the solid).
"""
import numpy as np

from ...codes import SPH, WALL
from ...jit import njit

#: the contact's damping, a fraction of the critical damping of a row on its contact spring
CONTACT_DAMPING = 1.0


@njit(inline="always")
def contact_pair(a, b, n_query, method, mat, fluid, wall_mu, body):
    """The SPH solid row of the pair (a, b) when the pair is an SPH solid and a contact wall
    (a wall row of a body with wall_mu >= 0), the solid an owned row (< n_query); else -1.
    The wall row is then a + b minus it. Such pairs take the contact of this module and are
    skipped in `sph_rates`."""
    if method[a] == SPH and method[b] == WALL and not fluid[mat[a]]:
        return a if wall_mu[body[b]] >= 0.0 else -1
    if b < n_query and method[b] == SPH and method[a] == WALL and not fluid[mat[b]]:
        return b if wall_mu[body[a]] >= 0.0 else -1
    return -1


@njit
def _box_gap(dim, x, s, w, half, direction):
    """Distance from row s's centre to the axis-aligned cell of half-width `half` around
    wall row w; the unit direction from the cell's nearest point to s (from the cell's
    centre when s is inside it) into `direction`."""
    dist2 = 0.0
    for d in range(3):
        direction[d] = 0.0
    for d in range(dim):
        e = x[s, d] - x[w, d]
        q = abs(e) - half
        if q > 0.0:
            direction[d] = q if e > 0.0 else -q
            dist2 += q * q
    if dist2 > 0.0:
        dist = np.sqrt(dist2)
        for d in range(dim):
            direction[d] /= dist
        return dist
    size = 0.0
    for d in range(dim):
        direction[d] = x[s, d] - x[w, d]
        size += direction[d] ** 2
    size = np.sqrt(size)
    for d in range(dim):
        direction[d] = direction[d] / size if size > 0.0 else 0.0
    return 0.0


@njit
def wall_gaps(dim, n_query, start, index, x, mass, rho, method, mat, fluid, wall_mu, body,
              gaps):
    """The gap of each owned SPH solid row s to the contact walls (wall rows of bodies with
    wall_mu >= 0): over its wall partners, the nearest of their lattice cells (a square or
    cube of the wall row's own spacing V_w^(1/d) around it), into gaps[s] = (distance,
    unit direction from the nearest point to s (3), the wall row); distance inf and row -1
    without. Over half neighbour lists: a pair is met once, in either row's list."""
    direction = np.zeros(3)
    for s in range(n_query):
        gaps[s, 0] = np.inf
        gaps[s, 4] = -1.0
    for a in range(n_query):
        for k in range(start[a], start[a + 1]):
            b = index[k]
            s = contact_pair(a, b, n_query, method, mat, fluid, wall_mu, body)
            if s < 0:
                continue
            w = a + b - s
            half = 0.5 * (mass[w] / rho[w]) ** (1.0 / dim)
            dist = _box_gap(dim, x, s, w, half, direction)
            if dist < gaps[s, 0]:
                gaps[s, 0] = dist
                for d in range(3):
                    gaps[s, 1 + d] = direction[d]
                gaps[s, 4] = w


@njit
def wall_contact(dim_tag, n, gaps, v, mass, rho, cs, wall_mu, body, clamped, dt, acc):
    """The contact walls' push and Coulomb friction on the owned SPH solid rows, added to
    `acc` after every other force (from `wall_gaps`: the distance g of row s to the
    nearest wall cell, the direction n from it to s, the wall row w).

    Push: a penalty on the overlap delta = Delta_s / 2 - g of s's own cell (side
    Delta_s = V_s^(1/d)) with the wall, along n, with its damping, pushing only:
        f = max(0, k delta - 2 zeta sqrt(k m_s) (v_s - v_w) . n),   k = M_s Delta_s^(d-2),
    M_s = rho_s c_s^2 the solid's P-wave modulus: the contact is as stiff as a layer of the
    solid one spacing thick (a block of height H sinks by rho g H / M_s of a spacing), and
    bounds the step as the solid's own waves do (omega = c_s / Delta_s); zeta =
    CONTACT_DAMPING. Sliding along a flat wall meets no force at all: the cells of a row
    tile its face.
    Friction, for a wall body of Coulomb coefficient mu > 0: the return of the trial
    sliding velocity to the Coulomb cone, as the MPM grid's friction boundary does at a
    node (Bardenhagen et al. 2001, eq. 11, applied to a particle):
        u = (v_s - v_w) + dt acc_s,   u_t = u - (u . n) n,
        acc_s -= min(mu f / m_s, |u_t| / dt) u_t / |u_t|,
    so a row sticks (its tangential velocity brought to the wall's within the step) while
    the force that would move it stays inside mu f, and slides against a friction of mu f
    otherwise. The trial velocity is the one the coming kicks reach (dt acc_s added);
    dt <= 0 (the kernels' warm-up) gives no friction. Rows held by a mirror clamp
    (`clamped`, empty without) take no contact: their clamp holds them, and their forces
    are handed to the free rows they mirror (as `sph_rates` leaves other materials'
    pushes out of them)."""
    dim = len(dim_tag)
    with_clamped = clamped.shape[0] > 0
    u = np.zeros(3)
    for s in range(n):
        w = int(gaps[s, 4])
        if w < 0 or (with_clamped and clamped[s]):
            continue
        spacing = (mass[s] / rho[s]) ** (1.0 / dim)
        overlap = 0.5 * spacing - gaps[s, 0]
        if overlap <= 0.0:
            continue
        vn = 0.0
        for d in range(dim):
            vn += (v[s, d] - v[w, d]) * gaps[s, 1 + d]
        k = rho[s] * cs[s] * cs[s] * spacing ** (dim - 2)
        fn = k * overlap - 2.0 * CONTACT_DAMPING * np.sqrt(k * mass[s]) * vn
        if fn <= 0.0:
            continue
        an = fn / mass[s]
        for d in range(dim):
            acc[s, d] += an * gaps[s, 1 + d]
        mu = wall_mu[body[w]]
        if mu <= 0.0 or dt <= 0.0:
            continue
        un = 0.0
        for d in range(dim):
            u[d] = v[s, d] - v[w, d] + dt * acc[s, d]
            un += u[d] * gaps[s, 1 + d]
        ut2 = 0.0
        for d in range(dim):
            u[d] -= un * gaps[s, 1 + d]
            ut2 += u[d] * u[d]
        if ut2 == 0.0:
            continue
        slip = np.sqrt(ut2)
        scale = min(mu * an, slip / dt) / slip
        for d in range(dim):
            acc[s, d] -= scale * u[d]
