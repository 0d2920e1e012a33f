"""F-bar for MPM: the volume change of the plastic materials averaged over the nodes, against
the volumetric locking of low-order MPM in isochoric plastic flow (the excess limit load of a
footing on von Mises soil: bench/accuracy_plastic.py).

After G2P has updated F (and vol = J vol0) without the stress of these particles
(`g2p(stress_later=...)`), the caller scatters w_p = vol0_p and w_p J_p of their rows to the
nodes (an ordinary P2G of "mass" w and "velocity" J, summed over the ranks like every nodal
sum), gathers J_bar_p = sum_I N_Ip (sum_q N_Iq w_q J_q) / (sum_q N_Iq w_q) back
(`kernels.coupling.add_gathered` with the weights as mass), and `fbar_stress` then replaces
    F_p <- (J_bar_p / J_p)^(1/d) F_p   (the d x d in-plane block; d the dimension),
    vol_p = J_bar_p vol0_p,
and computes their stress from the new F. The deviatoric part of F is untouched, its
determinant becomes the smoothed J_bar (de Souza Neto et al. 1996, "Design of simple low
order finite elements for large strain analysis of nearly incompressible solids", IJSS 33,
eq. 12, with the element's centre value replaced by the nodal projection, as Coombs et al.
2018, "Overcoming volumetric locking in material point methods", CMAME 333, do over cells).
The average is per velocity field (per body with multi-field contact), and only the
particles of plastic materials take part: an elastic or rigid body that shares nodes with
them keeps its own J.
"""
import numpy as np

from ...jit import njit
from ...materials.dispatch import compute_stress_tagged


@njit
def fbar_stress(dim, averaged, materials, mat, F, vol, vol0, Jbar, dt, mstate, sigma,
                prestress=None):
    """F-bar and the stress of the rows whose material is `averaged` (module docstring);
    `materials` = (tag, types, parameters) (`material_table`), `Jbar` (n, >=1) column 0
    the gathered average. Returns the first row whose J_bar is not > 0, or -1."""
    mat_tag, mtypes, mparams = materials
    L = np.zeros((3, 3))
    sig = np.zeros((3, 3))
    bad = -1
    for p in range(F.shape[0]):
        mi = mat[p]
        if not averaged[mi]:
            continue
        jbar = Jbar[p, 0]
        if not (jbar > 0.0):
            if bad < 0:
                bad = p
            continue
        ratio = jbar * vol0[p] / vol[p]
        s = ratio if dim == 1 else (np.sqrt(ratio) if dim == 2 else np.cbrt(ratio))
        for a in range(dim):
            for b in range(dim):
                F[p, a, b] *= s
        vol[p] = jbar * vol0[p]
        out = sig if prestress is not None else sigma[p]
        compute_stress_tagged(mat_tag, mtypes[mi], F[p], L, dt, mstate[p], mparams[mi], out)
        if prestress is not None:
            for a in range(3):
                for b in range(3):
                    sigma[p, a, b] = sig[a, b] + prestress[p, a, b]
    return bad
