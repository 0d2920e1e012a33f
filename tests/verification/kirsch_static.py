"""Static discrete equilibrium of the SPH disc of scene 11 (test_coupled_plate.py's docstring).

The case's particles within r < R_FREE + 4 h of the hole centre (R_FREE = 2 a); the exact
Kirsch displacement prescribed on r >= R_FREE; the linear small-strain SPH solid's strain
energy sum_a V_a 1/2 eps_a : C : eps_a (plane strain, over the rows whose kernel support
lies inside the set), plus optionally the hourglass energy of kernels/sph/hourglass.py,
minimised over the free rows by a dense solve. The gradient operators are linear:
grad u_a = sum_b (u_b - u_a) (x) c_ab, and the nodal force is their adjoint, as in
`sph_rates`. Prints sigma_yy / Kirsch - 1 on the mid-line rows at 1.06, 1.19, 1.31 a, for the
exact displacement ("exact u": the gradient's own error) and at the equilibrium.

    python tests/verification/kirsch_static.py [plain|bl|rkpm|quad ...]
    env: KAPPA=0,1,3,10 (hourglass factor, times E here), HF=1.3 (h / dp), MAP=1 (print the
    displacement and stress errors around the surface row: the checkerboard)

About 1 minute per variant and kappa (dense 3200 x 3200 solve).
"""
import os
import sys
from pathlib import Path

import numpy as np
from mpi4py import MPI

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_coupled_plate import (
    CASE,
    DP,
    NU,
    A,
    C,
    E,
    S,
    kirsch_displacement,
    kirsch_exact_syy,
)

from pmpmsph import load_case_file
from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.kernel_functions import kernel_dwdr, kernel_w
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.simulation import Simulation

R_FREE = 2.0 * A


def particles(hf):
    sim = Simulation(load_case_file(CASE), dist=Distributor(MPI.COMM_SELF))
    p = sim.particles
    x, vol = np.array(p["x"][: p.n_owned]), np.array(p["vol"][: p.n_owned])
    h = hf * DP
    keep = np.hypot(x[:, 0] - C, x[:, 1] - C) < R_FREE + 4 * h
    return np.ascontiguousarray(x[keep]), vol[keep], h


def pairs(x, h):
    """Full neighbour lists as pair arrays (a, b) (b = a included) and the CSR start."""
    start, index = neighbour_lists(x, len(x), 2.0 * h)
    a = np.repeat(np.arange(len(x)), np.diff(start))
    return a, index, start


def grad_sph(x, vol, h, a, b, corrected):
    """c_ab = V_b grad_a W_ab, with corrected: B_a V_b grad_a W_ab (Bonet-Lok)."""
    xab = x[a] - x[b]
    r = np.linalg.norm(xab, axis=1)
    c = vol[b][:, None] * (np.array([kernel_dwdr(0, 2, q, h) for q in r]) / r)[:, None] * xab
    if corrected:
        M = np.zeros((len(x), 2, 2))
        np.add.at(M, a, -xab[:, :, None] * c[:, None, :])   # sum (x_b - x_a) (x) c_ab
        B = np.linalg.inv(np.transpose(M, (0, 2, 1)))
        c = np.einsum("kij,kj->ki", B[a], c)
    return c


def grad_quadratic(x, vol, h, a, b):
    """Kernel-weighted least squares with the quadratic basis (exact for quadratic u)."""
    d = (x[b] - x[a]) / h
    w = vol[b] * np.array([kernel_w(0, 2, q * h, h) for q in np.linalg.norm(d, axis=1)])
    P = np.stack([d[:, 0], d[:, 1], 0.5 * d[:, 0] ** 2, d[:, 0] * d[:, 1], 0.5 * d[:, 1] ** 2], 1)
    Mq = np.zeros((len(x), 5, 5))
    np.add.at(Mq, a, w[:, None, None] * P[:, :, None] * P[:, None, :])
    coef = np.einsum("kij,kj->ki", np.linalg.pinv(Mq)[a], w[:, None] * P)
    return coef[:, :2] / h


def grad_rkpm(x, vol, h, start, index):
    """Seed 004's corrected kernel (kernels/sph/tlsph.py), its full gradient G_ab:
    grad u_a = sum_b V_b u_b (x) G_ab = sum_b V_b (u_b - u_a) (x) G_ab."""
    from pmpmsph.kernels.sph.tlsph import kernel_correction
    wt, gw = np.zeros(len(index)), np.zeros((len(index), 3))
    kernel_correction(x, vol, start, index, h, 0, 2, True, wt, gw)
    return vol[index][:, None] * gw[:, :2]


def operator(n, a, b, c):
    """Per row: (columns of u, D_a (4, 2k)) with grad u_a (xx, xy, yx, yy) = D_a u[columns]."""
    keep = a != b
    a, b, c = a[keep], b[keep], c[keep]
    st = np.searchsorted(a, np.arange(n + 1))
    rows = []
    for i in range(n):
        nb = np.concatenate([[i], b[st[i]:st[i + 1]]])
        cc = c[st[i]:st[i + 1]]
        D = np.zeros((2, 2, len(nb), 2))
        for k in range(2):
            D[k, :, 1:, k] = cc.T
            D[k, :, 0, k] = -cc.sum(axis=0)
        rows.append((np.stack([2 * nb, 2 * nb + 1], 1).reshape(-1), D.reshape(4, -1)))
    return rows


