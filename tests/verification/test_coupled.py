"""Coupled MPM-SPH verification (seed 000 §5-6; BENCHMARKS.md scenes 8-10), each beside the
pure-MPM (and, where boundary conditions allow, pure-SPH) run of the same set-up.

Scene 9 — copper bar (cell 0.1, spacing 0.05) compressed by 1 MPa on its end particles
(MPM in [0, 0.2] and [0.8, 1], SPH inside), damped to rest. Expected strain -7.8125e-6.
  Measured: MPM particles exact (1.000 of the expected strain, 0.750 on the loaded end
  particles, which carry the load); SPH with h = 1.3 spacing exact (1.000) at every
  particle; with the seed's h = cell size (2 spacings) the SPH interior takes an odd-even
  (zero-energy) pattern of the cubic spline at q = 0.5 (strains 0.16 ... 2.2 x expected,
  mean 1.20 x expected): the seed's 1 % is NOT met with h = cell size, and is met exactly
  with h = 1.3 spacing. (Artificial viscosity alpha = beta = 1 damps the pattern to
  0.93 ... 1.07.)
  Pure SPH cannot take this load (no stress boundary in SPH: the point of the coupling).
Scene 10 — 1 x 1 plate, MPM rim 0.2 wide, SPH core, 1 MPa on the two outer particle
layers of every side (cases/coupled_biaxial.toml). Measured sigma_xx on the horizontal
centre line: 40 x 40 particles (cell 0.05): -1.000 ... -1.018 MPa (1.8 %), no step at the
MPM/SPH transitions (< 0.3 %); 20 x 20 (the seed's): -1.004 ... -1.032 (3.2 %) — the
loaded layers themselves carry less than 1 MPa, so the interior carries a little more, a
deficit that halves with the layer thickness.
Scene 8 — reversal and energy of v(x, 0) = 0.01 c sin(k pi x + phase), 500 steps, reverse,
500 steps, dt = 0.1 spacing / c, MUSL + GIMP, SPH Verlet without viscosity. Reversal =
max |v + v(x, 0)| / max |v(x, 0)|; energy = max |E/E0 - 1| (kinetic + strain, the
diagnostics) over the run; momentum = max |P - P0| / sum m |v(x, 0)| (phase 0.7: the
phase 0 field is odd about x = 1/2, so P = 0 by symmetry whatever the interface does).
                                        reversal   energy    momentum (phase 0.7)
  k = 10 (the seed's: two cells, four spacings per wavelength)
  pure SPH, h = cell (0.1)              6e-13      2.0e-4    1e-15
  pure SPH, h = 1.3 spacing             5e-13      1.4e-3    1e-15 (test_sph_bar.py: 8e-4)
  pure MPM                              1.1 %      0.48 %    1e-15   (phase 0.7: 1.3 %, 2.1 %)
  coupled, seed interface, h = cell     9.1 %      41 %      11 %    (phase 0.7: 8.9 %, 70 %)
  coupled, seed interface, h = 1.3 sp.  7.0 %      98 %      13 %
  coupled, conservative, h = cell       2.5 %      1.25 %    1e-15   (phase 0.7: 2.1 %, 1.36 %)
  coupled, conservative, h = 1.3 sp.    2.1 %      0.79 %    1e-15   (phase 0.7: 1.2 %, 0.96 %)
  k = 1
  pure MPM                              0.75 %     0.77 %
  coupled, seed interface, h = cell     1.5 %      1.5 %     0.88 %  (asserted within 3 %)
  coupled, conservative, h = cell       0.57 %     0.15 %    1e-15
(Pure MPM was noted at 1.6 % / 2.7 % (k = 10) and 1.6 % / 1.6 % (k = 1) before; the
figures above are re-measured with the code of this commit.)
(Pure MPM at k = 10 is nearly a null test: the nodes sit at the zeros of sin(10 pi x), the
grid sees almost none of the wave, and the strain energy stays below 14 % of the total
where SPH exchanges it fully with the kinetic energy every half period; its particles
carry the wave in FLIP's sub-grid velocities, which is why its energy "holds".)
Cause of the seed interface's drift: its interface forces are not the adjoint of the
strain rates they come from (physics/coupling.py): an SPH particle's L reads its MPM
neighbours through the kernel, but its stress pushes them through the grid (P2G), and an
MPM point's L reads the transition SPH momentum on the grid, but its stress pushes the SPH
particles through the kernel (S_b in the SPH sums). So they are not equal and opposite:
with phase 0.7 the total momentum wanders by 11 % of sum m |v| (k = 10) and 1 % (k = 1),
and not work-conjugate: energy is made. Not the time integration (a common Verlet stage
for both, below, leaves the seed interface at 42-93 %) and not h = cell (h = 1.3 spacing
is worse, 98 %). It shrinks slowly with resolution (k = 10 at spacing 0.025 / 0.0125, the
same physical time: reversal 13.6 / 7.2 %, energy 9.2 / 7.5 %; pure MPM 1.9 / 1.7 %,
4.2 / 3.3 %; conservative interface 1.9 / 1.5 %, 1.3 / 0.96 %).
`[coupling] interface = "conservative"` makes every stress act through the discretisation
of its own strain rate (MPM stresses alone in P2G and given to the transition SPH
particles through the grid; SPH-MPM pairs one-sided, the reaction kicked into the MPM
points; both methods' kicks at the same Verlet stages): momentum to round-off and energy
as in pure MPM, above. NOT a replacement for the seed interface: the two halves of the
interface traction are then different discretisations that do not cancel, a uniform stress
leaves forces on the interface particles (up to 0.08 sigma with h = 1.3 spacing, 0.14 sigma
with h = cell; 0.24 and 0.28 sigma net on each interface: test_interface_patch_test),
and in scene 9 the constant part of them accumulates in FLIP's sub-grid velocities of the
MPM points: at t = 0.02 the kinetic energy is 1342 J (seed interface 4e-9 J) and the
interface MPM points' strains are -4.9 and +6.6 x expected. So: the seed interface (the
default) for loads, the conservative one for wave energy; one interface that is both
consistent and conservative is NOT done.
Variants measured on the way (k = 10, h = cell / 1.3 spacing, phase 0.7): the conservative
interface with the MPM points' reactions sent through the grid (as the fluid-solid `fsi`)
instead of kicked into them: energy 8.8 % / 55 % (the grid cannot carry a two-cell wave, so
the work of those forces is not the work the SPH side counts); without the common Verlet
stages (the MPM step first, then the whole SPH step): 3.5 % / 3.6 %; the seed interface
with the SPH sums reading the MPM points' displacement velocity (x_new - x_old)/dt instead
of their FLIP velocity: 300 % / 85 % (worse).
"""
import sys
from pathlib import Path

