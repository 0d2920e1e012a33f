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
    ("vibrating_bar", r"SPH UL .*h=1.3", "at h = 1.3 spacings the lattice sum of the cubic "
     "spline's gradient makes 1D waves 1.9 % fast whatever the spacing "
     "(tests/verification/test_sph_wave_speed.py): a phase error of ~0.1 after a period at "
     "every level; at level 4 the mode's energy (total conserved to 1e-4) also moves into "
     "particle-scale oscillations from t ~ 3.5 (max |v| up to 2.4 v0), as the tensile "
     "instability predicts for a nearest neighbour at q = 1/1.3 > 2/3, where the cubic "
     "spline's W'' > 0; at h = 2 spacings (q = 1/2) the same runs converge"),
    ("vibrating_bar", r"coupled", "energy is not conserved across the MPM/SPH interface: "
     "E/E0 after one period 1.06, 0.92, 1.10 at levels 1, 2, 4 (default h = 1.3 spacings); "
     "with h = 2 spacings the error is 2e-3 at levels 1-2 but energy grows by 49 % at "
     "level 4; the interface forces of the two discretisations are not equal and opposite "
     "(the same defect as scene 8 at k = 10, tests/verification/test_coupled.py)"),
    ("reversal", r"MPM .* usl", "USL loses energy every step (E/E0 after the first 500 k "
     "steps: 0.85, 0.23, 0.70 at levels 1, 2, 4, monotone in time; MUSL with the same "
     "shape stays within 1 %): the scheme's own dissipation, which does not fall with the "
     "step here"),
    ("reversal", r"MPM", "the energy error of explicit MPM is first order in the time step "
     "(MUSL, GIMP: halving the Courant number halves it, 4.8e-3 -> 2.4e-3) and grows with "
     "the highest frequency c / cell in the field, so at the fixed Courant number 0.1 it "
     "grows as the cells shrink (x5.5 from level 1 to 2); refine dt faster than the cell"),
    ("reversal", r"SPH UL verlet", "the energy error is the time integrator's, set by the "
     "Courant number: halving it divides the error by 4.0 (1.38e-3 -> 3.44e-4), halving the "
     "spacing at the fixed Courant number 0.1 does not (1.01e-3): the error sits in "
     "particle-scale modes whose frequency c/h grows as the spacing shrinks. The velocity "
     "reversal itself is exact to 1e-12 at every level (aux column)"),
    ("reversal", r"SPH UL (rk3|predictor)", "as for Verlet: set by the Courant number, "
     "not the spacing (RK3: halving the Courant number divides it by 8.0, 1.33e-3 -> "
     "1.67e-4); neither scheme is time-reversible, so the reversal error (aux) stays "
     "1e-3 ... 1e-2"),
    ("stress_bar", r"MPM (quadratic|cubic)", "B-splines do not apply the end stress "
     "locally: strain / expected = 0.25 (loaded layer), 1.333, 1.0, 0.889, 1.0, 1.037, 1.0, "
     "0.988 ... from the end, a boundary layer that decays by ~3 per cell and has the same "
     "shape in particle counts at every level, so its maximum beyond two spacings (0.889 "
     "for quadratic) does not fall; at a fixed distance from the ends it does"),
    ("stress_bar", r".", "the error is at its floor at every level: the particles reproduce "
     "the uniform strain and what is left is |eps| = 7.8e-6 itself (F - 1 of a linear law "
     "in the large-strain setting differs from sigma/E by O(eps)) plus the ringing the "
     "damping has not removed by t = 0.02; 1e-5 is far below 0.1 % at every level"),
    ("dam_break", r"SPH", "the reference is the experiment: the inviscid, free-slip, "
     "instantly released 2D model runs 4-5 % ahead of Koshizuka & Oka's front at every "
     "spacing (model error, not discretisation; cases/sph_dam_break.toml)"),
    ("dam_break", r"MPM", "the MPM front is a thin tongue (y < 0.06) on the free-slip floor "
     "that converges to a position ~17 % ahead of the experiment (x_front(T = 1.94) = 2.42, "
     "2.62, 2.65 at dx = 0.1, 0.05, 0.035, 3 / 17 / 34 particles ahead of x = 2.24): the "
     "error against the experiment grows as the tongue is resolved"),
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