def elasticity():
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    Cm = np.zeros((4, 4))
    for i, j in np.ndindex(2, 2):
        for k, m in np.ndindex(2, 2):
            Cm[2 * i + j, 2 * k + m] = (lam * (i == j) * (k == m)
                                       + mu * ((i == k) * (j == m) + (i == m) * (j == k)))
    return Cm, lam, mu


def hourglass(x, vol, h, D, inner, kappa):
    """Hessian of kappa E/2 sum_a V_a sum_b V_b phi_ab |u_b - u_a - G_a x_ba|^2,
    phi = -W'(r)/r, G_a = D_a u (the energy of kernels/sph/hourglass.py, small strain)."""
    K = np.zeros((2 * len(x), 2 * len(x)))
    for a in np.nonzero(inner)[0]:
        cols, Da = D[a]
        nb = cols[::2] // 2
        xba = x[nb] - x[a]
        for j in range(1, len(nb)):
            r = np.linalg.norm(xba[j])
            e = np.zeros((2, len(cols)))
            e[0, 2 * j] += 1.0
            e[1, 2 * j + 1] += 1.0
            e[0, 0] -= 1.0
            e[1, 1] -= 1.0
            for i in range(2):
                e[i] -= Da[2 * i] * xba[j, 0] + Da[2 * i + 1] * xba[j, 1]
            w = kappa * E * vol[a] * vol[nb[j]] * -kernel_dwdr(0, 2, r, h) / r
            K[np.ix_(cols, cols)] += w * e.T @ e
    return K


def solve(x, vol, h, D, kappa, label):
    n = len(x)
    r = np.hypot(x[:, 0] - C, x[:, 1] - C)
    inner = r < R_FREE + 2 * h - 1e-9        # rows with their whole support in the set
    free = np.repeat(r < R_FREE, 2)
    Cm, lam, mu = elasticity()
    K = np.zeros((2 * n, 2 * n))
    for i in np.nonzero(inner)[0]:
        cols, Da = D[i]
        K[np.ix_(cols, cols)] += vol[i] * Da.T @ Cm @ Da
    if kappa:
        K += hourglass(x, vol, h, D, inner, kappa)
    ue = kirsch_displacement(x[:, 0], x[:, 1]).reshape(-1)
    u = ue.copy()
    u[free] = np.linalg.solve(K[np.ix_(free, free)], -K[np.ix_(free, ~free)] @ ue[~free])
    line = np.nonzero((np.abs(x[:, 1] - C - 0.5 * DP) < 0.25 * DP) & (x[:, 0] > C)
                      & (x[:, 0] < C + 0.14))[0]
    line = line[np.argsort(x[line, 0])]

    def syy_error(uu):
        G = np.array([Da @ uu[cols] for cols, Da in D]).reshape(n, 2, 2)
        e = 0.5 * (G + G.transpose(0, 2, 1))
        syy = lam * (e[:, 0, 0] + e[:, 1, 1]) + 2 * mu * e[:, 1, 1]
        return syy / S / kirsch_exact_syy(x[:, 0] - C, x[:, 1] - C) - 1.0

    for name, uu in (("exact u", ue), ("equilibrium", u)):
        err = syy_error(uu)
        print(f"{label:22s} {name:12s} r/a", ((x[line, 0] - C) / A).round(3), "error %",
              (100 * err[line]).round(1), flush=True)
    if os.environ.get("MAP"):
        du = (u - ue).reshape(n, 2) / (S * A / E)
        err = syy_error(u)
        sel = (x[:, 0] > C + 0.09) & (x[:, 0] < C + 0.17) & (np.abs(x[:, 1] - C) < 0.05)
        for yv in sorted(set(np.round(x[sel, 1], 6)))[::-1]:
            row = np.nonzero(sel & (np.abs(x[:, 1] - yv) < 1e-6))[0]
            row = row[np.argsort(x[row, 0])]
            x0 = (x[row[0], 0] - C) / A
            print(f"  y - C = {(yv - C) / DP:+4.1f} dp, from x - C = {x0:.3f} a: du_y/(s a/E)",
                  " ".join(f"{v:+.3f}" for v in du[row, 1]),
                  "| sigma_yy error %", " ".join(f"{100 * v:+.0f}" for v in err[row]))


def main():
    hf = float(os.environ.get("HF", "1.3"))
    kappas = [float(k) for k in os.environ.get("KAPPA", "0").split(",")]
    x, vol, h = particles(hf)
    a, b, start = pairs(x, h)
    other = a != b                      # the lists hold the row itself too
    for v in sys.argv[1:] or ["plain", "bl", "rkpm", "quad"]:
        if v == "rkpm":
            D = operator(len(x), a, b, grad_rkpm(x, vol, h, start, b))
        elif v in ("plain", "bl"):
            c = grad_sph(x, vol, h, a[other], b[other], v == "bl")
            D = operator(len(x), a[other], b[other], c)
        else:
            c = grad_quadratic(x, vol, h, a[other], b[other])
            D = operator(len(x), a[other], b[other], c)
        for kappa in kappas:
            solve(x, vol, h, D, kappa, f"{v} h={hf}dp kappa={kappa:g}")


if __name__ == "__main__":
    main()
