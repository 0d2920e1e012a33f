"""Scene 11 (seed 000 §6.2; BENCHMARKS.md scene 11): a 2 x 2 plate (E = 1e6, nu = 0.3,
plane strain) with a central hole of radius a = 0.1 (20 a wide), SPH within r < 3 a of the
hole centre, MPM outside, pulled by s = 300 Pa on its two outer particle layers top and
bottom (cases/coupled_plate_hole.toml), damped to rest. Reference: Kirsch,
sigma_yy(r) = s (1 + a^2/(2 r^2) + 3 a^4/(2 r^4)) on the horizontal mid line.
The stress is the particles' own (sigma of the particle row just above the mid line,
y = 1 + dp/2), not a smoothed estimate: that is what each method computes, and a smoothing
would only flatten the peak at the hole further.

Measured (spacing a/8, h = 1.3 dp, t = 0.3; sigma_yy/s and the error against Kirsch), with
the case as it is (`[sph] correction = true` and `hourglass = 2`):

  r/a     Kirsch   coupled          pure SPH         pure MPM
  1.062   2.622    2.410   -8.0 %   1.694  -10.8 %   2.523  -3.8 %
  1.187   2.110    2.170   +2.9 %   1.529   -0.0 %   2.052  -2.7 %
  1.312   1.796    1.905   +6.1 %   1.345   +3.3 %   1.907  +6.1 %

and before (errors only; "corr.": correction = true without the hourglass control, the case
until now; "plain": neither):

  r/a     coupled corr.  pure SPH corr.  coupled plain  SPH plain  coupled plain + hourglass
  1.062   -19.0 %        -21.0 %         -26.1 %        -28.6 %    -20.4 %
  1.187    +0.8 %         -1.3 %          +9.8 %         +7.1 %     +9.5 %
  1.312    +7.2 %         +5.7 %         +13.1 %        +11.1 %    +11.5 %

All three points of the coupled plate are within the 10 % of BENCHMARKS.md. Coupled and pure
MPM are at rest (kinetic energy 2e-8 J; the coupled plate stays there, 8e-11 J at t = 0.7
with the same stresses: -8.1 / +2.8 / +6.0 %) with the far field at 1.000 s, and the coupled
profile is smooth across the MPM/SPH transition at 3 a (last SPH point 1.11 s at 2.94 a,
first MPM point 1.10 s at 3.06 a). Pure SPH is pulled by a prescribed velocity (see
`_pure_sph`) and reaches a gross stress of 0.73 s on the mid line (0.63 s without the
hourglass control); its errors are against Kirsch scaled by that. The coupled result does
not depend on h or kappa much: h = 1.1 / 1.5 dp: -8.2 / +2.2 / +5.8 % and -8.2 / +3.6 /
+6.5 %; kappa = 1 / 4: -8.9 / +2.3 / +5.9 % and -9.0 / +2.2 / +5.8 % (kappa = 10 is past the
stable time step of CFL 0.3: kernels/sph/hourglass.py).

Why the surface row was 19 % short, and what the hourglass control does. Two parts.
(1) The velocity gradient: applied to the exact Kirsch displacement on this particle set
(`test_kirsch_field_velocity_gradient_at_the_hole_surface`) the plain gradient gives sigma_yy
23 % short at the surface row (the truncated kernel; rows further in within 3 %), the
corrected one 5 % short (a one-sided linear fit of a field that curves steeply there).
(2) The discrete equilibrium, measured statically (`kirsch_static.py` in this folder: the
SPH disc r < 2 a with the exact Kirsch displacement prescribed on the particles beyond,
its strain energy minimised exactly): with the corrected gradient the surface row is then
23 % short (plain 31 %), and the displacement error is an odd-even checkerboard (alternating
in sign from particle to particle, 0.1-0.3 s a/E) with stress errors of -23, -5, +31, -60 % on
the rows at 0.5, 1.5, 2.5, 3.5 dp above the mid line next to the hole: the nodal force is
not exact at the stair-stepped surface, and its error goes into the mode that the corrected
gradient does not see (on a lattice the pair terms of an alternating field cancel). The
hourglass control (kernels/sph/hourglass.py) gives that mode stiffness without touching
homogeneous deformations; in the same static problem (error at 1.06 / 1.19 / 1.31 a):

  corrected gradient                           -23.2 / -4.8 / +1.8 %
  + hourglass, kappa = 1 / 3 / 10 (x E)        -12.7 / -2.1 / +1.5, -9.5 / +0.5 / +2.8,
                                               -10.0 / +0.2 / +2.7 %   (checkerboard gone)
  quadratic (WLS) gradient, exact for the Kirsch field to 1 %:  -24.8 / -5.1 / +2.4 %,
      with the control (kappa = 3 / 10 x E): -9.3 / -8.5 % at the surface row
  seed 004's corrected kernel (kernels/sph/tlsph.py): -17.4 / -0.8 / +0.4 %, with the control
      (kappa = 3 x E): -5.7 / +0.7 / +3.1 %
  h = 1.2 / 1.5 / 2.0 dp, corrected: -22.9 / -22.5 / -20.0 % at the surface row; with the
      control (kappa = 3 x E): -9.7 / -9.4 / -10.2 %

So a more accurate gradient alone does not help (the quadratic one is exact for the field
and its equilibrium is as far off); suppressing the odd-even mode does, and the remaining
8-10 % is the smooth error of the nodal equilibrium at the stepped surface plus the 5 % of
the linear fit. (In the static runs kappa multiplies E; the option multiplies the P-wave
modulus rho c^2 = 1.35 E, so static kappa = 3 is the option's 2.2.) The force of the
updated SPH is already the adjoint of the corrected velocity gradient (`sph_rates`: the
"symmetric corrected" form f_a = sum_b m_a m_b (S_a B_a + S_b B_b) grad_a W_ab), so that
form was not a change to try. The surface row's particle volume does not matter: the
particles within a + dp given 5 % less / more volume move its error by +0.6 / -0.6 %
(static, with and without the control; the lattice cell of the mid-line surface particle
misses only dp/(6 a) = 2 % of the material between it and the hole). Seed 004's
total-Lagrangian SPH does run in the coupling (`[sph] formulation = "total"`, h = 1.4 dp, no
hourglass control): coupled -13.5 / +2.0 / +4.4 %, at rest (6.6e-8 J), 393 s instead of 43 s;
the hourglass control is not implemented for it (the static -5.7 % above suggests it would
help there too).

Plate size: BENCHMARKS.md asks for "at least 8 hole radii wide". At 10 a (the previous
1 x 1 plate) the exact solution of the finite plate is itself well above Kirsch near the
hole: pure MPM gives +5.9 / +5.4 / +14 % at 1.06 / 1.19 / 1.31 a and, at spacing a/16,
+9 to +16 % between 1.09 and 1.41 a (net section 20 % of the width; Kt = 3.13 gross).
At 20 a pure MPM is within -3.8 / -2.7 / +6.1 %, so Kirsch is a fair reference. (The
corrected coupled plate at 10 a: -11.0 / +10.1 / +16.6 %; plain: -18 / +20 / +23 %.)
Finer spacing was not an option: the coupled plate at a/16 (10 a wide) does not settle,
with the plain kernel as with the corrected one (kinetic energy 1.2e-4 J at t = 0.2, the
stress near the hole 30 % low and 20-30 % high at the transition): the case header has it.

Reproduce: `python -m pytest -q -s tests/verification/test_coupled_plate.py` prints the
errors of each column (the pure SPH plate and the plate without the hourglass control are
marked slow; `-m "not slow"` leaves them out); the static figures:
`python tests/verification/kirsch_static.py` (see its docstring). The other "before"
columns: the same runs with `hourglass = 2.0` and/or `correction = true` removed from the
case's [sph] (the "plain" columns are the earlier measurements, not repeated here except
"coupled plain + hourglass"). Run times on one (shared) core: coupled 43 s, pure SPH 140 s,
pure MPM 9 s.
"""
from pathlib import Path

