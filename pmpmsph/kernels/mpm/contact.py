"""Multi-velocity-field frictional contact on the grid (Bardenhagen et al. 2000/2001).

Each body has its own nodal velocity field. At a node where two or more fields have mass,
the centre-of-mass velocity v_cm = sum m_b v_b / sum m_b is the no-slip answer; a field that
approaches it along its outward normal n_b ((v_b - v_cm).n_b > 0) gets its normal relative
velocity removed and its tangential relative velocity reduced by Coulomb friction
mu (v_b - v_cm).n_b; separating fields move freely. Normals come from the mass gradients
(`contact_normals`); with exactly two fields a shared normal (n_1 = -n_2) keeps the
correction momentum-conserving. The FLIP increments dv change by the same amounts.

Two fields that share a node are not necessarily touching: a node sees particles up to its
shape function's support away, so a check on the shared mass alone holds bodies apart by a
fraction of a cell (Bardenhagen's original), and a check on the distance between the fields'
nodal centres of mass (Nairn's "displacement check", used here until 2026-11-26 with a
tunable multiple) depends on where the surfaces lie between the nodes. Here contact is
decided from the particles themselves (`surface_reach`): each field's reach at the node is
the furthest its particles in the node's strip extend along its outward normal (each
particle a square or cube of its own volume), and the fields are in contact where the two
reaches overlap, or will by the end of the step at their approach speed. Measured on floats
in MPM water (docs/floats.md, spacing 0.005): drafts within +0.8 to +3.9 % of Archimedes
where the centre-of-mass check left them -5 to -18 % high; no gap parameter.
"""
import math

import numpy as np

from ...jit import njit
from .shapes import local_layout


@njit(inline="always")
def _fields_at(gmass, i, mass_cutoff):
    """(count, first, second, their total mass) of the fields with mass at node i (first and
    second: the lowest two such fields, -1 if none)."""
    count = 0
    first = -1
    second = -1
    mtot = 0.0
    for f in range(gmass.shape[0]):
        if gmass[f, i] > mass_cutoff:
            count += 1
            mtot += gmass[f, i]
            if first < 0:
                first = f
            elif second < 0:
                second = f
    return count, first, second, mtot


@njit
def contact_normals(dim, gmass, gmgrad, fluid, mass_cutoff, normals, reach):
    """normals[f, i] = the outward unit normal of field f at every node i where two or more
    fields have mass (zero elsewhere), as `multi_field_contact` takes them, and reach[f, i]
    set to -inf there (the start of `surface_reach`'s maxima), NaN at the other nodes. Where
    exactly two meet: n_f = -n_o along grad m_f - grad m_o, or along the solid's own mass
    gradient alone where a fluid field (`fluid[f]`) meets a solid one (the fluid's surface
    is wherever the solid pushes it; averaged with the fluid's, a node beside a block's side
    near its bottom corner took a normal tilted towards the water below and held the block
    up)."""
    nf, nn = gmass.shape
    for i in range(nn):
        for f in range(nf):
            for a in range(dim):
                normals[f, i, a] = 0.0
            reach[f, i] = np.nan
        count, first, second, _ = _fields_at(gmass, i, mass_cutoff)
        if count < 2:
            continue
        for f in range(nf):
            if gmass[f, i] <= mass_cutoff:
                continue
            reach[f, i] = -np.inf
            norm2 = 0.0
            wf = 1.0
            wo = 1.0
            other = second if f == first else first
            if count == 2 and fluid[f] != fluid[other]:
                wf = 0.0 if fluid[f] else 1.0
                wo = 0.0 if fluid[other] else 1.0
            for a in range(dim):
                if count == 2:
                    normals[f, i, a] = wf * gmgrad[f, i, a] - wo * gmgrad[other, i, a]
                else:
                    normals[f, i, a] = gmgrad[f, i, a]
                norm2 += normals[f, i, a] ** 2
            if norm2 > 0.0:
                inv = 1.0 / np.sqrt(norm2)
                for a in range(dim):
                    normals[f, i, a] *= inv


