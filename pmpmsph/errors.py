"""The two kinds of failure a user sees (DESIGN.md section 7).

`ConfigError` stops a run before step 1 (exit status 2) and names the TOML key;
`RunError` stops a running simulation (exit status 3) and names step, particle and cause.
"""
import difflib
import math

EXIT_CONFIG = 2
EXIT_RUNTIME = 3


def is_finite(v):
    """A finite float or an int that fits a float (TOML integers have no size limit, and
    math.isfinite raises OverflowError beyond 1.8e308)."""
    try:
        return math.isfinite(v)
    except OverflowError:
        return False


def did_you_mean(word, candidates):
    """' (did you mean 'x'?)' for the closest of `candidates` (difflib's ratio >= 0.6, the
    threshold its `get_close_matches` uses), else ''."""
    close = difflib.get_close_matches(str(word), sorted(candidates), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def short_repr(v):
    """repr of a value, shortened (an integer of 400 digits is not a useful message)."""
    text = repr(v)
    return text if len(text) <= 40 else f"{text[:20]}...({len(text)} characters)"


class ConfigError(Exception):
    """Bad input: `key` is the dotted TOML path (e.g. ``bodies[0].material``)."""

    def __init__(self, key, reason):
        self.key = key
        self.reason = reason
        super().__init__(f"{key}: {reason}")

    def __str__(self):
        return f"invalid input at '{self.key}': {self.reason}"


class RunError(Exception):
    """A failure during the time loop: step number, particle gid (or -1) and the cause."""

    def __init__(self, step, gid, cause):
        self.step = step
        self.gid = gid
        self.cause = cause
        super().__init__(str(self))

    def __str__(self):
        who = f"particle gid {self.gid}" if self.gid >= 0 else "no single particle"
        return f"run failed at step {self.step} ({who}): {self.cause}"


class RunStopped(Exception):
    """The run was stopped by a signal at the end of a step, its state written (exit status 3)."""

    def __init__(self, signame, step, time, checkpoint=None):
        self.signame = signame
        self.step = step
        self.time = time
        self.checkpoint = checkpoint
        super().__init__(str(self))

    def __str__(self):
        msg = f"stopped by {self.signame} after step {self.step} (t = {self.time:.6g})"
        if self.checkpoint:
            return (f"{msg}; state written to {self.checkpoint}; continue with: "
                    f"python -m pmpmsph --restart {self.checkpoint}")
        return f"{msg}; no checkpoint written (no output folder)"
