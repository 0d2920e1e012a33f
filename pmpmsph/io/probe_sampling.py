"""What the `[[probes]]` read (config/probes.py, docs/probes.md): each rank's partial sums
over its owned particles, and the values from their global sums.

Every probe fills a slice of one float64 vector per rank (`ProbeSampler.local`); the caller
sums the vectors over the ranks in one collective and hands the sum to `values`. Each sum
is over owned rows only, so every particle counts once whatever the rank count, and the
values agree between rank counts to the round-off of the summation order.

Interpolation (point probes and gauges) is the Shepard-normalised SPH interpolant, for SPH
and MPM particles alike (Shepard 1968; Randles & Libersky 1996, eq. 10):

    f(x) = sum_j f_j V_j W(|x - x_j|, h) / sum_j V_j W(|x - x_j|, h),    V_j = m_j / rho_j

with the Wendland C2 kernel of support 2h (W = a_d / h^d (1 - q/2)^4 (2q + 1), q = r/h, a_2
= 7/(4 pi), a_3 = 21/(16 pi); in 1D (5/8)(1 - q/2)^3 (1 + 3q/2)), whatever the scene's own
kernel: smooth and positive, so the denominator is a fluid (or solid) fraction,
phi(x) = sum_j V_j W, about 1 inside a body and 1/2 on a flat free surface. h: the probe's
`h`, else the scene's SPH smoothing length, else (MPM only) the grid cell size (support two
cells, two to four particle spacings at the usual 1 to 4 particles per cell). Sums over the
wall particles are left out (their pressure is the fluid's, extrapolated).
"""
import math

import numpy as np

from ..codes import SPH
from ..config.probes import STRESS_COMPONENTS, vertical_axis

_STRESS_INDEX = {"xx": (0, 0), "yy": (1, 1), "zz": (2, 2), "xy": (0, 1), "yz": (1, 2),
                 "xz": (0, 2)}
#: float64 entries of one (particles x samples) block of a gauge (memory bound)
_BLOCK = 1 << 21


def wendland(r, h, dim):
    """Wendland C2 kernel of support 2h at distances r (module docstring)."""
    q = np.asarray(r, float) / h
    t = np.clip(1.0 - 0.5 * q, 0.0, None)
    if dim == 1:
        return 0.625 / h * t ** 3 * (1.0 + 1.5 * q)
    a = 7.0 / (4.0 * math.pi) if dim == 2 else 21.0 / (16.0 * math.pi)
    return a / h ** dim * t ** 4 * (2.0 * q + 1.0)


def _probe_h(case, spec):
    if spec.h is not None:
        return spec.h
    if case.sph is not None:
        return case.sph.h
    return min(case.grid.cell_size)


