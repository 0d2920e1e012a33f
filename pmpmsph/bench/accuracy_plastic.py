"""The accuracy map's plasticity study: Prandtl's strip footing (cases/prandtl_footing.toml,
MPM, half model; cases/prandtl_footing_sph.toml, SPH, full model): the pressure under a rigid
rough footing pushed into weightless von Mises soil, from the reaction of its
`[[prescribed]]` constraint, against the limit (2 + pi) c_u (Prandtl 1920; Hill 1950,
ch. VIII), at a settlement of 0.05 B."""
from pathlib import Path

import numpy as np

from ..config.load import load_case_file
from ..simulation import Simulation
from .accuracy_core import advance

CASES = Path(__file__).resolve().parents[2] / "cases"
C_U = 1.0e4  # the cases' yield stress / sqrt(3)
LIMIT = (2.0 + np.pi) * C_U
WIDTH, SPEED = 1.0, 0.05  # B, the footing's speed
AT, HALF_WINDOW = 0.05, 0.005  # the settlement / B read, and the window averaged about it
ROW_STEPS = 25


def footing(dist, family, cell, shape="gimp", fbar=True, end=None):
    """The footing's Simulation at cell size (MPM) or spacing (SPH) `cell`, and the length
    of footing its reaction holds (b = B/2 for the MPM half model, B for the SPH one).
    MPM: `shape`, and `fbar` (the case's F-bar, kernels/mpm/fbar.py) on or off."""
    end = (AT + HALF_WINDOW) * WIDTH / SPEED if end is None else end
    if family == "MPM":
        over = [("grid.cell_size", cell),
                ("grid.cells", [int(round(3.0 / cell)), int(round(2.2 / cell))]),
                ("mpm.shape", shape), ("mpm.fbar", fbar), ("time.end", end)]
        case, held = load_case_file(CASES / "prandtl_footing.toml", over), 0.5 * WIDTH
    else:
        over = [("bodies[0].spacing", cell), ("bodies[1].spacing", cell), ("time.end", end)]
        case, held = load_case_file(CASES / "prandtl_footing_sph.toml", over), WIDTH
    return Simulation(case, dist=dist, write_output=False), held


def pressure_curve(sim, held, end):
    """Advance `sim` to `end`; (settlement / B, pressure / limit) every ROW_STEPS steps, and
    the seconds spent stepping."""
    rows = []

    def record(s):
        if s.step_count % ROW_STEPS == 0:
            rows.append(s.diagnostics())

    secs = advance(sim, end, record)
    s = np.array([r["time"] for r in rows]) * SPEED / WIDTH
    q = -np.array([r["reaction0_y"] for r in rows]) / held / LIMIT
    return s, q, secs


def level_at(s, q, at, half=HALF_WINDOW):
    """Mean of q over settlements within `half` of `at`."""
    return float(np.mean(q[(s > at - half) & (s < at + half)]))


def run_footing(dist, m, cell, quick):
    sim, held = footing(dist, m["family"], cell, m.get("shape", "gimp"), m.get("fbar", True))
    s, q, secs = pressure_curve(sim, held, sim.case.time.end)
    level = level_at(s, q, AT)
    return sim, secs, {"error": abs(level - 1.0), "aux": level,
                       "series": {"s / B": s.tolist(), "q / q_lim": q.tolist()}}


FOOTING = dict(
    key="prandtl_footing", scene="footing", title="Prandtl strip footing on weightless von "
    "Mises soil (plane strain): limit pressure",
    metric="|q / ((2 + pi) c_u) - 1| with q the mean pressure under the footing over "
           "settlements 0.045 ... 0.055 B (the reaction of the held footing); aux = q / "
           "((2 + pi) c_u)",
    aux="q / q_lim", knob="cell size or spacing / B",
    methods=[dict(label="MPM gimp usl fbar", family="MPM", shape="gimp", transfer="usl",
                  quick=True),
             dict(label="MPM gimp usl", family="MPM", shape="gimp", transfer="usl",
                  fbar=False),
             dict(label="MPM quadratic usl fbar", family="MPM", shape="quadratic",
                  transfer="usl"),
             dict(label="SPH UL wendland PEC", family="SPH UL")],
    levels={"full": [0.1, 0.05, 0.025], "quick": [0.1]}, knob_of=lambda cell: cell / WIDTH,
    run=run_footing,
    series=dict(title="Prandtl footing: pressure against settlement", x="s / B",
                y="q / q_lim"),
    not_applicable={"SPH TL": "the soil flows plastically far from its reference "
                              "configuration",
                    "coupled": "one soil and a held footing: nothing to hand over"})
