"""How much of a bending strain rate each corrected SPH gradient reads (docs/plate.md).

A strip 0.4 x 0.02, 2 / 4 / 8 particles through its thickness, h = 1.4 spacings, given the
bending velocity field v = (-k x (y - t/2), k x^2 / 2), whose dv_x/dx = -k (y - t/2) varies
through the thickness. Measured at mid-span on each row, as a fraction of the exact value:
- the updated formulation's Bonet-Lok gradient (`[sph] correction = true`, the L of one
  evaluation): 1/3 at 2 through; 0.75 / 0.93 on the surface / inner rows at 4; 0.89 / 0.99
  / 1.00 at 8: a weighted linear fit across a few rows averages their slopes;
- the total formulation's corrected kernel (Liu's, the gradient of a linearly complete
  interpolant) applied to the same field: 1.003 at 2 through, exact at 4 and 8.
That deficit is why an updated-Lagrangian plate with Bonet & Lok's correction is far too
soft in bending (+57 / +82 % at 2 / 4 through alone). `[sph] correction = "liu"` gives the
updated formulation Liu's corrected kernel (kernels/sph/liu.py): it reads the bending
exactly (the second test), and the plate alone sags +43.7 / +19.1 % (plain clamps), the
total formulation's figures.
"""
import numpy as np
import pytest
from mpi4py import MPI

from pmpmsph import Scene
from pmpmsph.kernels.neighbours import neighbour_lists
from pmpmsph.kernels.sph.kernel_functions import SUPPORT
from pmpmsph.kernels.sph.tlsph import deformation_gradient, kernel_correction
from pmpmsph.parallel.distributor import Distributor

THICK, SPAN, K = 0.02, 0.4, 1.0


def _strip(through, correction=True):
    sp = THICK / through
    sc = Scene(2, time=dict(end=1.0, cfl=0.2), parallel=dict(balance_every=0),
               domain=dict(min=[-0.1, -0.1], max=[SPAN + 0.1, 0.1]),
               sph=dict(formulation="updated", correction=correction, h_factor=1.4,
                        integrator="verlet"))
    sc.material("steel", model="neo_hookean", E=1e7, nu=0.3, rho=7800.0)
    sc.body(name="strip", method="sph", material="steel", shape="box", min=[0.0, 0.0],
            max=[SPAN, THICK], spacing=sp)
    return sc.simulation(dist=Distributor(MPI.COMM_SELF))


def _fractions(through, correction=True):
    """(y of the mid-span rows, UL L_xx / exact, Liu L_xx / exact) at mid-span."""
    sim = _strip(through, correction)
    p = sim.particles
    n = p.n_owned
    x = np.ascontiguousarray(p["x"][:n].copy())
    v = np.stack([-K * (x[:, 1] - THICK / 2) * x[:, 0], 0.5 * K * x[:, 0] ** 2], axis=1)
    p["v"][:n] = v
    sim.sph.evaluated = False
    sim.sph.evaluate()
    h = sim.sph.h
    start, index = neighbour_lists(x, n, SUPPORT * h)
    gw, wt = np.empty((len(index), 2)), np.empty(len(index))
    vol = np.ascontiguousarray(p["mass"][:n] / p["rho"][:n])
    kernel_correction(x, vol, start, index, h, 0, 2, True, wt, gw)
    G = np.zeros((n, 3, 3))
    deformation_gradient(np.arange(n), start, index, gw, vol, np.ascontiguousarray(x + v), x,
                         2, G)
    exact = -K * (x[:, 1] - THICK / 2)
    sp = THICK / through
    mid = (np.abs(x[:, 0] - SPAN / 2) < sp) & (x[:, 0] < SPAN / 2) & (x[:, 1] < THICK / 2)
    order = np.argsort(x[mid, 1])
    return (x[mid, 1][order], (p["L"][:n, 0, 0][mid] / exact[mid])[order],
            ((G[:, 0, 0] - 1.0)[mid] / exact[mid])[order])


@pytest.mark.parametrize("through,updated", [(2, [0.336]), (4, [0.752, 0.928]),
                                             (8, [0.894, 0.986, 1.0, 1.0])])
def test_updated_gradient_reads_too_little_bending(through, updated):
    _, ul, liu = _fractions(through)
    assert np.allclose(ul, updated, atol=0.005), ul
    assert np.allclose(liu, 1.0, atol=0.005), liu


@pytest.mark.parametrize("through", [2, 4, 8])
def test_updated_formulation_with_liu_reads_bending_exactly(through):
    _, ul, _ = _fractions(through, correction="liu")
    assert np.allclose(ul, 1.0, atol=0.005), ul