import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph import load_case_file
from pmpmsph.parallel.distributor import Distributor
from pmpmsph.simulation import Simulation

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "parallel"))
from scenes import coupled_bar_1d, coupled_stress_bar  # noqa: E402

EXPECTED = -1e6 / 128e9
C = np.sqrt(128e9 / 8790.0)
ROOT = Path(__file__).resolve().parents[2]


def _serial(sc):
    return sc.simulation(dist=Distributor(MPI.COMM_SELF))


def test_scene9_static_strain():
    """h = 1.3 spacing. With the seed's h = cell size (0.1) the SPH region's mean strain is
    1.20 x the expected one (odd-even mode, see the module docstring): not met; measure it
    with `coupled_stress_bar(h=0.1)` (tests/parallel/scenes.py)."""
    sim = _serial(coupled_stress_bar(h=0.065))
    sim.run()
    p = sim.particles
    order = np.argsort(p["x"][:, 0])
    strain = (p["F"][:, 0, 0] - 1.0)[order]
    meth = p["method"][order]
    assert list(meth) == [0] * 4 + [1] * 12 + [0] * 4
    mpm_inner = strain[2:4].tolist() + strain[-4:-2].tolist()
    assert np.all(np.abs(np.array(mpm_inner) / EXPECTED - 1) < 0.01)
    assert np.all(np.abs(strain[4:16] / EXPECTED - 1) < 0.01)  # every SPH particle


def test_scene10_biaxial_stress_in_both_regions():
    sets = [("grid.cell_size", 0.05), ("grid.cells", [32, 32]), ("bodies[0].spacing", 0.025),
            ("loads[0].box.max", [0.05, 1.0]), ("loads[1].box.min", [0.95, 0.0]),
            ("loads[2].box.max", [1.0, 0.05]), ("loads[3].box.min", [0.0, 0.95])]
    case = load_case_file(ROOT / "cases" / "coupled_biaxial.toml", overrides=sets)
    sim = Simulation(case, dist=Distributor(MPI.COMM_SELF))
    sim.run()
    p = sim.particles
    x, s, m = p["x"], p["sigma"] / 1e6, p["method"]
    for axis, comp in ((1, 0), (0, 1)):  # sigma_xx on y = 1/2, sigma_yy on x = 1/2
        line = np.abs(x[:, axis] - 0.4875) < 0.005
        inner = line & (np.abs(x[:, 1 - axis] - 0.5) < 0.45)  # not the loaded layers
        order = np.argsort(x[inner, 1 - axis])
        vals = s[inner, comp, comp][order]
        meth = m[inner][order]
        assert np.all(np.abs(vals + 1.0) < 0.02), vals
        assert set(meth) == {0, 1}
        jumps = np.nonzero(np.diff(meth))[0]
        assert np.all(np.abs(vals[jumps + 1] - vals[jumps]) < 0.02)
    assert sim.diagnostics()["kinetic"] < 1e-5


