"""Scenes 12 and 13 (BENCHMARKS.md): seed 004's square plate in simple shear, corrected-kernel
SPH (pmpmsph.kernels.sph.tlsph) advanced by the serial driver `tlsph_driver` (TVD-RK3).

Main runs: the seed's combination -- kernel corrected in the current configuration for the
force (eq. 5), F by eq. 8 with the reference-configuration correction -- with k_h = 1.4.
Measured (this build, CFL 0.3; drift = max_t |E - E0| / E0 over 1.2 s; corner = top-right
displacement at t = 1.2):

  n      corrected   uncorrected   corner (u1, u2)
  11     1.9e-4      9.2e-2        (0.67100, -0.27922)
  21     5.3e-5      5.6e-2        (0.67019, -0.28233)
  41     1.7e-5      blows up      (0.66987, -0.28322)
  max_t |u_11 - u_21| = 0.0044, |u_21 - u_41| = 0.0016

That combination is not energy-consistent (the force is the adjoint of eq. 6 in the current
configuration, not of eq. 8), and an edge mode grows exponentially: with k_h = 1.2 the 41 x 41
run blows up at t ~ 1.0 s (k_h = 1.0 at 21 x 21 too), at 81 x 81 also k_h = 1.3 and 1.4 blow up
before 1.2 s, and 41 x 41 with k_h = 1.4 does at t ~ 2.3 s; the time step does not matter
(CFL 0.3 and 0.15 alike). Hence k_h = 1.4 here, and the two energy-consistent variants are
tested as well: the total-Lagrangian force with eq. 8 (drift 6e-5 / 1.4e-5 / 3.3e-6 at
11 / 21 / 41 with k_h = 1.2, 7.7e-7 at 81 x 81, stable to t = 4 s) and eq. 9 with the
current-configuration force (k_h = 1.4: drift 8.1e-5 / 2.0e-5 / 4.8e-6 at 11 / 21 / 41; corner
path within 1.2e-3 / 3.8e-4 / 7.3e-5 of eq. 8; with k_h = 1.2 at 81 x 81 it stays bounded in
energy, drift 1.9e-4, but the corner path departs by ~0.02 from t ~ 0.8 s).

Scene 13 (Maxwell, 21 x 21, T = 1.5 s): dissipated energy E0 - E(T) = 0.0343 (eta = 1),
0.0436 (1/5), 0.0223 (1/25) of E0 = 0.3204 -- identical to 3 digits at 41 x 41, CFL 0.1 and
with the total-Lagrangian force. It is *not* monotone in eta: as eta -> 0 the body becomes an
inviscid fluid, and simple shear is an exact stress-free motion of a free body of such a
fluid, so the dissipation 2 eta |D|^2 V T vanishes (eta = 1e-3: 9.0e-4 against
2 eta |D|^2 V T = 9.6e-4, D12 = 0.4). The benchmark's "growing as eta falls" holds from
eta = 1 to 1/5 at all times and for all three etas only early (t = 0.1 s: 3e-4, 1.0e-3,
1.2e-3); the tests assert that and the physical limits.
"""
import functools
import itertools

import numpy as np
import pytest

from tlsph_driver import curve_at, drift, run_plate

T12, T13 = 1.2, 1.5
TT12 = np.linspace(0.0, T12, 241)
TT13 = np.linspace(0.0, T13, 301)


@functools.cache
def run(T, **kw):
    return run_plate(T, **kw)


def cached(T, **kw):
    return run(T, **dict(sorted(kw.items())))


@pytest.mark.parametrize("n", [11, 21])
def test_scene12_energy_corrected_vs_uncorrected(n):
    """Total energy (eq. 7) over 1.2 s: drift below 1 % with the corrected kernel and far
    below that of the plain kernel (seed 004, Figure 3 at 11 x 11)."""
    corr = cached(T12, n=n)
    plain = cached(T12, n=n, corrected=False)
    assert corr["t"][-1] == pytest.approx(T12)
    assert corr["n_degenerate"] == 0
    d_corr, _ = drift(corr)
    d_plain, _ = drift(plain)
    assert d_corr < 1e-3  # target 1 %; measured 1.9e-4 (11), 5.3e-5 (21)
    assert d_plain > 20 * d_corr  # measured 9.2e-2 (11), 5.6e-2 (21)
    E0 = corr["E"][0]
    assert E0 == pytest.approx(0.5 * 3.0 * 0.64 / 3.0, rel=0.01)  # int rho/2 (0.8 y)^2


def test_scene12_corner_displacement_converges():
    """Top-right corner path for 11, 21, 41 particles per side: the differences shrink."""
    c = {n: curve_at(cached(T12, n=n), TT12) for n in (11, 21, 41)}
    d1 = np.abs(c[11] - c[21]).max()
    d2 = np.abs(c[21] - c[41]).max()
    assert d2 < 0.5 * d1  # measured 0.0044 -> 0.0016
    assert drift(cached(T12, n=41))[0] < 1e-3  # measured 1.7e-5
    # the plate swings about a rigid rotation: at 1.2 s the corner has moved by ~(0.67, -0.28)
    assert c[41][-1] == pytest.approx([0.670, -0.283], abs=0.003)


