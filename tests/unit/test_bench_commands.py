"""The bench commands of issues 19 and 22 run end to end at a tiny size (their figures are
measured on an idle machine, not here): `floats`, `scaling --scene coupled_dam` and
`scaling --case FILE [--weak]`."""
import json
from pathlib import Path

import numpy as np

from pmpmsph.bench import floats, scaling


def test_scaling_worker_times_the_coupled_scene(tmp_path):
    """`scaling --scene coupled_dam`'s worker: the coupled case at a coarse spacing, its
    phases (the SPH ones too) and halo bytes in the JSON the table is made from."""
    path = tmp_path / "w.json"
    assert scaling.worker(["--scene", "coupled_dam", "--spacing", "0.02", "--steps", "2",
                           "--warmup", "1", "--json", str(path)]) == 0
    result = json.loads(path.read_text())
    assert result["particles"] == 2342 and result["steps"] == 2
    phases = result["per_rank"][0]["phases"]
    assert set(phases) == set(scaling.SCENES["coupled_dam"][0])
    assert phases["sph"] > 0.0 and phases["p2g"] > 0.0


def test_archimedes_fraction_of_an_incompressible_block():
    """In nearly incompressible water the fraction is the density ratio; in the bench's
    Tait water (kappa = 2e4) the water is denser at depth, so the block floats higher."""
    kappa = floats.KAPPA
    try:
        floats.KAPPA = 1e12
        assert abs(floats.archimedes_fraction(0.8 * 997.0 * 0.1 * 0.06, 0.1, 0.06) - 0.8) < 1e-6
    finally:
        floats.KAPPA = kappa
    assert 0.79 < floats.archimedes_fraction(0.8 * 997.0 * 0.1 * 0.06, 0.1, 0.06) < 0.8


def test_float_run_measures_a_block():
    r = floats.float_run("mpm_in_mpm", spacing=0.02, end=0.05, width=0.12, height=0.06,
                         drop=0.02, cell_spacings=2)
    assert np.isfinite(r["fraction"]) and r["particles"] > 0
    # dropped from 0.02 above the surface, it has not reached it at t = 0.05 s
    assert r["fraction"] < 0.0


# -- `scaling --case` and `--weak` (issue 22, item 7) --------------------------------------------
CASES = Path(__file__).resolve().parents[2] / "cases"
#: the 3D impact at 0.08 cells (113 points): an MPM case with a grid
TINY_IMPACT = ["grid.cell_size=0.08", "grid.cells=[20,5,8]", "bodies[0].spacing=0.04"]
#: the 2D SPH dam break at spacing 0.1 (no grid: the slabs cut the [domain] in cells of 2h)
TINY_DAM = [f"bodies[{i}].spacing=0.1" for i in range(4)]


def _per_slab(name, sets, copies):
    """Particles in each of `copies` equal slabs (the faces an N-rank run starts from) of the
    case replicated `copies` times, and the one-copy count."""
    from pmpmsph.config.load import parse_set
    from pmpmsph.parallel.distributor import Distributor
    from pmpmsph.simulation import Simulation

    data, case_name, base = scaling.case_data(str(CASES / name), parse_set(sets))
    one = scaling.build_case(data, case_name, base)
    axis = scaling.slab_axis(one)
    h = one.sph.h if one.grid is None else None
    counts = []
    for n in (1, copies):
        case = scaling.build_case(scaling.replicate(data, n, axis, h), case_name, base)
        sim = Simulation(case, dist=Distributor.serial(), write_output=False)
        dec = sim.decomposition
        assert dec.axis == axis
        x = sim.particles["x"][:sim.particles.n_owned, axis]
        cell = np.floor((x - dec.origin) / dec.dx).astype(int)
        faces = np.round(np.linspace(0, dec.ncells, n + 1)).astype(int)
        counts.append([int(np.sum((cell >= lo) & (cell < hi)))
                       for lo, hi in zip(faces[:-1], faces[1:])])
        sim.close()
    return counts


def test_weak_scaling_copies_along_the_slab_axis_one_per_slab():
    """`replicate` on a grid case (MPM, 3D) and a [domain] case (SPH, 2D, slabs cut along
    y there, the domain's longest axis): N copies, each of the N equal slabs holds exactly
    the one-copy particle count."""
    (one,), three = _per_slab("elastic_impact_3d.toml", TINY_IMPACT, 3)
    assert one > 0 and three == [one] * 3
    (one,), two = _per_slab("sph_dam_break.toml", TINY_DAM, 2)
    assert one > 0 and two == [one] * 2


def test_scaling_case_weak_writes_the_table_and_the_plot(tmp_path):
    """`scaling --case FILE --weak --ranks 1 2` end to end (mpirun, 2 steps): the JSON of
    each run, scaling.json and scaling.png; on 2 ranks twice the particles, each rank
    starting with the one-rank count, and the exchange counted (messages, bytes)."""
    out = tmp_path / "weak"
    rows = scaling.run([1, 2], 0, 2, str(out), repeat=1, case=str(CASES /
                       "elastic_impact_3d.toml"), sets=TINY_IMPACT, weak=True, warmup=1)
    for name in ("scaling.json", "scaling.png", "scaling_1_0.json", "scaling_2_0.json"):
        assert (out / name).stat().st_size > 0, name
    assert (out / "scaling.png").read_bytes()[:4] == b"\x89PNG"
    one, two = json.loads((out / "scaling.json").read_text())
    assert one["ranks"] == 1 and two["ranks"] == 2 and two["kind"] == "weak"
    assert two["particles"] == 2 * one["particles"] and two["replicas"] == 2
    assert [r["start_particles"] for r in two["per_rank"]] == [one["particles"]] * 2
    assert one["messages_per_step"] == 0 and two["messages_per_step"] >= 1
    assert two["p2p_bytes_per_step"] > 0 and rows[1]["efficiency"] > 0