def test_scene10_pure_mpm_for_comparison():
    """Scene 10 with every particle MPM (the case without its SPH region): the same 40 x 40
    plate and loads. Measured: sigma_xx on y = 1/2 and sigma_yy on x = 1/2 from -1.0006 to
    -1.0168 MPa (1.7 %; the coupled plate: -1.000 ... -1.018). Pure SPH cannot take the load
    (no stress boundary in SPH), as in scene 9."""
    import tomllib

    from pmpmsph.config.load import apply_overrides, case_from_dict

    sets = [("grid.cell_size", 0.05), ("grid.cells", [32, 32]), ("bodies[0].spacing", 0.025),
            ("loads[0].box.max", [0.05, 1.0]), ("loads[1].box.min", [0.95, 0.0]),
            ("loads[2].box.max", [1.0, 0.05]), ("loads[3].box.min", [0.0, 0.95])]
    text = (ROOT / "cases" / "coupled_biaxial.toml").read_text()
    data = tomllib.loads(text)
    del data["regions"], data["sph"]
    sim = Simulation(case_from_dict(apply_overrides(data, sets), name="pure_mpm", text=text),
                     dist=Distributor(MPI.COMM_SELF))
    assert sim.sph is None and sim.coupling.name == "none"
    sim.run()
    p = sim.particles
    x, s = p["x"], p["sigma"] / 1e6
    for axis, comp in ((1, 0), (0, 1)):
        line = np.abs(x[:, axis] - 0.4875) < 0.005
        inner = line & (np.abs(x[:, 1 - axis] - 0.5) < 0.45)
        assert np.all(np.abs(s[inner, comp, comp] + 1.0) < 0.02)
    assert sim.diagnostics()["kinetic"] < 1e-5


def _reversal(mode, k, interface="seed", h=None, phase=0.0):
    """Scene 8: v(x, 0) = 0.01 c sin(k pi x + phase), 500 steps, reverse, 500 steps.
    Returns (max |v + v(x, 0)| / max |v(x, 0)|, max |E/E0 - 1| over the run, max |P - P0|
    over the run / sum m |v(x, 0)|)."""
    sc = coupled_bar_1d(mode, h=h)
    sc.data["mpm"]["transfer"] = "musl"
    if mode == "coupled":
        sc.data["coupling"] = dict(interface=interface)
    sc.data["time"].pop("cfl")
    sc.data["time"]["dt"] = 0.1 * 0.05 / C  # Courant 0.1 on the particle spacing
    sim = _serial(sc)
    p = sim.particles
    x0 = p["x"][:, 0].copy()
    v0 = 0.01 * C * np.sin(k * np.pi * x0 + phase)
    p["v"][:, 0] = v0
    gid0 = p["gid"].copy()
    d0 = sim.diagnostics()
    e0, p0 = d0["total"], d0["px"]
    worst = dp = 0.0
    for leg in range(2):
        for _ in range(500):
            sim.step()
            d = sim.diagnostics()
            worst = max(worst, abs(d["total"] / e0 - 1.0))
            dp = max(dp, abs(d["px"] - (p0 if leg == 0 else -p0)))
        if leg == 0:
            p["v"][:] *= -1.0
            if sim.sph is not None:
                sim.sph.evaluated = False
    order = np.argsort(p["gid"])
    err = np.abs(p["v"][order, 0] + v0[np.argsort(gid0)]).max() / np.abs(v0).max()
    return err, worst, dp / np.sum(p["mass"] * np.abs(v0))


def test_scene8_reversal_smooth_mode_coupled_and_mpm():
    for mode in ("coupled", "mpm"):
        err, drift, _ = _reversal(mode, 1)
        print(mode, err, drift)
        assert err < 0.03 and drift < 0.03


