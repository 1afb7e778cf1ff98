"""Steps and located events of the HB continuation (:func:`rotor.periodic.harmonic_balance.hb_branch`): a point of
the branch, one accepted step, and the folds, grazings and corners located between two points, each by its own
corrected orbits.

A step is retried with half its length where the corrector fails or the tangent turns more than the options'
``max_turn_deg`` (:func:`_advance`), except across the ring's surface, where the turn is the grazing corner's. A
grazing is located on the gap side's piece continued past the ring without its force (:func:`_gap_grazing`: the
law's force is zero at zero penetration, so that piece's grazing orbit is the branch's, and it is smooth there,
where the branch's penetration changes slope by orders at the corner); a fold by regula falsi on the speed
component of the tangent (:func:`_locate`); a grazing fold, where the corrector cannot follow the curve's turn, by
:func:`_corner` from the last point brought onto the grazing (:func:`_onto_grazing`). ``tr`` is the tracer of
:mod:`rotor.periodic.harmonic_balance` (``correct``, ``tangent``, ``evaluate``, ``opts``, ``sz``, ``sw``, ``locate``,
``free``).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from rotor.periodic.hb_aft import HarmonicSystem, full_coefficients, largest_penetration

#: scaled step below which a tangent turn above ``max_turn_deg`` is accepted (a corner)
CORNER_DS = 1e-4
#: a corrected point farther than this many steps from its predictor jumped to another part of the curve (the
#: corrector on the hyperplane moves a point of a smooth curve by ~ds·tan(turn), a corner's by at most ds for a
#: 45° turn); the step is halved. Measured: 0.005-0.06 steps on smooth stretches, 23 on a jump (a random conformal
#: rotor of tests/rotor/periodic/test_harmonic_balance.py: from 138.9 rad/s next to grazing on the branch's middle
#: part, back onto its rising part at 134.6 rad/s, which the branch then followed back to the start)
MAX_CORRECTION_STEPS = 1.0


@dataclass(frozen=True)
class HBEvent:
    """A located point of a branch between points ``index − 1`` and ``index``: ``kind`` "fold" (smooth turning
    point), "grazing_fold" (the speed turns at a corner where the orbit grazes the ring), "corner" (the speed turns
    at a kink off the ring) or "grazing" (the largest penetration changes sign); ``speed_rad_s`` (rad/s),
    ``dspeed_ds`` (speed component of the unit scaled tangent there), ``penetration_m`` (m), ``coefficients``
    (2H+1, n) (m, rad)."""

    kind: str
    index: int
    speed_rad_s: float
    dspeed_ds: float
    penetration_m: float
    coefficients: np.ndarray


@dataclass
class _Point:
    y: np.ndarray
    tau: np.ndarray
    hs: HarmonicSystem
    z: np.ndarray
    res: float
    its: int
    pen: float


def _make_point(tr, got, tau_prev) -> _Point:
    y, Jy, hs, z, res, its = got
    nh = 2 * hs.fourier.harmonics + 1
    return _Point(y, tr.tangent(Jy, tau_prev), hs, z, res, its, largest_penetration(hs, z.reshape(nh, hs.n_r)))


def _advance(tr, pt: _Point, ds: float, corner_first: bool = False):
    """One accepted step from ``pt``: ``(point, ds used, rejected steps)``, or ``(None, ds, rejected)`` below
    ``ds_min``. A step is retried with half the length when the corrector fails or lands farther than
    :data:`MAX_CORRECTION_STEPS` steps from its predictor, or the tangent turns more than ``max_turn_deg``, unless
    the step is already below :data:`CORNER_DS` or crossed the ring's surface going on (the penetration changed sign and grows along the new tangent: the turn is the grazing corner's, and the
    grazing is located afterwards by its own solves). A step that crossed with the new tangent heading back to
    the surface jumped over a turn there (a grazing fold, which :func:`_corner` passes): always halved. ``corner_first``:
    a failed corrector from a point within 1e-5 δ0 of grazing returns ``(None, ds, …)`` at once, for
    :func:`_corner` (the curve turns there by more than the hyperplane can follow)."""
    o = tr.opts
    rejected = 0
    cos_max = math.cos(math.radians(o.max_turn_deg))
    while ds >= o.ds_min:
        got = tr.correct(pt.y + ds * pt.tau, pt.tau)
        if got is not None and np.linalg.norm(got[0] - pt.y - ds * pt.tau) > MAX_CORRECTION_STEPS * ds:
            got = None                      # jumped: treated as a failed corrector
        if got is not None:
            new = _make_point(tr, got, pt.tau)
            crossed = new.pen * pt.pen < 0.0
            if crossed and _pen_slope(tr, new) * new.pen <= 0.0:
                pass                        # over a turn at the surface: the new tangent heads back to it
            elif float(new.tau @ pt.tau) >= cos_max or ds <= CORNER_DS or crossed:
                return new, ds, rejected
        elif corner_first and abs(pt.pen) <= 1e-5 * pt.hs.clearance_m:
            return None, ds, rejected
        ds *= 0.5
        rejected += 1
    return None, ds, rejected


def _on_arc(tr, a: _Point, s: float, what: str):
    """The orbit at scaled arclength ``s`` from ``a`` along its tangent, and the quantity ``what`` ("fold": the
    speed component of its tangent, "grazing": its penetration over δ0) there."""
    got = tr.correct(a.y + s * a.tau, a.tau)
    if got is None:
        return None, math.nan
    p = _make_point(tr, got, a.tau)
    return p, (float(p.tau[-1]) if what == "fold" else p.pen / p.hs.clearance_m)


def _locate(tr, a: _Point, b: _Point, ds: float, what: str, index: int) -> HBEvent:
    """Regula falsi (Illinois) on the arclength in ``(0, ds)`` between ``a`` and ``b`` for the zero of ``what``
    (:func:`_on_arc`); a jump of the quantity (a corner) is bracketed down to 1e-12 of the step instead. A grazing
    is first sought on the gap side's piece alone (:func:`_gap_grazing`: the law is off there, the penetration
    smooth; across the corner its slope changes by orders, which regula falsi would bracket only linearly)."""
    g = {"fold": lambda p: float(p.tau[-1]), "grazing": lambda p: p.pen / p.hs.clearance_m}[what]
    s0, s1, g0, g1 = 0.0, ds, g(a), g(b)
    best = (a, g0) if abs(g0) < abs(g1) else (b, g1)
    if what == "grazing" and tr.locate:
        p = _gap_grazing(tr, a, b, ds)
        best = (p, g(p)) if abs(g(p)) < abs(best[1]) else best
    last = 0
    for it in range(60 if tr.locate and abs(best[1]) > 1e-12 else 0):
        s = (s0 * g1 - s1 * g0) / (g1 - g0) if g1 != g0 else 0.5 * (s0 + s1)
        if not (s0 < s < s1) or it % 4 == 3:           # every fourth trial a bisection: a jump shrinks too
            s = 0.5 * (s0 + s1)
        p, gs = _on_arc(tr, a, s, what)
        if p is None:
            break
        if abs(gs) < abs(best[1]):
            best = (p, gs)
        if gs * g0 > 0:
            s0, g0 = s, gs
            g1, last = (0.5 * g1 if last == -1 else g1), -1
        else:
            s1, g1 = s, gs
            g0, last = (0.5 * g0 if last == 1 else g0), 1
        if abs(gs) < 1e-12 or s1 - s0 < 1e-12 * ds:
            break
    p, gv = best
    kind = what
    if what == "fold" and abs(gv) > 1e-6:
        kind = "grazing_fold" if abs(p.pen) <= 1e-6 * p.hs.clearance_m else "corner"
    return HBEvent(kind, index, float(p.y[-1] * tr.sw), float(p.tau[-1]), p.pen, full_coefficients(p.hs, p.z))


def _events_between(tr, a: _Point, b: _Point, ds: float, index: int) -> list[HBEvent]:
    """The events between ``a`` and ``b``: a grazing where the penetration changes sign, a fold where the tangent's
    speed component does; both, with the grazing's speed beyond both ends' (the speed turns there), is one grazing
    fold at the grazing (the corner of a step that crossed the surface)."""
    out = []
    fold = a.tau[-1] * b.tau[-1] < 0
    if np.isfinite(a.pen) and a.pen * b.pen < 0:
        g = _locate(tr, a, b, ds, "grazing", index)
        wa, wb = a.y[-1] * tr.sw, b.y[-1] * tr.sw
        if fold and (g.speed_rad_s - wa) * (g.speed_rad_s - wb) > 0.0:
            return [dataclasses.replace(g, kind="grazing_fold")]
        out.append(g)
    if fold:
        out.append(_locate(tr, a, b, ds, "fold", index))
    return sorted(out, key=lambda e: abs(e.speed_rad_s - a.y[-1] * tr.sw))


def _one_sided(tr, c: _Point, side: float):
    """The tangent at the grazing point ``c`` on one side of the ring: the Jacobian at ``c``'s coefficients
    scaled so that the largest penetration is ``side`` × 1e-9 δ0 (gap side −1, contact side +1; the relative
    displacement is linear in the coefficients), oriented with ``c.tau``."""
    d0 = c.hs.clearance_m
    y = c.y.copy()
    y[:-1] *= d0 * (1.0 + side * 1e-9) / (d0 + c.pen)
    return tr.tangent(tr.evaluate(y)[1], c.tau)


def _corner(tr, pts: list) -> tuple[_Point, HBEvent] | None:
    """Past a grazing corner where the corrector stalls (the curve turns by more than a right angle at the point
    where the orbit touches the ring: the hyperplane orthogonal to the incoming tangent misses the outgoing
    side): from the last point, within 1e-5 δ0 of grazing, along the other side's one-sided tangent, oriented
    into that side. Returns the first point past it and the corner's event, or None."""
    c = pts[-1]
    d0 = c.hs.clearance_m
    if len(pts) < 2 or not np.isfinite(c.pen) or abs(c.pen) > 1e-5 * d0:
        return None
    came_from = 1.0 if pts[-2].pen > 0 else -1.0
    out = -came_from
    c = _onto_grazing(tr, c, pts[-2])
    t = _one_sided(tr, c, out)
    nh = 2 * c.hs.fourier.harmonics + 1
    z_probe = (c.y[:-1] + 1e-6 * t[:-1]) * tr.sz
    if (largest_penetration(c.hs, z_probe.reshape(nh, c.hs.n_r)) - c.pen) * out < 0:
        t = -t
    start = _Point(c.y, t, c.hs, c.z, c.res, c.its, c.pen)
    new, _, _ = _advance(tr, start, tr.opts.ds)
    if new is None or new.pen * out <= 0:
        return None
    kind = "grazing_fold" if c.tau[-1] * t[-1] < 0 else "grazing"
    return new, HBEvent(kind, len(pts), float(c.y[-1] * tr.sw), float(t[-1]), c.pen, full_coefficients(c.hs, c.z))