import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph import load_case_file
from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.correction import correction_matrices
from pmpmsph.kernels.sph.rates import sph_rates
from pmpmsph.kernels.sph.views import (pair_lists, pair_rows, rate_options, rate_terms, rates,
                                       smoothing_of)
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.simulation import Simulation

CASE = Path(__file__).resolve().parents[2] / "cases" / "coupled_plate_hole.toml"
A = 0.1
S = 300.0
C = 1.0        # hole centre (C, C)
WIDTH = 2.0
DP = 0.0125    # particle spacing
E, NU = 1.0e6, 0.3
END = 0.3
PURE_SPH = [-0.108, 0.000, 0.033]   # pure SPH errors (module docstring)


def kirsch(r):
    return 1.0 + A * A / (2.0 * r * r) + 1.5 * A ** 4 / r ** 4


def kirsch_displacement(x, y):
    """Kirsch's plane-strain displacement (infinite plate, tension S along y)."""
    mu = E / (2.0 * (1.0 + NU))
    kap = 3.0 - 4.0 * NU
    # polar coordinates about the load axis: e1' = e_y, e2' = -e_x
    x1, x2 = y - C, -(x - C)
    r = np.hypot(x1, x2)
    th = np.arctan2(x2, x1)
    c2, s2 = np.cos(2.0 * th), np.sin(2.0 * th)
    ur = S / (4.0 * mu) * (r * ((kap - 1.0) / 2.0 + c2) + A * A / r * (1.0 + (1.0 + kap) * c2)
                           - A ** 4 / r ** 3 * c2)
    ut = S / (4.0 * mu) * ((1.0 - kap) * A * A / r - r - A ** 4 / r ** 3) * s2
    u1 = ur * np.cos(th) - ut * np.sin(th)
    u2 = ur * np.sin(th) + ut * np.cos(th)
    return np.stack([-u2, u1], axis=1)


