"""Column sums of 1D MPM-SPH interface operators (docs/interface.md), with numpy only.

Every particle p reads its strain rate from the velocities as L_p = sum_q G_pq v_q, and the
forces are the adjoint, f_q = -sum_p V_p sigma_p G_pq, which makes the semi-discrete energy
exact. A uniform stress sigma then leaves the force -sigma C_q on particle q, with the
column sum C_q = sum_p V_p G_pq: the patch test asks C_q = 0 away from the free ends.

The bar of scenes 8-9: 20 particles at spacing 0.05 on [0, 1], MPM in [0, 0.2] and
[0.8, 1], SPH between; grid cells 0.1 (GIMP); cubic spline with h = 1.3 spacings or h = cell.
Operators: the grid's (node velocities from the particles in P2G, gradient of the GIMP
weights) and the kernel's (plain symmetric form sum_q V_q (v_q - v_p) W'(x_p - x_q)).

    python scripts/interface_columns.py
"""
import numpy as np

SPACING, CELL, N = 0.05, 0.1, 20
X = SPACING / 2 + SPACING * np.arange(N)
V = np.full(N, SPACING)
NODES = np.arange(-0.2, 1.2 + 1e-9, CELL)
MPM = (X < 0.2) | (X > 0.8)


def gimp(xp, lp=SPACING / 2):
    """GIMP weights S_i(xp) and gradients of every node (1D)."""
    S, dS = np.zeros(len(NODES)), np.zeros(len(NODES))
    for i, xi in enumerate(NODES):
        r = xp - xi
        a, sg = abs(r), np.sign(r)
        if a < lp:
            S[i], dS[i] = 1 - (r * r + lp * lp) / (2 * CELL * lp), -r / (CELL * lp)
        elif a < CELL - lp:
            S[i], dS[i] = 1 - a / CELL, -sg / CELL
        elif a < CELL + lp:
            S[i] = (CELL + lp - a) ** 2 / (4 * CELL * lp)
            dS[i] = -sg * (CELL + lp - a) / (2 * CELL * lp)
    return S, dS


def spline_slope(r, h):
    """dW/dr of the 1D cubic spline at signed distance r."""
    q, c = abs(r) / h, 2.0 / (3.0 * h * h)
    if q < 1:
        return np.sign(r) * c * (-3 * q + 2.25 * q * q)
    if q < 2:
        return np.sign(r) * c * (-0.75 * (2 - q) ** 2)
    return 0.0


def grid_operator(in_p2g):
    S = np.array([gimp(x)[0] for x in X])
    dS = np.array([gimp(x)[1] for x in X])
    w = np.where(in_p2g, V, 0.0)  # mass ~ volume (one density)
    node_mass = S.T @ w
    P = np.divide(S.T * w, node_mass[:, None], out=np.zeros((len(NODES), N)),
                  where=node_mass[:, None] > 0)
    return dS @ P


def kernel_operator(h):
    G = np.zeros((N, N))
    for p in range(N):
        for q in range(N):
            if q != p:
                d = spline_slope(X[p] - X[q], h)
                G[p, q] += V[q] * d
                G[p, p] -= V[q] * d
    return G


def columns(G):
    return V @ G


def zero_modes(G):
    """Dimension of the null space of the stiffness G^T V G (translation is always one)."""
    K = G.T @ np.diag(V) @ G
    return int(np.sum(np.linalg.eigvalsh(K) < 1e-9 * np.abs(K).max()))


def least_change(G, zone, reach):
    """The least-norm correction dG of the rows p in `zone`, on their pairs within `reach`,
    that makes every column of G + dG vanish away from the free ends and every row exact
    for constant and linear fields: sum_q dG_pq = -(G 1)_p, sum_q dG_pq x_q = 1 - (G x)_p,
    sum_p V_p dG_pq = -C_q (docs/interface.md). Returns G + dG and the solve's residual."""
    C = columns(G)
    rows = np.nonzero(zone)[0]
    entries = [(p, q) for p in rows for q in range(N) if abs(X[q] - X[p]) < reach]
    inner = np.arange(2, N - 2)  # the free ends' two particles carry their load
    A = np.zeros((2 * len(rows) + len(inner), len(entries)))
    rhs = np.zeros(A.shape[0])
    for k, (p, q) in enumerate(entries):
        i = np.searchsorted(rows, p)
        A[i, k] = 1.0
        A[len(rows) + i, k] = X[q]
        if 2 <= q < N - 2:
            A[2 * len(rows) + q - 2, k] = V[p]
    rhs[: len(rows)] = -G[rows].sum(axis=1)
    rhs[len(rows): 2 * len(rows)] = 1.0 - G[rows] @ X
    rhs[2 * len(rows):] = -C[inner]
    d, *_ = np.linalg.lstsq(A, rhs, rcond=None)
    dG = np.zeros_like(G)
    for k, (p, q) in enumerate(entries):
        dG[p, q] += d[k]
    return G + dG, np.abs(A @ d - rhs).max()


