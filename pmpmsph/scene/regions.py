"""Method regions of a scene (seed 000 §4): which scheme a particle takes by where it is."""
import numpy as np

from ..codes import METHOD_CODES


def region_methods(case, x, method):
    """Method codes of positions x under the case's method regions (applied in order over
    `method`, the codes the particles have now; wall particles are left alone)."""
    out = np.array(method, dtype=np.int8, copy=True)
    for reg in case.regions:
        inside = reg.geometry.contains(x) & (out != METHOD_CODES["wall"])
        out[inside] = METHOD_CODES[reg.method]
    return out
