"""Multi-velocity-field frictional contact on the grid (Bardenhagen et al. 2000/2001).

Each body has its own nodal velocity field. At a node where two or more fields have mass,
the centre-of-mass velocity v_cm = sum m_b v_b / sum m_b is the no-slip answer; a field that
approaches it along its outward normal n_b ((v_b - v_cm).n_b > 0) gets its normal relative
velocity removed and its tangential relative velocity reduced by Coulomb friction
mu (v_b - v_cm).n_b; separating fields move freely. Normals come from the mass gradients:
n_b = -grad m_b / |grad m_b|; with exactly two fields a shared normal (n_1 = -n_2) keeps the
correction momentum-conserving. The FLIP increments dv change by the same amounts.
"""
import numpy as np

from ...jit import njit


@njit
def multi_field_contact(dim, gmass, gmgrad, gmx, gvel, gdv, mu, mass_cutoff, gap):
    nf, nn = gmass.shape
    nb = np.zeros(3)
    vcm = np.zeros(3)
    for i in range(nn):
        count = 0
        mtot = 0.0
        for f in range(nf):
            if gmass[f, i] > mass_cutoff:
                count += 1
                mtot += gmass[f, i]
        if count < 2:
            continue
        for a in range(dim):
            s = 0.0
            for f in range(nf):
                if gmass[f, i] > mass_cutoff:
                    s += gmass[f, i] * gvel[f, i, a]
            vcm[a] = s / mtot
        first = -1
        second = -1
        for f in range(nf):
            if gmass[f, i] > mass_cutoff:
                if first < 0:
                    first = f
                elif second < 0:
                    second = f
        for f in range(nf):
            if gmass[f, i] <= mass_cutoff:
                continue
            # outward normal of field f
            norm2 = 0.0
            for a in range(dim):
                if count == 2:
                    other = second if f == first else first
                    nb[a] = gmgrad[f, i, a] - gmgrad[other, i, a]
                else:
                    nb[a] = gmgrad[f, i, a]
                norm2 += nb[a] * nb[a]
            if norm2 <= 0.0:
                continue
            inv = 1.0 / np.sqrt(norm2)
            dvn = 0.0
            for a in range(dim):
                nb[a] *= inv
                dvn += (gvel[f, i, a] - vcm[a]) * nb[a]
            if dvn <= 0.0:
                continue
            if count == 2:
                other = second if f == first else first
                sep = 0.0
                for a in range(dim):
                    sep += (gmx[other, i, a] / gmass[other, i] - gmx[f, i, a] / gmass[f, i]) * nb[a]
                if sep > gap:
                    continue
            # tangential relative velocity after removing the normal part
            vt2 = 0.0
            for a in range(dim):
                t = gvel[f, i, a] - vcm[a] - dvn * nb[a]
                vt2 += t * t
            vt = np.sqrt(vt2)
            slip = 0.0
            if vt > 0.0:
                slip = min(mu * dvn, vt) / vt
            for a in range(dim):
                t = gvel[f, i, a] - vcm[a] - dvn * nb[a]
                corr = -dvn * nb[a] - slip * t
                gvel[f, i, a] += corr
                gdv[f, i, a] += corr


def touching_separation(weight, dx, support):
    """Separation of the two nodal centres of mass when two uniform half-spaces touch at a node.

    `weight(r)` is the 1-D shape function of the node at distance r (cell units) and `support`
    its half-width; each side's centre is the N-weighted mean of |r| over that side.
    """
    r = np.linspace(0.0, support, 4001)
    w = np.array([weight(ri) for ri in r])
    mean = np.trapezoid(r * w, r) / np.trapezoid(w, r)
    return 2.0 * mean * dx
