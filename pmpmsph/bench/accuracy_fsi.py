"""The accuracy map's FSI study: water on an elastic plate (BENCHMARKS.md scene 20,
bench/plate_fsi.py), one curve per plate / water pairing, so the map shows whether the
coupled pairing (an MPM plate under SPH water) reaches an error sooner than the pure ones
(issue 19, item 5)."""
import numpy as np

from .accuracy_core import advance
from .plate_fsi import midspan_deflection, start_heights, water_on_plate

#: seconds simulated, and the closing window the deflection is averaged over
END, WINDOW = 0.5, 0.1


def run_plate(dist, m, spacing, quick):
    sc, ref = water_on_plate(m["combo"], spacing=spacing, end=END,
                             hourglass=m.get("hourglass"))
    sim = sc.simulation(dist=dist)
    body = [b.name for b in sim.case.bodies].index("plate")
    y0 = start_heights(sim)
    samples = []

    def sample(s):
        if s.time >= END - WINDOW and s.step_count % 20 == 0:
            samples.append(midspan_deflection(s, body, ref["span"], y0))

    secs = advance(sim, END, sample)
    w = -float(np.mean(samples))
    return sim, secs, {"error": abs(w / ref["w_bending"] - 1.0),
                       "aux": abs(w / (ref["w_bending"] + ref["w_shear"]) - 1.0)}


PLATE_FSI = dict(
    key="plate_fsi", scene=20, title="Water on an elastic plate (2D FSI, static): mid-span "
    "deflection",
    metric="|w / w_beam - 1|, w the plate's mid-span deflection averaged over the last 0.1 s "
           "of 0.5 s, w_beam = q L^4 / (384 D) = 4.000 mm (Euler-Bernoulli); aux = against "
           "Timoshenko's 4.137 mm",
    aux="against Timoshenko", knob="particle spacing",
    methods=[dict(label="coupled MPM plate / SPH water", family="coupled", combo="mpm_plate"),
             dict(label="coupled TL-SPH plate / MPM water", family="coupled",
                  combo="sph_plate"),  # mirror clamps, no hourglass control
             dict(label="MPM plate / MPM water (contact)", family="MPM", combo="mpm_mpm",
                  quick=True),
             # the UL-SPH plate (Liu's kernel, mirror clamps, quadratic hourglass control)
             # runs 5x slower per particle: its finest level would take most of an hour
             dict(label="SPH UL plate / SPH water", family="SPH UL", combo="sph_sph",
                  levels={"full": [0.01, 0.005], "quick": [0.01]})],
    levels={"full": [0.01, 0.005, 0.0025], "quick": [0.01]}, knob_of=lambda sp: sp,
    run=run_plate,
    not_applicable={"SPH TL": "the total formulation is every SPH body's, and a fluid has no "
                              "reference configuration (the TL-SPH plate is run under MPM "
                              "water instead)"})
