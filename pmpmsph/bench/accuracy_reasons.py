"""Why a method does not converge on a scene: the causes found by looking at the runs.

`reason_for` is called by the report for every (scene, method) whose error does not fall
with refinement; a cause is listed here only once it was found (each entry says how);
anything else reports "cause not investigated". The first matching entry wins.
"""
import re

# (study key, regular expression on the method label, cause)
REASONS = [
    ("spring", r"MPM linear", "linear hats: particles crossing into nearly empty cells give "
     "the cell-crossing error, which grows as the cells shrink (cases/spring_1d.toml: "
     "+4.3, +11.8, +27 % at 2x, 4x, 8x)"),
    ("vibrating_bar", r"MPM linear", "linear hats: the free-end particle crossing into an "
     "empty cell sees a nearly massless node (USL inverts it: det F <= 0; USF/MUSL lose the "
     "mode; tests/verification/test_vibrating_bar.py)"),
    ("vibrating_bar", r"SPH UL", "no artificial stress or viscosity (both off, as for the "
     "reversal): after one to one and a half periods the mode's energy (total conserved to "
     "1e-4) moves into particle-scale oscillations, earlier the finer the spacing (h = 2 "
     "spacings, level 8: max |v| 0.19 = 1.9 v0 and |F - 1| 1.3e-2 at t = 15, where the mode "
     "has no strain; level 4 at t ~ 3.5 with h = 1.3): the pairing (tensile) instability, "
     "with the nearest neighbour at q = 1/1.3 > 2/3 where the cubic spline's W'' > 0 "
     "(unstable in tension) or at q = 1/2 for h = 2 (W'' < 0, unstable in compression). "
     "At h = 1.3 spacings 1D waves are also 1.9 % fast whatever the spacing "
     "(tests/verification/test_sph_wave_speed.py). Over one period (--quick) h = 2 spacings "
     "converges at order ~1.8"),
    ("vibrating_bar", r"coupled", "energy is not conserved across the MPM/SPH interface: "
     "E/E0 after one period 1.06, 0.92, 1.10 at levels 1, 2, 4 (default h = 1.3 spacings); "
     "with h = 2 spacings the error is 2e-3 at levels 1-2 but energy grows by 49 % at "
     "level 4; the interface forces of the two discretisations are not equal and opposite "
     "(the same defect as scene 8 at k = 10, tests/verification/test_coupled.py), and the "
     "SPH part carries the instability of the pure SPH runs"),
    ("reversal", r"MPM", "level 1 is pre-asymptotic: sin(10 pi x) has 2 cells per "
     "wavelength there (the grid's Nyquist limit), the grid hardly sees the mode and little "
     "energy is exchanged (K/E0 stays 0.95 over the first 500 steps against 0.86 and 0.74 "
     "at levels 2 and 4, GIMP MUSL), so its small error is not accuracy; from level 2 on the "
     "error falls (GIMP MUSL 4.2e-2 -> 1.1e-2, USL 0.89 -> 0.12 from level 2 to 8). The "
     "energy error is first order in the time step (GIMP MUSL: half the Courant number, half "
     "the error), and USL loses energy monotonically in time (0.85, 0.23, 0.70 of E0 after "
     "the first 500 k steps at levels 1, 2, 4) where MUSL stays within 1 %"),
    ("reversal", r"SPH UL verlet", "the energy error is the time integrator's, set by the "
     "Courant number at the coarse levels: halving it divides the error by 4.0 (1.38e-3 "
     "-> 3.44e-4), halving the spacing at the fixed Courant number 0.1 hardly does "
     "(1.01e-3). The velocity reversal itself is exact to 1e-12 at every level (aux)"),
    ("reversal", r"SPH UL (rk3|predictor)", "as for Verlet: set by the Courant number, "
     "not the spacing (RK3: halving the Courant number divides it by 8.0, 1.33e-3 -> "
     "1.67e-4); neither scheme is time-reversible, so the reversal error (aux) stays "
     "1e-3 ... 1e-2"),
    ("stress_bar", r"MPM (quadratic|cubic)", "B-splines do not apply the end stress "
     "locally: strain / expected = 0.25 (loaded layer), 1.333, 1.0, 0.889, 1.0, 1.037, 1.0, "
     "0.988 ... from the end, a boundary layer that decays by ~3 per cell and has the same "
     "shape in particle counts at every level, so its maximum beyond two spacings (0.889 "
     "for quadratic) does not fall; at a fixed distance from the ends it does"),
    ("stress_bar", r"gimp", "the error is static (kinetic energy 7e-16, the same at "
     "t = 0.02 and 0.04) and sits at the first particle beyond the excluded end layers "
     "(x0 = 0.978 at level 8): GIMP's application of the end load leaves a boundary error "
     "that doubles per level, 8.7e-6 -> 7.7e-5 (0.008 %); the interior strain is exact to "
     "|eps| = 7.8e-6 at every level"),
    ("stress_bar", r".", "the error is at its floor at every level: the particles reproduce "
     "the uniform strain and what is left is |eps| = 7.8e-6 itself (F - 1 of a linear law "
     "in the large-strain setting differs from sigma/E by O(eps)); 1e-5 is far below "
     "0.1 % at every level"),
    ("two_disks", r"MPM linear", "linear hats: cell-crossing error (the disks travel ~6 "
     "cells at 40 cells), as in scenes 1 and 14; every smoother shape converges here"),
    ("dam_break", r"SPH", "the reference is the experiment: the front runs 4.6, 6.1, 7.6, "
     "8.8 % ahead at dx = 0.05, 0.035, 0.025, 0.0177 (x_front(T = 1.94) = 2.34 ... 2.44 "
     "against 2.24), i.e. refinement converges to a front ahead of the experiment's: the "
     "inviscid, free-slip, instantly released 2D model's error (the experiment's gate and "
     "wall friction slow the surge), which refinement cannot remove"),
    ("dam_break", r"MPM quadratic usl (apic|mls)", "the front self-converges (x_front(T = "
     "1.94) = 2.523, 2.568, 2.600, 2.620 with APIC and 2.494, 2.543, 2.579, 2.603 with MLS "
     "as dx falls from 0.05 to 0.0177: differences 0.045, 0.032, 0.020 and 0.048, 0.037, "
     "0.024, shrinking by ~0.65 a level, so a limit near 2.65), but to the inviscid, "
     "free-slip, instantly released front, which runs ~18 % ahead of the experiment's "
     "(gate and floor friction slow the real surge); the error against the experiment "
     "therefore grows towards that limit"),
    ("dam_break", r"MPM", "as for SPH, and more so: the MPM front is a thin tongue "
     "(y < 0.06) on the free-slip floor, x_front(T = 1.94) = 2.60, 2.63, 2.64, 2.74 as dx "
     "falls (3 / 17 / 34 particles ahead of x = 2.24 at dx = 0.1 / 0.05 / 0.035): FLIP's "
     "noise lets the tongue run on (no self-convergence: differences 0.027, 0.012, 0.100); "
     "PIC converges from behind (1.45 -> 1.81, differences 0.11-0.13), dissipating"),
    ("plate", r"SPH TL uncorrected", "the uncorrected kernel's free-edge instability: "
     "41 x 41 inverts a particle before t = 1.2 (as tests/verification/"
     "test_tlsph_plate.py records for this combination)"),
    ("plate", r"SPH UL", "the tensile instability of updated-Lagrangian SPH (the shear puts "
     "one principal stress in tension; this study runs it without artificial stress): "
     "energy is conserved to 1e-4, but the particle volumes J spread into particle-scale "
     "noise that grows with resolution (0.972 ... 1.012 at 21 x 21, 0.935 ... 1.061 at "
     "41 x 41, t = 1.2). With artificial stress 0.3 (Gray, Monaghan & Swift) the spread at "
     "41 x 41 is 0.981 ... 1.013 and the corner error against the 41 x 41 TL reference falls "
     "monotonically, 4.7 %, 2.7 %, 2.1 % at 11, 21, 41, slowly (order ~0.6: the uncorrected "
     "kernel is truncated at the free corner where the error is taken)"),
    ("plate_fsi", r"TL-SPH plate", "until 2026-11-26 the total-Lagrangian stage rewrote "
     "the MPM water's F and stress at every evaluation and the plate fell through; since "
     "then its plain clamps made it soft by about one smoothing length of span (+17.5, "
     "+8.7, +4.7 % at 2, 4, 8 particles through the thickness with hourglass 0.1); with "
     "mirror clamps and no control +12.7, +6.7, +2.0 % (docs/plate.md)"),
    ("plate_fsi", r"SPH UL plate", "until 2026-11-26 the updated-Lagrangian plate "
     "(Bonet-Lok's gradient, linear-fit hourglass control 2) did not hold a static bending "
     "load at 2 or 4 particles through the thickness (at 4 three times the beam's "
     "deflection, at 2 it folded); since then it runs with Liu's kernel, mirror clamps and "
     "the quadratic-fit control, which leaves bending alone (docs/plate.md)"),
    ("couette", r"SPH UL", "the error is the start-up's (t = 0.1: -1.2, -1.0, -0.9 % of U "
     "in the interior at 20, 40, 80 across; steady 0.04 %): the flow lags because the "
     "Morris operator on a square lattice at a fixed h = 1.3 spacings is short of the "
     "Laplacian by a constant 3.7 % (2.6 % the lattice sum of the Wendland kernel, 1.1 % "
     "the 0.01 h^2 against r -> 0; a direct sum for u = y^2), so the effective viscosity is "
     "0.963 nu at every spacing; at h = 2 spacings without the 0.01 h^2 it is 0.9992 nu. "
     "It converges only with h / spacing growing, or with a renormalised operator"),
]


def reason_for(scene, method, rows):
    """The cause recorded for this scene and method, or the failure of its runs."""
    failed = [r["note"] for r in rows if r["note"]]
    for key, pattern, cause in REASONS:
        if key == scene and re.search(pattern, method):
            return cause + (f" ({failed[0]})" if failed else "")
    if failed:
        return f"a run stopped: {failed[0]}"
    return "cause not investigated"
