"""SPH time integrators, one class each: how a step combines the stage's evaluations, for
the updated-Lagrangian stage (`SPHStage`: rates `evaluate`, stress `stress`, stages
`_advance`) and the total-Lagrangian one (`TLSPHStage`: `evaluate(dt)` does both). A new
integrator is one class here and its line in `SPH_INTEGRATORS` (`[sph] integrator`'s
choices come from it).

Each `updated(stage, dt, m0, kicked)` / `total(stage, dt)` returns a failed row or -1.
Traits: `multi_stage` (it keeps the step-start state x_n, v_n, rho_n, F_n) and `aliases`.
"""
from ...kernels.sph.integrate import add_scaled, cayley_update


class Verlet:
    """Kick-drift-kick (velocity Verlet, leapfrog): symplectic, one evaluation a step. The
    updated form drifts in two halves around the kinematics so that rho and F advance with
    the mid-step velocity gradient (Cayley), and the hourglass control's displacement and
    the conservative coupling's kicks ride on its half kicks."""

    name = "verlet"
    aliases = ("leapfrog",)
    multi_stage = False

    @staticmethod
    def updated(stage, dt, m0, kicked):
        p, n = stage.p, stage.p.n_owned
        tag, meth = stage.dim_tag, p["method"]
        with stage.timers.phase("integrate"):
            if not kicked:
                add_scaled(tag, n, meth, 0.5 * dt, p["v"], p["acc"])  # kick
            stage._drift(n, 0.5 * dt)
        stage.kinematics()
        with stage.timers.phase("integrate"):
            cayley_update(tag, n, meth, dt, p["rho"], p["F"], p["drho"], p["L"])
            stage._drift(n, 0.5 * dt)
        bad = stage.stress(dt, m0)
        stage.evaluate()
        with stage.timers.phase("integrate"):
            add_scaled(tag, n, meth, 0.5 * dt, p["v"], p["acc"])  # kick
        return bad

    @staticmethod
    def total(stage, dt):
        p, n = stage.p, stage.p.n_owned
        tag, meth = stage.dim_tag, p["method"]
        with stage.timers.phase("integrate"):
            add_scaled(tag, n, meth, 0.5 * dt, p["v"], p["acc"])  # kick
            add_scaled(tag, n, meth, dt, p["x"], p["v"])  # drift
        stage.evaluate(dt)
        with stage.timers.phase("integrate"):
            add_scaled(tag, n, meth, 0.5 * dt, p["v"], p["acc"])  # kick
        return stage._bad


class PredictorCorrector:
    """Predictor with the last rates to mid-step, corrector from the step start with the
    mid-step rates (the midpoint rule; seed 004 section 5's alternative)."""

    name = "predictor_corrector"
    aliases = ()
    multi_stage = True

    @staticmethod
    def updated(stage, dt, m0, kicked):
        stage._advance(0.0, 1.0, 0.5 * dt, save=True)  # predictor with the last rates
        stage.stress(0.5 * dt, m0)
        stage.evaluate()
        stage._advance(1.0, 0.0, dt)           # corrector from the step start
        return stage.stress(dt, m0)

    @staticmethod
    def total(stage, dt):
        stage._advance(0.0, 1.0, 0.5 * dt, save=True)
        stage.evaluate(0.5 * dt)
        stage._advance(1.0, 0.0, dt)
        stage.evaluate(dt)
        return stage._bad


class TVDRungeKutta3:
    """Shu & Osher's third-order TVD Runge-Kutta (seed 004, section 5): y1 = y + dt f(y),
    y2 = 3/4 y + 1/4 (y1 + dt f(y1)), y = 1/3 y + 2/3 (y2 + dt f(y2))."""

    name = "rk3"
    aliases = ()
    multi_stage = True
    STAGES = ((0.0, 1.0, 1.0), (0.75, 0.25, 0.5), (1.0 / 3.0, 2.0 / 3.0, 1.0))

    @classmethod
    def updated(cls, stage, dt, m0, kicked):
        bad = -1
        for c0, c1, frac in cls.STAGES:
            if c0 > 0.0:
                stage.evaluate()
            stage._advance(c0, c1, c1 * dt, save=c0 == 0.0)
            bad = stage.stress(frac * dt, m0)
            if bad >= 0:
                break
        if bad < 0:
            stage.evaluate()  # rates at the new state start the next step
        return bad

    @classmethod
    def total(cls, stage, dt):
        for c0, c1, frac in cls.STAGES:
            stage._advance(c0, c1, c1 * dt, save=c0 == 0.0)
            stage.evaluate(frac * dt)
        return stage._bad


#: `[sph] integrator` -> integrator class (aliases included)
SPH_INTEGRATORS = {name: cls for cls in (Verlet, PredictorCorrector, TVDRungeKutta3)
                   for name in (cls.name,) + cls.aliases}