def test_total_lagrangian_force_is_conservative_and_converges():
    """Eq. 8 with its adjoint force (reference kernel, first Piola-Kirchhoff stress): energy
    conserved to the time-integration error, stable at k_h = 1.2 where the seed's mix of
    configurations is not, converging to the same corner path."""
    c = {}
    for n in (11, 21, 41):
        h = cached(T12, n=n, k_h=1.2, force="reference")
        assert drift(h)[0] < 1e-4  # measured 6.1e-5, 1.4e-5, 3.3e-6
        c[n] = curve_at(h, TT12)
    d1 = np.abs(c[11] - c[21]).max()
    d2 = np.abs(c[21] - c[41]).max()
    assert d2 < 0.5 * d1  # measured 0.0040 -> 0.0010
    seed = curve_at(cached(T12, n=41), TT12)
    assert np.abs(c[41] - seed).max() < 2e-3


def test_total_lagrangian_force_long_run_stable():
    """41 x 41, k_h = 1.2, three times the scene's duration: no growing mode (the seed's
    current-configuration force blows up here before t = 1.2 s)."""
    h = cached(3.6, n=41, k_h=1.2, force="reference")
    assert h["t"][-1] == pytest.approx(3.6)
    assert drift(h)[0] < 1e-4


def test_scene12_eq9_against_eq8():
    """F by eq. 9 (exp(dt L) F, current-configuration L of eq. 6) instead of eq. 8: with the
    force of eq. 5 the pair is exactly energy-consistent, and the corner path agrees."""
    h9 = cached(T12, n=21, f_mode="exp")
    h8 = cached(T12, n=21)
    assert drift(h9)[0] < 1e-4  # measured 2.0e-5 (third order in dt)
    diff = np.abs(curve_at(h9, TT12) - curve_at(h8, TT12)).max()
    assert diff < 1e-3  # measured 3.8e-4


def test_scene12_eq9_time_convergence():
    """The exponential RK3 of eq. 9 is third order: halving CFL cuts the drift ~8x
    (measured 8.1e-5 -> 1.1e-5 at 11 x 11)."""
    a = drift(cached(T12, n=11, f_mode="exp"))[0]
    b = drift(cached(T12, n=11, f_mode="exp", cfl=0.15))[0]
    assert b < a / 5


ETAS = (1.0, 0.2, 0.04)


def dissipation(h):
    return h["E"][0] - h["E"]


def test_scene13_dissipation_positive():
    """Maxwell (eqs. 13-17): E0 - E(t) >= 0 and non-decreasing for every eta."""
    for eta in ETAS:
        h = cached(T13, n=21, eta=eta)
        assert h["t"][-1] == pytest.approx(T13)
        D = dissipation(h)
        E0 = h["E"][0]
        assert D.min() > -1e-4 * E0
        assert np.diff(D).min() > -1e-4 * E0
        assert D[-1] > 0.05 * E0


def test_scene13_dissipation_against_eta():
    """Growing as eta falls from 1 to 1/5 (and for all three early on); towards the inviscid
    limit (eta -> 0) it falls again: 2 eta |D|^2 V T for a shear flow that stays simple."""
    runs = {eta: cached(T13, n=21, eta=eta) for eta in ETAS + (1e-3,)}
    D_end = {eta: dissipation(h)[-1] for eta, h in runs.items()}
    assert D_end[1.0] < D_end[0.2]  # measured 0.0343 < 0.0436
    early = [np.interp(0.1, runs[eta]["t"], dissipation(runs[eta])) for eta in ETAS]
    assert early[0] < early[1] < early[2]  # 3e-4, 1.0e-3, 1.2e-3
    assert D_end[0.04] < D_end[0.2]  # measured 0.0223 (non-monotone, see module doc)
    assert D_end[1e-3] == pytest.approx(2 * 1e-3 * 2 * 0.4 ** 2 * 1.0 * T13, rel=0.1)


def test_scene13_limits_of_eta():
    """Large eta: the hyperelastic run of scene 12 (closest corner path, converging as eta
    grows); small eta: simple-shear-like flow, corner u1 -> 0.8 * 1 * T = 1.2."""
    hyper = curve_at(cached(T13, n=21), TT13)
    dev = []
    u1 = []
    for eta in (1e3,) + ETAS + (1e-3,):
        h = cached(T13, n=21, eta=eta)
        dev.append(np.abs(curve_at(h, TT13) - hyper).max())
        u1.append(h["u"][-1][0])
    assert dev[0] < 1e-3
    assert all(a < b for a, b in itertools.pairwise(dev))  # 1e-4, 0.081, 0.206, 0.320, ...
    assert all(a < b for a, b in itertools.pairwise(u1))  # 0.767, 0.848, 0.973, 1.087, 1.187
    assert u1[-1] == pytest.approx(1.2, rel=0.02)
