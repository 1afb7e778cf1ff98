"""Which orbit method runs, and each method checking the other: ``orbit``/``branch --method hb|shooting|auto``.

Shooting (:mod:`rotor.studies.orbit`) integrates the production scheme, whose orbits carry the trapezoidal rule's
frequency warping, a relative error of about ``π²/(3N²)`` at ``N`` steps per revolution
(:func:`shooting_step_error`; ``Ω' = Ω tan(π/N)/(π/N)``, :mod:`rotor.periodic.jeffcott`), but it handles
impacts and stick/slip. Harmonic balance (:mod:`rotor.studies.hb_orbit`) has no step: its error is the spectrum
it cuts off, estimated by the tail of the harmonics it keeps (:func:`rotor.studies.hb_orbit.spectrum_tail`), and it
applies only to a frictionless ring (:func:`rotor.periodic.hb_aft.hb_not_applicable`).

:func:`auto_choice` (``--method auto``): HB where it applies AND its spectrum converges (the ladder of harmonics
1, 2, 4 … :data:`rotor.studies.hb_orbit.MAX_AUTO_HARMONICS`, stopped when the tail is below the shooting's step
error at the speed, or when the next rung's predicted CPU exceeds :data:`HB_CPU_LIMIT_S`: a dense Newton step
costs ~(2H+1)³, ×8 a rung); else shooting, with the reason. :func:`cross_check`: where both apply, the other
method's orbit at the same speed and the largest difference of the 1X velocity amplitudes.
"""
from __future__ import annotations

import math
import time

from contact.errors import ConvergenceError, InputError, OutsideDomainError
from rotor.periodic.hb_aft import hb_not_applicable
from rotor.studies.hb_orbit import MAX_AUTO_HARMONICS, HBPoint, hb_point
from rotor.studies.steady_state import SteadyStateOptions, point_system, step_per_rev

METHODS = ("shooting", "hb", "auto")
#: a rung of the HB ladder is not started when its predicted CPU (the last rung's × 8) exceeds this (s)
HB_CPU_LIMIT_S = 30.0


def shooting_step_error(steps_per_rev: int) -> float:
    """The relative frequency warping of the average-acceleration Newmark scheme at ``steps_per_rev`` steps per
    revolution, ``tan(π/N)/(π/N) − 1 ≈ π²/(3N²)`` (–): the size of shooting's O(h²) orbit error on a rotor whose
    response is not near a sharp resonance (the amplitudes' error is this times their slope in the speed)."""
    h = math.pi / int(steps_per_rev)
    return math.tan(h) / h - 1.0


def check_method(method: str, prog: str) -> None:
    """InputError (exit 2) naming ``--method``, the value typed and what is allowed, for an unknown method."""
    if method not in METHODS:
        raise InputError(f"--method = {method}: must be one of {', '.join(METHODS)} ({prog})")


def hb_refusal(scene: str, speed_rpm: float, **overrides) -> str | None:
    """Why HB does not apply to ``scene`` at ``speed_rpm`` (one line, from
    :func:`rotor.periodic.hb_aft.hb_not_applicable`), or None."""
    return hb_not_applicable(point_system(scene, speed_rpm, **overrides)[2])