def _cut(text, head):
    """The case text without its table `head` ("[sph]", "[[regions]]", ...), sub-tables
    included."""
    i = text.index("\n" + head + "\n")
    name = head.strip("[]")
    j = i + len(head) + 2
    while True:
        k = text.find("\n[", j)
        if k < 0:
            return text[:i] + "\n"
        if not text[k + 1:].lstrip("[").startswith(name + "."):
            return text[:i] + text[k:]
        j = k + 2


def _pure_mpm(tmp_path):
    """The case without its SPH region and [sph] section: every particle MPM."""
    text = _cut(_cut(CASE.read_text(), "[sph]"), "[[regions]]")
    path = tmp_path / "plate_mpm.toml"
    path.write_text(text)
    return path


def _pure_sph(tmp_path):
    """Every particle SPH (corrected kernel as in the case). SPH particles take no
    traction: the two outer layers are pulled apart at a constant speed V = 9.1e-4 m/s (the
    plane-strain uniaxial strain s (1 - nu^2)/E reached at t = 0.3), x free. (A pull that
    stops and then holds needs two prescriptions on one particle, which the loader does not
    combine: the last one selecting a particle wins.) The errors are taken against the
    gross stress of the mid-line row, sum(sigma_yy) dp / width, which this slow pull makes
    ~s."""
    text = CASE.read_text()
    for head in ("[grid]", "[mpm]", "[[regions]]", "[[loads]]", "[[loads]]"):
        text = _cut(text, head)
    text = text.replace('method = "mpm"', 'method = "sph"')
    speed = S * (1.0 - NU * NU) / E * WIDTH / 2.0 / END
    text += f"\n[domain]\nmin = [-0.1, -0.1]\nmax = [{WIDTH + 0.1}, {WIDTH + 0.1}]\n"
    for lo, hi, sign in ((WIDTH - 2 * DP, WIDTH, 1.0), (0.0, 2 * DP, -1.0)):
        text += (f'\n[[prescribed]]\nbody = "plate"\n'
                 f'box = {{ min = [0.0, {lo}], max = [{WIDTH}, {hi}] }}\n'
                 f'velocity = ["free", {sign * speed}]\n')
    path = tmp_path / "plate_sph.toml"
    path.write_text(text)
    return path