def _pen_slope(tr, p: _Point) -> float:
    """Derivative of the largest penetration along ``p``'s tangent (m per scaled arclength; a difference 1e-6)."""
    nh = 2 * p.hs.fourier.harmonics + 1
    z = (p.y[:-1] + 1e-6 * p.tau[:-1]) * tr.sz
    return (largest_penetration(p.hs, z.reshape(nh, p.hs.n_r)) - p.pen) / 1e-6


def _gap_grazing(tr, a: _Point, b: _Point, ds: float) -> _Point:
    """The grazing orbit between ``a`` and ``b`` (one of them in the gap) on the gap side's piece continued past
    the ring without its force (smooth there; at zero penetration the law's force is zero, so its grazing orbit is
    the branch's): secant steps on the penetration along that point's tangent (the first slope the tangent's
    own), each a corrected orbit, to 1e-12 δ0; at most 12, the nearest returned."""
    base, sgn = (a, 1.0) if a.pen < 0.0 else (b, -1.0)
    d0, slope = base.hs.clearance_m, sgn * _pen_slope(tr, base)
    s, pen, best = 0.0, base.pen, base
    tr.free = True
    try:
        for _ in range(12):
            if abs(pen) <= 1e-12 * d0 or slope == 0.0:
                break
            s_new = s - pen / slope
            got = tr.correct(base.y + sgn * s_new * base.tau, base.tau)
            if got is None:
                break
            p = _make_point(tr, got, base.tau)
            slope, s, pen = (p.pen - pen) / (s_new - s), s_new, p.pen
            best = p if abs(p.pen) < abs(best.pen) else best
    finally:
        tr.free = False
    return best


def _onto_grazing(tr, c: _Point, prev: _Point) -> _Point:
    """``c`` moved along its own piece of the curve to within 1e-12 δ0 of grazing (secant steps on the penetration
    with ``prev``, on the same piece, along ``c``'s tangent, each a corrected orbit on ``c``'s side, halved where it
    crosses; at most 8)."""
    d0 = c.hs.clearance_m
    for _ in range(8):
        if abs(c.pen) <= 1e-12 * d0:
            break
        slope = (c.pen - prev.pen) / float(np.linalg.norm(c.y - prev.y))
        if slope == 0.0:
            break
        s, new = -c.pen / slope, None
        for _ in range(6):                  # a step that crosses to the other piece (or fails) is halved
            got = tr.correct(c.y + s * c.tau, c.tau)
            new = None if got is None else _make_point(tr, got, c.tau)
            if new is not None and new.pen * c.pen > 0.0:
                break
            s, new = 0.5 * s, None
        if new is None or abs(new.pen) >= abs(c.pen):
            break
        prev, c = c, new
    return c