def auto_choice(scene: str, speed_rpm: float, *, harmonics: int | None = None, steps_per_rev: int | None = None,
                period_revs: int = 1, **overrides) -> tuple[HBPoint | None, dict]:
    """``(HB point or None, choice)``: the HB orbit where it applies and its spectrum converged within the error
    shooting would have at this speed, else None (shooting runs). ``choice``: ``method`` ("hb" or "shooting"),
    ``reason`` (one line), ``hb_spectrum_tail``, ``shooting_step_error`` (at ``steps_per_rev``, None: the
    step the scene needs there), ``hb_cpu_s`` (the ladder's CPU, s)."""
    _, _, system = point_system(scene, speed_rpm, **overrides)
    n = int(steps_per_rev or step_per_rev(system, SteadyStateOptions()))
    bound = shooting_step_error(n)
    choice = {"method": "shooting", "shooting_steps_per_rev": n, "shooting_step_error": bound,
              "hb_spectrum_tail": None, "hb_cpu_s": None}
    why = hb_not_applicable(system)
    if why is not None:
        return None, {**choice, "reason": why}
    c0 = time.process_time()
    try:
        pt = hb_point(scene, speed_rpm, harmonics=harmonics, period_revs=period_revs, tail_tol=bound,
                      max_cpu_s=HB_CPU_LIMIT_S, **overrides)
    except (ConvergenceError, OutsideDomainError) as e:
        return None, {**choice, "hb_cpu_s": time.process_time() - c0, "reason": f"HB failed ({e}); shooting"}
    choice.update(hb_spectrum_tail=pt.tail, hb_cpu_s=pt.cpu_s)
    H = pt.orbit.harmonics
    if not pt.orbit.converged:
        return None, {**choice, "reason": f"HB Newton stalled at {H} harmonics (residual {pt.orbit.residual:.1e}); "
                                          "shooting"}
    if not pt.tail < bound:
        top = MAX_AUTO_HARMONICS if harmonics is None else harmonics
        return None, {**choice, "reason": f"HB spectrum not converged: tail {pt.tail:.1e} at {H} harmonics (limit "
                                          f"{top}, CPU limit {HB_CPU_LIMIT_S:g} s a rung) is not below shooting's step "
                                          f"error {bound:.1e} at {n} steps per revolution; shooting"}
    return pt, {**choice, "method": "hb",
                "reason": f"HB applies (frictionless ring) and its spectrum converged: tail {pt.tail:.1e} at {H} "
                          f"harmonics, below shooting's step error {bound:.1e} at {n} steps per revolution; HB CPU "
                          f"{pt.cpu_s:.2f} s"}


def amplitude_difference(a: dict, b: dict) -> dict:
    """The largest difference of the 1X velocity amplitudes (mm/s) between two results' ``<station>.<y|z>``
    channels (shared ones), absolute and relative to the largest 1X amplitude of ``b``, and its channel."""
    keys = [k for k in a if k in b]
    if not keys:
        return {"largest_1X_difference_mm_s": None, "largest_1X_difference_rel": None, "channel": None}
    k = max(keys, key=lambda c: abs(a[c][0] - b[c][0]))
    top = max(abs(b[c][0]) for c in keys)
    d = abs(a[k][0] - b[k][0])
    return {"largest_1X_difference_mm_s": d, "largest_1X_difference_rel": d / top if top else 0.0, "channel": k}


def cross_check(hb: dict, shooting: dict) -> dict:
    """The JSON ``cross_check`` of an orbit computed by both methods (their :meth:`as_dict`-shaped dicts): the
    1X amplitude difference (:func:`amplitude_difference`, relative to the HB orbit's), the edge penetration
    difference (mm), and, where shooting carried ``richardson``, the extrapolated orbit's difference from HB; with
    the error each method expects (HB's spectrum tail, shooting's step error)."""
    n = int(shooting["steps_per_rev"])
    out = {"methods": ["hb", "shooting"], "speed_rpm": hb["speed_rpm"],
           **amplitude_difference(shooting["velocity_amplitudes_mm_s_1X_to_5X"], hb["velocity_amplitudes_mm_s_1X_to_5X"]),
           "max_edge_penetration_difference_mm": abs(shooting["max_edge_penetration_mm"] - hb["max_edge_penetration_mm"]),
           "hb_spectrum_tail": hb.get("spectrum_tail"), "shooting_steps_per_rev": n,
           "shooting_step_error": shooting_step_error(n)}
    rich = shooting.get("richardson")
    if rich and rich.get("converged"):
        d = amplitude_difference(rich["velocity_amplitudes_mm_s_1X_to_5X"], hb["velocity_amplitudes_mm_s_1X_to_5X"])
        out["richardson"] = {"largest_1X_difference_mm_s": d["largest_1X_difference_mm_s"],
                             "largest_1X_difference_rel": d["largest_1X_difference_rel"], "channel": d["channel"]}
    return out
