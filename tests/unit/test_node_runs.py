"""The ghost-node exchange's packing (kernels/node_runs.py) against numpy views of the same
node layers: the same values in the same order, and the three ways of combining them."""
import numpy as np
import pytest

from pmpmsph.kernels.node_runs import ADD, COPY, MAXIMUM, PACK, move_runs


def _runs(shape, axis, lo, hi):
    inner = int(np.prod(shape[axis + 1:], dtype=np.int64))
    return (int(np.prod(shape[:axis], dtype=np.int64)), shape[axis] * inner, lo * inner,
            (hi - lo) * inner)


def _layers(arr, shape, axis, lo, hi):
    """The numpy view of node layers [lo, hi) along `axis` of a (fields, nodes[, k]) array."""
    blk = arr.reshape((arr.shape[0],) + tuple(shape) + arr.shape[2:])
    index = [slice(None)] * blk.ndim
    index[1 + axis] = slice(lo, hi)
    return blk[tuple(index)]


@pytest.mark.parametrize("shape,axis,lo,hi", [((7, 5), 0, 2, 5), ((7, 5), 1, 1, 4),
                                              ((4, 5, 6), 0, 1, 3), ((4, 5, 6), 1, 2, 5),
                                              ((4, 5, 6), 2, 0, 6), ((9,), 0, 3, 8)])
def test_runs_are_the_layers_in_c_order(shape, axis, lo, hi):
    rng = np.random.default_rng(3)
    nn = int(np.prod(shape))
    mass, mom = rng.random((2, nn)), rng.random((2, nn, len(shape)))
    arrays = (mass, mom)
    flat = tuple(a.reshape(a.shape[0], -1) for a in arrays)
    comps = np.array([1, len(shape)], np.int64)
    runs = _runs(shape, axis, lo, hi)
    buf = np.empty(sum(_layers(a, shape, axis, lo, hi).size for a in arrays))
    move_runs(flat, comps, *runs, buf, PACK)
    expect = np.concatenate([_layers(a, shape, axis, lo, hi).ravel() for a in arrays])
    assert np.array_equal(buf, expect)

    received = rng.random(buf.size)
    received[::7] = np.nan  # a NaN counts as missing in MAXIMUM (np.fmax)
    parts = np.split(received, [_layers(mass, shape, axis, lo, hi).size])
    for mode, combine in ((ADD, np.add), (MAXIMUM, np.fmax), (COPY, None)):
        got = tuple(a.copy() for a in arrays)
        want = tuple(a.copy() for a in arrays)
        move_runs(tuple(a.reshape(a.shape[0], -1) for a in got), comps, *runs, received,
                  mode)
        for w, part in zip(want, parts):
            view = _layers(w, shape, axis, lo, hi)
            value = part.reshape(view.shape)
            if combine is None:
                view[...] = value
            else:
                combine(view, value, out=view)
        for g, w in zip(got, want):
            assert np.array_equal(g, w, equal_nan=True)