def reversal(G, k=10, steps=500):
    """Scene 8 on the linear model: E = rho = c = 1, v(x, 0) = 0.01 sin(k pi x), velocity
    Verlet with f = -G^T V sigma, sigma = G u, dt = 0.1 spacing; `steps` forward, reverse,
    `steps` back. Returns (max |E / E0 - 1|, max |v_end + v0| / max |v0|)."""
    m = V
    u = np.zeros(N)
    v0 = 0.01 * np.sin(k * np.pi * X)
    v = v0.copy()
    dt = 0.1 * SPACING

    def acc(u):
        return -(G.T @ (V * (G @ u))) / m

    def energy(u, v):
        return 0.5 * np.sum(m * v * v) + 0.5 * np.sum(V * (G @ u) ** 2)

    e0, worst = energy(u, v), 0.0
    a = acc(u)
    for leg in range(2):
        for _ in range(steps):
            v += 0.5 * dt * a
            u += dt * v
            a = acc(u)
            v += 0.5 * dt * a
            worst = max(worst, abs(energy(u, v) / e0 - 1.0))
        if leg == 0:
            v = -v
    return worst, np.abs(v + v0).max() / np.abs(v0).max()


def main():
    near = np.minimum(np.abs(X - 0.2), np.abs(X - 0.8))
    for h, name in ((0.065, "h = 1.3 spacings"), (0.1, "h = cell")):
        print(f"-- {name}: C_q of the particles 1-10 (0.75 / 0.25 at a free end is its load)")
        Gs = kernel_operator(h)
        print("pure SPH        ", np.round(columns(Gs)[:10], 3))
        print("pure MPM        ", np.round(columns(grid_operator(np.ones(N, bool)))[:10], 3))
        trans = ~MPM & (near < CELL)
        G = np.where(MPM[:, None], grid_operator(MPM | trans), Gs)
        print("conservative    ", np.round(columns(G)[:10], 3))
        for width in (0.1, 0.15, 0.2):  # a blend alpha G_grid + (1 - alpha) G_kernel
            signed = np.where(MPM, -near, near)
            alpha = np.clip(0.5 - signed / width, 0.0, 1.0)
            Gm = grid_operator((alpha > 0) | (near < CELL + width))
            C = columns(alpha[:, None] * Gm + (1 - alpha[:, None]) * Gs)
            print(f"blend over {width:.2f} ", np.round(C[:10], 3),
                  f" max |C| inside {np.abs(C[2:-2]).max():.3f}")
        zone = (near < 2 * CELL) & (X > 0.1) & (X < 0.9)  # off the free ends' particles
        Gc, residual = least_change(G, zone | ~MPM, 2 * h)
        C = columns(Gc)
        print("least change    ", np.round(C[:10], 3),
              f" max |C| inside {np.abs(C[2:-2]).max():.1e} (solve residual {residual:.0e}),"
              f" rows: |G 1| {np.abs(Gc.sum(axis=1)).max():.0e},"
              f" |G x - 1| {np.abs(Gc @ X - 1)[2:-2].max():.2e},"
              f" zero modes {zero_modes(Gc)} (pure SPH {zero_modes(Gs)}, pure MPM "
              f"{zero_modes(grid_operator(np.ones(N, bool)))}, conservative {zero_modes(G)})")
        for label, op in (("conservative", G), ("least change", Gc)):
            drift, back = reversal(op)
            print(f"   k = 10 reversal, {label}: energy {drift:.1e}, velocities back to "
                  f"{back:.0e}")


if __name__ == "__main__":
    main()