def test_scene8_two_cell_wave_conservative_interface():
    """k = 10 (the seed's): the conservative interface conserves momentum to round-off
    (an asymmetric phase, so that symmetry does not do it) and energy as pure MPM does;
    h = cell size (the seed's) and h = 1.3 spacing. Figures in the module docstring."""
    for h, phase, err_max, drift_max in ((None, 0.0, 0.03, 0.015), (None, 0.7, 0.025, 0.016),
                                          (0.065, 0.0, 0.025, 0.01), (0.065, 0.7, 0.015, 0.011)):
        err, drift, dp = _reversal("coupled", 10, "conservative", h=h, phase=phase)
        print(h, phase, err, drift, dp)
        assert err < err_max and drift < drift_max and dp < 1e-12
    err, drift, _ = _reversal("coupled", 1, "conservative")
    assert err < 0.007 and drift < 0.002
    err, drift, _ = _reversal("mpm", 10)  # the same resolution in pure MPM
    assert err < 0.012 and drift < 0.006


def _interface_forces(interface, h):
    """Forces / |sigma| on the particles of the scene-9 bar (no load, no damping) in a
    uniform uniaxial strain -1e-5, from one step of 1e-10 s (sorted by position)."""
    sc = coupled_stress_bar(h=h)
    sc.data["coupling"] = dict(interface=interface)
    sc.data["mpm"]["damping"] = 0.0
    sc.data["sph"]["damping"] = 0.0
    sc.data["loads"] = []
    sc.data["time"].pop("cfl")
    sc.data["time"]["dt"] = 1e-10
    sim = _serial(sc)
    p = sim.particles
    E, nu, eps = 128e9, 0.3, -1e-5
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    p["F"][:, 0, 0] = 1.0 + eps
    p["vol"][:] = p["vol0"] * (1.0 + eps)
    p["rho"][:] = p["mass"] / p["vol"]
    p["sigma"][:] = 0.0
    p["sigma"][:, 0, 0] = (lam + 2 * mu) * eps
    p["sigma"][:, 1, 1] = p["sigma"][:, 2, 2] = lam * eps
    v0 = p["v"][:, 0].copy()
    sim.step()
    f = p["mass"] * (p["v"][:, 0] - v0) / sim.dt / abs((lam + 2 * mu) * eps)
    return f[np.argsort(p["x"][:, 0])]


def test_interface_patch_test():
    """A uniform stress is an equilibrium of every particle but the free ends' two (which
    carry -0.75 and -0.25 sigma, the load they would need) with the seed's interface (to
    4e-12 sigma). With the conservative one the two particles either side of each interface
    keep forces towards the SPH region: h = 1.3 spacing +0.078, +0.042 (MPM) and +0.042,
    +0.078 (SPH) sigma, 0.24 sigma in all; h = cell: +0.009, +0.143 (MPM), +0.143, +0.009,
    -0.023 (SPH), and the end particle -0.273: asserted as that interface's measured
    limitation (module docstring), so that a change shows."""
    for h, worst in ((0.065, 0.0782), (0.1, 0.1429)):
        f = _interface_forces("seed", h)
        assert np.allclose(f[[0, 1, -2, -1]], [-0.75, -0.25, 0.25, 0.75], atol=1e-6)
        assert np.abs(f[2:-2]).max() < 1e-10
        f = _interface_forces("conservative", h)
        assert np.allclose(f, -f[::-1], atol=1e-10)  # symmetric: no net force on the bar
        assert abs(np.abs(f[2:-2]).max() - worst) < 1e-3


def test_conservative_interface_needs_the_verlet_step():
    from pmpmsph.errors import ConfigError

    sc = coupled_bar_1d(integrator="predictor_corrector")
    sc.data["coupling"] = dict(interface="conservative")
    with pytest.raises(ConfigError, match="coupling.interface"):
        _serial(sc)


def test_handover_relabels_particles_that_cross_into_the_sph_region():
    from scenes import handover_bar

    sim = _serial(handover_bar())
    p = sim.particles
    n = p.n_owned
    x0 = p["x"][:, 0].copy()
    assert np.all(p["method"] == 0)
    m0 = p["mass"].sum()
    sim.run()
    t = sim.time
    assert np.all(p["method"] == 1)          # every particle crossed x = 0.6 and is SPH now
    assert sim.coupling.handed_over == n
    order = np.argsort(p["gid"])
    # a free rigid translation stays one: positions x0 + v t, velocity v, no strain
    assert np.allclose(p["x"][order, 0], x0 + 50.0 * t, rtol=0, atol=1e-9)
    assert np.allclose(p["v"][:, 0], 50.0, rtol=1e-9)
    assert np.allclose(p["F"][:, 0, 0], 1.0, atol=1e-9)
    assert p["mass"].sum() == m0