def _run(path, overrides=()):
    case = load_case_file(path, overrides=[("time.end", END)] + list(overrides))
    sim = Simulation(case, dist=Distributor(MPI.COMM_SELF))
    sim.run()
    p = sim.particles
    x, syy = p["x"], p["sigma"][:, 1, 1]
    # the particle row y = C + dp/2 right of the hole
    line = (np.abs(x[:, 1] - C - 0.5 * DP) < 0.25 * DP) & (x[:, 0] > C)
    r = x[line, 0] - C
    order = np.argsort(r)
    far = syy[np.abs(x[:, 1] - 1.5) < 0.007].mean() / S   # two full rows: their mean is s
    # the gross stress of the mid-line row (its force over the width)
    row = np.abs(x[:, 1] - C - 0.5 * DP) < 0.25 * DP
    gross = syy[row].sum() * DP / WIDTH / S
    return sim, r[order], syy[line][order] / S, p["method"][line][order], far, gross


def _near_errors(label, r, syy, scale=1.0):
    near = r < 1.35 * A
    err = syy[near] / scale / kirsch(r[near]) - 1.0
    print(label, "r/a", (r[near] / A).round(3), "sigma_yy/s", syy[near].round(3),
          "error", err.round(3))
    return err


def test_kirsch_field_velocity_gradient_at_the_hole_surface():
    """The cause, measured without a run: the SPH velocity gradient applied to the exact
    Kirsch displacement on the case's particles, as plane-strain sigma_yy/s on the mid line
    against Kirsch at the particle. Plain kernel: the surface row 23 % short (the kernel cut
    by the free surface), the next rows within 3 %; corrected: 5 % short, then within 1.5 %."""

    case = load_case_file(CASE)
    sim = Simulation(case, dist=Distributor(MPI.COMM_SELF))
    p = sim.particles
    n = p.n_owned
    x = np.ascontiguousarray(p["x"][:n])
    keep = np.hypot(x[:, 0] - C, x[:, 1] - C) < 0.3     # the SPH disc and its neighbours
    x = np.ascontiguousarray(x[keep])
    n = len(x)
    mass = p["mass"][: p.n_owned][keep].copy()
    rho = mass / p["vol"][: p.n_owned][keep]
    u = kirsch_displacement(x[:, 0], x[:, 1])
    h = case.sph.h
    start, index = neighbour_lists(x, n, 2.0 * h, half=True)
    method = np.ones(n, np.int8)
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    line = np.nonzero((np.abs(x[:, 1] - C - 0.5 * DP) < 0.25 * DP) & (x[:, 0] > C)
                      & (x[:, 0] < C + 0.15))[0]
    line = line[np.argsort(x[line, 0])]
    out = {}
    for corr in (False, True):
        B = np.zeros((n, 3, 3))
        if corr:
            correction_matrices((0, 0), (0,), h, n, x, mass, rho, method, start, index,
                                np.zeros((n, 3, 3)), B)
        L = np.zeros((n, 3, 3))
        sph_rates(smoothing_of((0, 0), (0,), h), pair_lists(n, start, index),
                  pair_rows(x, u, u, mass, rho, np.zeros((n, 6)), np.ones(n), method,
                           np.zeros(n, np.int32)),
                  rate_options((0,) if corr else (), np.zeros(1, np.bool_), np.zeros(3),
                              damping=0.0, av_alpha=0.0, av_beta=0.0, want_force=False,
                              want_L=True, want_fsi=False, split=False),
                  rate_terms(B=B), rates(np.zeros((n, 2)), np.zeros(n), L))
        e = 0.5 * (L + np.transpose(L, (0, 2, 1)))
        syy = lam * (e[:, 0, 0] + e[:, 1, 1]) + 2 * mu * e[:, 1, 1]
        xl, yl = x[line, 0] - C, x[line, 1] - C
        exact = kirsch_exact_syy(xl, yl)
        out[corr] = syy[line] / S / exact - 1.0
        print("corrected" if corr else "plain", "r/a", (xl / A).round(3), "error",
              out[corr].round(3))
    assert out[False][0] == pytest.approx(-0.23, abs=0.01)
    assert np.all(np.abs(out[False][1:4]) < 0.03)
    assert out[True][0] == pytest.approx(-0.05, abs=0.01)
    assert np.all(np.abs(out[True][1:4]) < 0.015)


