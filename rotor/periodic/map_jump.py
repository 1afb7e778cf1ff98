"""Where the corrector stalls because the period map jumps: the jump measured between two iterates.

A restart of a branch (:mod:`rotor.periodic.continuation`) says why the corrector failed. Where the failure is
a jump of the scheme's period map, not a step too long, the reason should say so with its size. The corrector
(:func:`rotor.periodic.corrector.correct`) records, when it rejects a full Newton step whose map switches the end
faces a different number of times in the period than the iterate's, the two points (``Evaluator.straddle``);
:func:`jump_across` bisects the segment between them on that number and measures the residual's change across
the boundary. A continuous map changes by the bisection's width there; a jump stays.

Measured on the Friswell rotor in a loose aluminium housing at 200 N preload (tests/rotor/scenes/
friswell-591-loose-aluminium.toml, branch 2 300 -> 2 800 rpm, stall at 2 542 rpm): the switches go from 2 to 4
across a boundary where the residual jumps by 3.8e-3 of the orbit's scale (the left face's holding force, 19.99 N
at its peak, passes μN = 20 N and the face then slips for 196 of 1 857 steps, most of them at about the
regularisation speed ``w_reg`` under a regularised force of 14-15 N; the jump is 1.9e-3 with ``w_reg`` a quarter
of its 1 µm/s, 1.8e-3 at a hundredth). Newton's iterates alternate between the two sides (residuals 1e-5 on one,
3.5e-3 on the other): the scheme's map has no fixed point there.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

#: bisection steps on the segment between the two iterates (its width 2^-40 of the segment's at the end)
BISECTIONS = 40
#: a change across the boundary larger than this many times the change of a smooth map over the bracket's width
#: (estimated from the segment's own ends) is a jump
JUMP_FACTOR = 1e3
#: and larger than this (scaled residual: ten times the corrector's default tolerance, branch_types.py): a smaller
#: one is within what the corrector accepts
JUMP_FLOOR = 1e-8


def jump_across(residual: Callable, y_a, y_b) -> dict | None:
    """The jump of the map between the scaled points ``y_a`` and ``y_b``, whose maps switch the faces a different
    number of times in the period.

    ``residual(y)``: ``(R, switches)``, the scaled residual of the period map at ``y`` and its end-face switches in
    the period. Returns None where the ends switch alike, or where the residual changes across the boundary no
    more than a continuous map would over the final bracket (``JUMP_FACTOR`` times the segment's mean slope times
    the bracket's width) or than ``JUMP_FLOOR``; else ``{"jump": max |ΔR|, "switches": (a, b), "at": y}``, ``y``
    the boundary's point on the ``y_a`` side."""
    y_a, y_b = np.asarray(y_a, float), np.asarray(y_b, float)
    R_lo, e_lo = residual(y_a)
    R_hi, e_hi = residual(y_b)
    if e_lo == e_hi:
        return None
    slope = float(np.max(np.abs(R_hi - R_lo)))          # the residual's change over the whole segment
    lo, hi = 0.0, 1.0
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        R, e = residual(y_a + mid * (y_b - y_a))
        if e == e_lo:
            lo, R_lo = mid, R
        else:
            hi, R_hi = mid, R
    jump = float(np.max(np.abs(R_hi - R_lo)))
    if not jump > max(JUMP_FACTOR * slope * (hi - lo), JUMP_FLOOR):
        return None
    return {"jump": jump, "switches": (int(e_lo), int(e_hi)), "at": y_a + lo * (y_b - y_a)}


def jump_text(found: dict | None, name: str, value: float) -> str:
    """The jump in words for a stall's reason (empty without one); ``name = value``: where (the parameter)."""
    if found is None:
        return ""
    a, b = found["switches"]
    return (f"; the period map jumps by {found['jump']:.1e} of the orbit's scale at {name} = {value:.6g}, where "
            f"its switches in the period go from {a} to {b} (the scheme's map has no orbit across it)")
