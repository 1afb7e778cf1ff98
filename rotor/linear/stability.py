"""Is the rotor's linearisation stable? A mode with negative damping says it is not.

The damped whirl modes (:func:`rotor.linear.modes.modes` with ``damped=True``: ``(λ²M + λ(C − ΩG) + K) q = 0``)
of a stable rotor all decay, ``ζ = −Re λ / |λ| > 0`` (or 0 for an undamped one). A cross-coupled bearing
(``k_yz = −k_zy``: a follower force, Friswell et al. 2010 §5.9) or an indefinite damping matrix feeds one mode:
its ζ < 0 and its free vibration grows as ``e^{−ζ|λ|t}``. Then a steady forced response (``rotor unbalance``,
``rotor response``) is not what the rotor will do, and a time integration diverges whatever the contact law.

:func:`first_unstable` looks over a sweep's speeds; :func:`stability_field` is the JSON field of a steady answer;
:func:`warning` the stderr line that names the mode. The loose support is locked (bearing and support move
together, the linear jobs' default) or open (unconnected), as the caller says.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: ζ below −ZETA_TOL is negative damping (round-off of an undamped, gyroscopic model stays far above)
ZETA_TOL = 1e-6
#: most speeds of a sweep whose eigenproblem is solved for the check (evenly chosen, both ends kept)
MOST_SPEEDS = 32


@dataclass(frozen=True)
class UnstableMode:
    """A mode with negative damping: ``mode`` (1-based, by frequency), its ``frequency_hz`` (Hz), ``damping_ratio``
    (< 0), ``whirl`` direction, the spin ``speed_rpm`` (rpm) and whether the loose support was ``locked``."""

    mode: int
    frequency_hz: float
    damping_ratio: float
    whirl: str
    speed_rpm: float
    locked: bool

    @classmethod
    def from_dict(cls, d: dict) -> "UnstableMode":
        """The inverse of :meth:`as_dict`."""
        lock = {"locked": True, "open": False}.get(d.get("loose_support"))
        return cls(int(d["mode"]), float(d["frequency_hz"]), float(d["damping_ratio"]), str(d["whirl"]),
                   float(d["speed_rpm"]), lock)

    @property
    def growth_rate_1_s(self) -> float:
        """Growth rate σ = −ζ ω (1/s) of the mode's free vibration (``e^{σ t}``)."""
        return -self.damping_ratio * 2 * math.pi * self.frequency_hz / math.sqrt(max(1e-300, 1 - self.damping_ratio ** 2))

    def sentence(self) -> str:
        """``mode 2 (18.96 Hz, forward whirl) has damping ratio -0.0312 at 1064 rpm (loose support locked)``."""
        return (f"mode {self.mode} ({self.frequency_hz:.4g} Hz, {self.whirl} whirl) has damping ratio "
                f"{self.damping_ratio:.3g} at {self.speed_rpm:.6g} rpm, growing as e^({self.growth_rate_1_s:.3g} t/s)"
                + ("" if self.locked is None else f" (loose support {'locked' if self.locked else 'open'})"))

    def as_dict(self) -> dict:
        return {"mode": self.mode, "frequency_hz": self.frequency_hz, "damping_ratio": self.damping_ratio,
                "whirl": self.whirl, "speed_rpm": self.speed_rpm, "growth_rate_1_s": self.growth_rate_1_s,
                "loose_support": None if self.locked is None else ("locked" if self.locked else "open")}


def unstable_modes(model, speed_rad_s: float, *, lock_loose_support: bool = True) -> list[UnstableMode]:
    """The modes with ζ < −:data:`ZETA_TOL` at ``speed_rad_s`` (rad/s), most negative damping first."""
    from rotor.linear.modes import modes
    m = modes(model, speed_rad_s, lock_loose_support=lock_loose_support, damped=True)
    locked = bool(lock_loose_support) if model.loose_pair is not None else None
    out = [UnstableMode(j + 1, float(m.frequency_hz[j]), float(z), m.whirl[j], speed_rad_s * 30 / math.pi, locked)
           for j, z in enumerate(m.damping_ratio) if z < -ZETA_TOL]
    return sorted(out, key=lambda u: u.damping_ratio)


def first_unstable(model, speeds_rad_s, *, lock_loose_support: bool = True,
                   most: int = MOST_SPEEDS) -> UnstableMode | None:
    """The least-damped unstable mode at the lowest of ``speeds_rad_s`` (at most ``most`` of them checked, evenly
    chosen with both ends) where one exists; None when every checked speed is stable."""
    speeds = np.sort(np.atleast_1d(np.asarray(speeds_rad_s, dtype=float)))
    if speeds.size > most:
        speeds = speeds[np.unique(np.round(np.linspace(0, speeds.size - 1, most)).astype(int))]
    for w in speeds:
        bad = unstable_modes(model, float(w), lock_loose_support=lock_loose_support)
        if bad:
            return bad[0]
    return None


def linearisation_unstable(model, speed_rad_s: float) -> UnstableMode | None:
    """The unstable mode of the nonlinear rotor's linearisation at ``speed_rad_s`` (rad/s): with the loose support
    locked, then open (ring and support unconnected: the clearance open all round); None if both are stable.
    A time integration or a shooting of such a rotor diverges because of the rotor, whatever the contact law."""
    for lock in ((True, False) if model.loose_pair is not None else (True,)):
        bad = unstable_modes(model, speed_rad_s, lock_loose_support=lock)
        if bad:
            return bad[0]
    return None


def divergence_message(found: UnstableMode, exc: BaseException) -> str:
    """What a nonlinear job says when its run fails on an unstable rotor: the instability, not the law."""
    return (f"the rotor is unstable: {found.sentence()}; its vibration grows until the run fails, whatever the contact "
            f"law (remove the negative damping: cross-coupled stiffness or damping of a bearing); the run stopped with: "
            f"{' '.join(str(exc).split())[:160]}")


def stability_field(found: UnstableMode | None) -> dict:
    """The JSON field of a steady answer: ``{"stable": bool, "unstable_mode": {...} or None}``."""
    return {"stable": found is None, "unstable_mode": None if found is None else found.as_dict()}


def warning(prog: str, found: UnstableMode, consequence: str) -> str:
    """``PROG: warning: unstable rotor: <the mode>; <consequence>`` (one line, for stderr)."""
    return f"{prog}: warning: unstable rotor: {found.sentence()}; {consequence}"
