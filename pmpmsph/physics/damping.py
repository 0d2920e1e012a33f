"""Wave absorbers (`[[damping]]`): damping zones on the fluids, as DualSPHysics' (Altomare et
al. 2017, Coastal Eng. 127, §2.3): inside a box the fluid particles' velocities are reduced
each step by the factor 1 - dt beta s^2, s growing from 0 on the box's inner face to 1 on the
face `direction`, so a wave entering the zone is absorbed over its depth without a
reflecting jump. A tank's ends with such zones let a float settle in seconds instead of
bobbing on the sloshing the drop excites (bench/floats.py). Acts after every step on the
particles of fluid bodies that are not walls; MPM points lose their APIC affine velocity in
the same proportion. A fluid at rest is untouched (v = 0), so hydrostatics are unchanged.
"""
import numpy as np

from ..kernels.damping import damp_in_zone


class DampingZones:
    def __init__(self, specs, case, particles):
        self.particles = particles
        self.dim = case.dim
        self.damped_body = np.array([case.materials[b.material].fluid and not b.wall
                                     for b in case.bodies])
        self.zones = []
        for s in specs:
            lo = np.array(s.region.lo, float)
            hi = np.array(s.region.hi, float)
            self.zones.append((lo, hi, "xyz".index(s.direction[0]), s.direction[1] == "+",
                               s.rate))

    def apply(self, dt):
        p = self.particles
        n = p.n_owned
        affine = p["C"] if "C" in p else None
        for lo, hi, axis, toward_hi, rate in self.zones:
            damp_in_zone(self.dim, n, p["x"], p["v"], affine, self.damped_body, p["body"],
                         lo, hi, axis, toward_hi, rate * dt)
