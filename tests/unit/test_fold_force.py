"""PIC-USL without damping folds the forces into the momentum scatter (P2G scatters p + dt f,
the grid divides by m and adds g dt; `MPMStage.fold_force`). It is the same update as the
general path (v = p/m, then v += dt (f/m + g)) up to rounding: 100 steps of the throughput
scene (a falling fluid block hitting the walls, quadratic B-splines) agree to 1e-10."""
import numpy as np

from pmpmsph.bench.throughput import mpm_peer_scene


def test_folded_force_scatter_equals_the_general_update():
    folded = mpm_peer_scene(32).simulation(write_output=False)
    general = mpm_peer_scene(32).simulation(write_output=False)
    assert folded.mpm.fold_force
    general.mpm.fold_force = False
    folded.run(max_steps=100)
    general.run(max_steps=100)
    for name in ("x", "v", "J", "sigma"):  # a fluid scene stores J (`mpm.deformation`)
        a, b = folded.particles[name], general.particles[name]
        scale = np.abs(b).max()
        assert np.abs(a - b).max() <= 1e-10 * scale, name
    assert np.abs(folded.particles["v"]).max() > 0.5  # it moved (falls at 1 m/s, then hits)