class ProbeSampler:
    """The probes of a case: `local()` (this rank's partial sums), `values(sums, time)` (the
    row of probes.csv from their global sum) and `width` (the vector's length)."""

    def __init__(self, case, particles, prescribed=None):
        self.case = case
        self.dim = case.dim
        self.p = particles
        self.prescribed = prescribed
        if prescribed is not None and any(s.prescribed is not None for s in case.probes):
            prescribed.open_tap()
        walls = {i for i, b in enumerate(case.bodies) if b.wall}
        fluids = {i for i, b in enumerate(case.bodies)
                  if not b.wall and case.materials[b.material].fluid}
        self.gravity = np.array(case.gravity, float)
        self.axis, self.up = vertical_axis(case.gravity, self.dim)
        # periodic axes: distances by the nearest image
        periodic = case.periodic or (case.grid.periodic if case.grid else ())
        self.period = {a: case.domain[1][a] - case.domain[0][a] for a in periodic}
        self.slices, self.bodies, self.hs, self.samples = [], [], [], []
        self.damping = case.sph.damping if case.sph is not None else 0.0
        self._walls_state = {}  # probe index -> (time, momentum) at its last row
        self._tap_elapsed = 0.0  # the time the constraints' impulses of `local` span
        start = 0
        for spec in case.probes:
            h = _probe_h(case, spec) if spec.kind != "force" else 0.0
            chosen = ({case.body_index(spec.body)} if spec.body is not None
                      else fluids if spec.kind == "gauge"
                      else set(range(len(case.bodies))) - walls)
            if spec.kind == "force" and spec.walls:
                chosen = set(range(len(case.bodies))) - walls
            z = None
            if spec.kind == "point":
                width = 1 + len(self._quantities(spec))
            elif spec.kind == "gauge":
                step = spec.step if spec.step is not None else 0.25 * h
                z = np.linspace(spec.bottom, spec.top,
                                int(math.ceil((spec.top - spec.bottom) / step - 1e-9)) + 1)
                width = len(z)
            else:
                width = self.dim + 1 if spec.walls else 3
            self.slices.append(slice(start, start + width))
            self.bodies.append(np.array(sorted(chosen), np.int32))
            self.hs.append(h)
            self.samples.append(z)
            start += width
        self.width = start
        self.columns = ("time", "step") + tuple(c for s in case.probes
                                                for c in s.columns(self.dim))

    # -- this rank's partial sums ------------------------------------------------------------
    def _quantities(self, spec):
        """(column suffix, function of the selected rows) of a point probe, in column order."""
        out = []
        for f in spec.fields:
            if f == "pressure":
                out.append(lambda s: -np.trace(s["sigma"], axis1=1, axis2=2) / 3.0)
            elif f == "density":
                out.append(lambda s: s["rho"])
            elif f == "velocity":
                out += [lambda s, a=a: s["v"][:, a] for a in range(self.dim)]
            else:
                out += [lambda s, ij=_STRESS_INDEX[c]: s["sigma"][:, ij[0], ij[1]]
                        for c in STRESS_COMPONENTS[self.dim]]
        return out

    def _rows(self, rows):
        """{field: values} of `rows` for the interpolation: rho is the SPH density where
        it is the state (updated-Lagrangian SPH rows; vol follows it only at the next
        stress update), else m/V; V = m/rho."""
        p = self.p
        mass = p["mass"][rows]
        rho = mass / p["vol"][rows]
        if "rho" in p:
            sph = p["method"][rows] == SPH
            rho[sph] = p["rho"][rows][sph]
        return {"mass": mass, "rho": rho, "vol": mass / rho, "x": p["x"][rows],
                "v": p["v"][rows], "sigma": p["sigma"][rows]}

    def _offsets(self, x, point, axes):
        """x - point along `axes` (nearest periodic image)."""
        d = x[:, axes] - np.asarray(point, float)
        for k, a in enumerate(axes):
            if a in self.period:
                L = self.period[a]
                d[:, k] -= L * np.round(d[:, k] / L)
        return d

    def local(self):
        """This rank's partial sums of every probe (length `width`)."""
        out = np.zeros(self.width)
        p = self.p
        n = p.n_owned
        tap = None
        if self.prescribed is not None and self.prescribed.tap is not None:
            tap, self._tap_elapsed = self.prescribed.take_tap()  # once for every probe
        for spec, sl, bodies, h, z in zip(self.case.probes, self.slices, self.bodies,
                                          self.hs, self.samples):
            if spec.kind == "force":
                out[sl] = (tap[spec.prescribed] if spec.prescribed is not None
                           else self._walls_local(bodies, n))
                continue
            rows = np.nonzero(np.isin(p["body"][:n], bodies))[0]
            if spec.kind == "point":
                out[sl] = self._point_local(spec, rows, h)
            else:
                out[sl] = self._gauge_local(spec, rows, h, z)
        return out

    def _point_local(self, spec, rows, h):
        """[sum V W, sum f V W for each quantity]."""
        d = self._offsets(self.p["x"][rows], spec.position, list(range(self.dim)))
        r = np.sqrt(np.einsum("ij,ij->i", d, d))
        inside = r < 2.0 * h
        sel = self._rows(rows[inside])
        w = wendland(r[inside], h, self.dim) * sel["vol"]
        return np.concatenate([[w.sum()], [w @ q(sel) for q in self._quantities(spec)]])

    def _gauge_local(self, spec, rows, h, z):
        """phi at the samples z of the line: sum V W."""
        horizontal = [a for a in range(self.dim) if a != self.axis]
        x = self.p["x"][rows]
        dh = self._offsets(x, spec.position, horizontal)
        dh2 = np.einsum("ij,ij->i", dh, dh)
        zj = x[:, self.axis]
        keep = (dh2 < 4.0 * h * h) & (zj > z[0] - 2.0 * h) & (zj < z[-1] + 2.0 * h)
        dh2, zj, vol = dh2[keep], zj[keep], self._rows(rows[keep])["vol"]
        phi = np.zeros(len(z))
        block = max(1, _BLOCK // len(z))
        for i in range(0, len(zj), block):  # (particles x samples) a block at a time
            dz = z[None, :] - zj[i:i + block, None]
            r = np.sqrt(dh2[i:i + block, None] + dz * dz)
            phi += vol[i:i + block] @ wendland(r, h, self.dim)
        return phi

    def _walls_local(self, bodies, n):
        """The momentum and mass of the non-wall particles (dim + 1)."""
        p = self.p
        rows = np.isin(p["body"][:n], bodies)
        mass = p["mass"][:n][rows]
        return np.concatenate([mass @ p["v"][:n][rows], [mass.sum()]])

    # -- the row from the global sums --------------------------------------------------------
    def values(self, sums, time, step):
        """{column: value} of one probes.csv row from the global `sums` of `local()`."""
        row = {"time": time, "step": step}
        for i, (spec, sl) in enumerate(zip(self.case.probes, self.slices)):
            s = sums[sl]
            names = spec.columns(self.dim)
            if spec.kind == "point":
                ok = s[0] >= spec.min_fraction and s[0] > 0.0
                vals = s[1:] / s[0] if ok else np.full(len(names), np.nan)
            elif spec.kind == "gauge":
                vals = [self._elevation(spec, s, self.samples[i])]
            elif spec.prescribed is not None:
                # mean reaction since the last row (physics/loads.py `reaction_row`)
                elapsed = self._tap_elapsed
                vals = s[: self.dim] / elapsed if elapsed > 0.0 else np.full(self.dim, np.nan)
            else:
                vals = self._wall_force(i, s, time)
            row.update(zip(names, (float(v) for v in vals)))
        return row

    def _elevation(self, spec, phi, z):
        """The highest point (along up) of the line where phi >= threshold, linearly
        interpolated to the crossing with the next sample up; nan if phi < threshold all
        along (dry)."""
        wet = np.nonzero(phi >= spec.threshold)[0]
        if len(wet) == 0:
            return math.nan
        k = wet.max() if self.up > 0 else wet.min()
        nxt = k + 1 if self.up > 0 else k - 1
        if nxt < 0 or nxt >= len(z):
            return z[k]
        return z[k] + (phi[k] - spec.threshold) / (phi[k] - phi[nxt]) * (z[nxt] - z[k])

    def _wall_force(self, i, s, time):
        """Force of the particles on the walls, mean since the last row, from the momentum
        balance of the non-wall particles: dP/dt = F_walls->particles + M g - alpha P (the
        pair forces between particles cancel; alpha: `[sph] damping`, trapezoid rule), so
        F_on_walls = M g - (P1 - P0)/(t1 - t0) - alpha (P0 + P1)/2. nan at the first row."""
        P, M = s[: self.dim], s[self.dim]
        last = self._walls_state.get(i)
        self._walls_state[i] = (time, P.copy())
        if last is None or time <= last[0]:
            return np.full(self.dim, np.nan)
        t0, P0 = last
        return (M * self.gravity - (P - P0) / (time - t0)
                - self.damping * 0.5 * (P0 + P))