@njit
def surface_reach(dim, x, vol, pfield, lp, origin, offset, inv_dx, strides, support, normals,
                  reach):
    """reach[f, i] = max over the particles p of field f within `support` cells of node i
    per axis (1 + lp_p,a with GIMP's half-widths `lp`; None: `support`) and within half a
    cell of the line through it along n_f(i) of (x_p - x_i).n_f(i) + r_p: how far body f
    reaches along its outward normal at node i, from the node, with r_p = l_p sum_a |n_a|
    the extent of p's square (cube) of half-side l_p = vol_p^(1/dim) / 2 along n. Only the
    nodes `contact_normals` marked (reach not NaN) are touched."""
    st, off, nax = local_layout(dim, strides, offset, normals.shape[1])
    # the particle in scalars (a store to `reach` could alias an array, whose loads would
    # then be redone at every node); axes beyond dim span the one node 0
    X1 = X2 = 0.0
    lo1 = lo2 = 0
    hi1 = hi2 = 1
    for p in range(x.shape[0]):
        f = pfield[p]
        # (pow for the side only in 3D: in 2D a square root, a third of this kernel's time)
        side = vol[p] if dim == 1 else (math.sqrt(vol[p]) if dim == 2
                                        else vol[p] ** (1.0 / 3.0))
        half = 0.5 * side
        X0 = (x[p, 0] - origin[0]) * inv_dx
        s0 = support if lp is None else 1.0 + lp[p, 0]
        lo0 = max(int(np.ceil(X0 - s0)) - off[0], 0)
        hi0 = min(int(np.floor(X0 + s0)) - off[0] + 1, nax[0])
        if dim > 1:
            X1 = (x[p, 1] - origin[1]) * inv_dx
            s1 = support if lp is None else 1.0 + lp[p, 1]
            lo1 = max(int(np.ceil(X1 - s1)) - off[1], 0)
            hi1 = min(int(np.floor(X1 + s1)) - off[1] + 1, nax[1])
        if dim > 2:
            X2 = (x[p, 2] - origin[2]) * inv_dx
            s2 = support if lp is None else 1.0 + lp[p, 2]
            lo2 = max(int(np.ceil(X2 - s2)) - off[2], 0)
            hi2 = min(int(np.floor(X2 + s2)) - off[2] + 1, nax[2])
        for i0 in range(lo0, hi0):
            rel0 = X0 - (i0 + off[0])
            for i1 in range(lo1, hi1):
                rel1 = X1 - (i1 + off[1])
                for i2 in range(lo2, hi2):
                    node = i0 * st[0] + i1 * st[1] + i2 * st[2]
                    if np.isnan(reach[f, node]):  # (not a contact node)
                        continue
                    na = normals[f, node, 0]
                    d = rel0 * na
                    dist2 = rel0 * rel0
                    r = abs(na)
                    if dim > 1:
                        na = normals[f, node, 1]
                        d += rel1 * na
                        dist2 += rel1 * rel1
                        r += abs(na)
                    if dim > 2:
                        rel2 = X2 - (i2 + off[2])
                        na = normals[f, node, 2]
                        d += rel2 * na
                        dist2 += rel2 * rel2
                        r += abs(na)
                    if r == 0.0:
                        continue
                    # only the particles in the node's strip along n, one cell wide (the
                    # strips of neighbouring nodes tile space): a body beside the node's
                    # line, e.g. water beside a block seen from a node under its bottom
                    # edge, is not in front of the node
                    if dist2 - d * d > 0.25:
                        continue
                    d = d / inv_dx + half * r
                    if d > reach[f, node]:
                        reach[f, node] = d


@njit
def multi_field_contact(dim, gmass, normals, reach, gvel, gdv, mu, mass_cutoff, dt):
    """The contact of the module doc at every node where two or more fields have mass, with
    the normals of `contact_normals`; two fields are in contact at a node only where their
    surfaces meet there by the end of the step: the gap -(reach_f + reach_o) between them
    (`surface_reach`) is at most what their approach speed along the normal closes in `dt`
    (a gap checked at the start of the step alone lets fast bodies pass into each other)."""
    nf, nn = gmass.shape
    vcm = np.zeros(3)
    for i in range(nn):
        count, first, second, mtot = _fields_at(gmass, i, mass_cutoff)
        if count < 2:
            continue
        if count == 2:
            closing = 0.0
            for a in range(dim):
                closing += (gvel[first, i, a] - gvel[second, i, a]) * normals[first, i, a]
            if reach[first, i] + reach[second, i] + dt * max(closing, 0.0) < 0.0:
                continue
        for a in range(dim):
            s = 0.0
            for f in range(nf):
                if gmass[f, i] > mass_cutoff:
                    s += gmass[f, i] * gvel[f, i, a]
            vcm[a] = s / mtot
        for f in range(nf):
            if gmass[f, i] <= mass_cutoff:
                continue
            dvn = 0.0
            norm2 = 0.0
            for a in range(dim):
                dvn += (gvel[f, i, a] - vcm[a]) * normals[f, i, a]
                norm2 += normals[f, i, a] ** 2
            if norm2 == 0.0 or dvn <= 0.0:
                continue
            vt2 = 0.0
            for a in range(dim):
                t = gvel[f, i, a] - vcm[a] - dvn * normals[f, i, a]
                vt2 += t * t
            vt = np.sqrt(vt2)
            slip = 0.0
            if vt > 0.0:
                slip = min(mu * dvn, vt) / vt
            for a in range(dim):
                t = gvel[f, i, a] - vcm[a] - dvn * normals[f, i, a]
                corr = -dvn * normals[f, i, a] - slip * t
                gvel[f, i, a] += corr
                gdv[f, i, a] += corr