def kirsch_exact_syy(dx, dy):
    """sigma_yy/s of Kirsch at (dx, dy) from the hole centre (any angle)."""
    x1, x2 = dy, -dx
    r = np.hypot(x1, x2)
    th = np.arctan2(x2, x1)
    q2, q4 = A * A / (r * r), A ** 4 / r ** 4
    c2, s2 = np.cos(2 * th), np.sin(2 * th)
    srr = 0.5 * (1 - q2) + 0.5 * (1 - 4 * q2 + 3 * q4) * c2
    stt = 0.5 * (1 + q2) - 0.5 * (1 + 3 * q4) * c2
    srt = -0.5 * (1 + 2 * q2 - 3 * q4) * s2
    ct, st = np.cos(th), np.sin(th)
    return srr * ct * ct + stt * st * st - 2 * srt * ct * st


def test_scene11_coupled_plate_settles_smoothly_across_the_transition():
    sim, r, syy, meth, far, _ = _run(CASE)
    assert sim.diagnostics()["kinetic"] < 1e-7          # at rest (stable)
    assert abs(far - 1.0) < 0.01                         # the far field carries s
    assert set(meth) == {0, 1}
    jump = np.nonzero(np.diff(meth))[0][0]               # last SPH -> first MPM point
    step = syy[jump] - syy[jump + 1]
    assert abs(step - (kirsch(r[jump]) - kirsch(r[jump + 1]))) < 0.02
    err = _near_errors("coupled", r, syy)
    assert len(err) == 3
    # 1.06 a (the particle row on the hole's surface), 1.19 a and 1.31 a: within the 10 %
    # of scene 11
    assert np.all(np.abs(err) < 0.10)
    # pinned, so that a change shows
    assert np.all(np.abs(err - np.array([-0.080, 0.029, 0.061])) < 0.01)


@pytest.mark.slow
def test_scene11_coupled_plate_without_the_hourglass_control():
    """The case as it was (`[sph] hourglass = 0`): the surface row 19 % short, the odd-even
    mode of the corrected SPH solid (module docstring)."""
    sim, r, syy, _, far, _ = _run(CASE, [("sph.hourglass", 0.0)])
    assert sim.diagnostics()["kinetic"] < 1e-7
    assert abs(far - 1.0) < 0.01
    err = _near_errors("coupled, no hourglass control", r, syy)
    assert np.all(np.abs(err - np.array([-0.190, 0.008, 0.072])) < 0.01)


def test_scene11_pure_mpm_within_10_percent_of_kirsch_near_the_hole(tmp_path):
    sim, r, syy, meth, far, _ = _run(_pure_mpm(tmp_path))
    assert set(meth) == {0}
    assert sim.diagnostics()["kinetic"] < 1e-7
    assert abs(far - 1.0) < 0.01
    err = _near_errors("MPM", r, syy)
    assert len(err) == 3 and np.all(np.abs(err) < 0.10)
    assert np.all(np.abs(err - np.array([-0.038, -0.027, 0.061])) < 0.01)


@pytest.mark.slow
def test_scene11_pure_sph_plate(tmp_path):
    _, r, syy, meth, far, gross = _run(_pure_sph(tmp_path))
    assert set(meth) == {1}
    print("pure SPH: gross stress of the mid-line row", gross, "far rows", far)
    assert 0.5 < gross < 1.0   # measured 0.725 (see `_pure_sph`)
    err = _near_errors("SPH", r, syy, scale=gross)
    assert len(err) == 3
    assert np.all(np.abs(err - np.array(PURE_SPH)) < 0.01)

