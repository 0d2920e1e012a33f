"""The bench commands of issue 19 run end to end at a tiny size (their figures are measured
on an idle machine, not here): `floats` and `scaling --scene coupled_dam`."""
import json

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
