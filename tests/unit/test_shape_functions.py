"""The MPM shape-function registry (pmpmsph/kernels/mpm/shape_functions/): every registered
shape is a partition of unity that reproduces linear fields over `width` nodes, and the
generated switches, choice list and traits are the registry's."""
import numpy as np
import pytest

from pmpmsph.config.case import SHAPES
from pmpmsph.kernels.mpm.shape_functions.registry import (ShapeFunction, register_shape,
                                                         shape_functions)
from pmpmsph.kernels.mpm.shapes import (STENCIL_WIDTH, apic_d_inverse, stencil_width,
                                        weights_1d)
from pmpmsph.physics.mpm.stage import MPMStage

REGISTERED = shape_functions()


def test_the_switches_and_the_choice_list_are_the_registry():
    assert SHAPES == tuple(s.name for s in REGISTERED)
    for s in REGISTERED:
        assert stencil_width(s.code) == STENCIL_WIDTH[s.code] == s.width
        assert apic_d_inverse(s.code) == s.apic_d_inverse
    assert {s.name: s.apic_d_inverse for s in REGISTERED if s.apic_d_inverse} == {
        "quadratic": 4.0, "cubic": 3.0}  # Jiang et al. 2015, section 5.1


@pytest.mark.parametrize("shape", REGISTERED, ids=lambda s: s.name)
def test_partition_of_unity_and_linear_completeness(shape):
    rng = np.random.default_rng(11)
    lp = 0.25 if shape.half_width else 0.5
    for X in 7.0 + rng.uniform(0.0, 1.0, 50):
        base, w, dw = weights_1d(shape.code, X, lp)
        w, dw = np.array(w), np.array(dw)
        assert np.all(w[shape.width:] == 0.0) and np.all(w >= 0.0)
        nodes = base + np.arange(4)
        assert w.sum() == pytest.approx(1.0, abs=1e-14)
        assert dw.sum() == pytest.approx(0.0, abs=1e-14)
        assert np.dot(w, nodes) == pytest.approx(X, abs=1e-13)      # linear fields exact
        assert np.dot(dw, nodes) == pytest.approx(1.0, abs=1e-13)   # and their gradient


def test_register_refuses_a_taken_code_and_a_wide_stencil():
    linear = REGISTERED[0]
    with pytest.raises(ValueError, match="code 0"):
        register_shape(ShapeFunction("other", linear.code, linear.weights, 2, 1.0))
    with pytest.raises(ValueError, match="width 5"):
        register_shape(ShapeFunction("wide", 99, linear.weights, 5, 2.5))
    assert [s.code for s in shape_functions()] == [s.code for s in REGISTERED]


def test_shapes_with_a_particle_half_width_carry_the_lp_field():
    class Case:  # (what MPMStage.fields reads)
        class mpm:
            velocity_update = "flip"
        bodies = ()
    for s in REGISTERED:
        Case.mpm.shape = s.name
        names = [f.name for f in MPMStage.fields(Case)]
        assert ("lp" in names) == (s.name in ("gimp", "cpdi"))
