"""The flexible family ``foundation-spline``: the Winkler foundation law times a monotone spline correction.

``log P(Δr) = log(R l s(Δr)) + c(log Δr)`` with ``s`` the foundation shape ``e (ε − sin ε cos ε)``
(:func:`contact.calibrate.families.foundation_shape`) and ``c`` a cubic Hermite spline of the fitted points
``(log Δr_k, log P_k − log(R l s(Δr_k)))``. Its knot slopes follow one of two rules, the one whose spline predicts
the interior knots better, each left out in turn (:func:`leave_one_out`, the points alone decide):

- the not-a-knot cubic spline's through the same points (de Boor 1978: twice continuously differentiable, fourth
  order on uneven knots as well, so a grid refined where the curve bends stays accurate next to the refinement);
- the Fritsch–Carlson (PCHIP) ones (Fritsch & Carlson 1980: the harmonic mean of the neighbouring secants,
  one-sided three-point slopes at the ends, limited to keep their sign): third order, and on uneven knots its
  slope next to a short interval leans to that interval's secant, but it does not overshoot near a noisy end.

Measured: on the 12 knots of issue 37's generated pair 29 (seed 2755664993, a sharp stiffening) the not-a-knot
slopes interpolate to 0.25 % at the midpoints, PCHIP's to 0.51 % (leave-one-out 2.7 % against 4.1 %); on the 20 mm
ring's 13 zero-tilt training points (reports/published/law-tilt-correction.md) PCHIP's leave-one-out is 0.30 %
against 0.39 % and its verification points are within their bounds, the not-a-knot slopes 0.056 % beyond one (at
0.593 µm, whose FEM level sequence is not asymptotic). A rule whose correction would make the force fall is not
taken. Beyond the end knots ``c`` goes on as a
straight line of its end slope: the law is the foundation law times a power of Δr there (value and slope
matched, so the force and its derivative are continuous). The foundation shape's logarithmic slope lies in
``[1, 1.5]``, so a correction whose slope stays above −1 everywhere gives a force that rises with Δr: checked at
fit time (:func:`rises`), and a law file that falls is refused on load
(:func:`contact.calibrate.validate.check_behaviour`).

Flexible by construction: any rising, smooth force curve through the points is followed to the spline's
interpolation error; the foundation shape only sets the ends' limits (the ``Δr^1.5`` onset of a thin ring's
contact, ``Δr^1`` far beyond the clearance) and takes the bulk of the curvature, so the correction is gentle.

The compiled kernel evaluates the same spline (law code 3, ``contact._kernel``); the knots are stored in the
law file as scalar parameters ``knot_count`` and ``log_penetration_NN`` / ``log_correction_NN`` /
``log_slope_NN`` (NN from 00), at most :data:`MAX_KNOTS`; with more points, :data:`MAX_KNOTS` of them spread
over the range are the knots and the others are held out.
"""
from __future__ import annotations

import math

import numpy as np

from contact.errors import InputError
from contact.loose_support import SPLINE_MAX_KNOTS

FAMILY = "foundation-spline"
#: the largest number of knots (the compiled kernel's parameter slots hold this many)
MAX_KNOTS = SPLINE_MAX_KNOTS


def pchip_slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Fritsch–Carlson knot slopes ``dy/dx`` of the monotone cubic Hermite interpolant (x rising, >= 2 knots)."""
    h = np.diff(x)
    d = np.diff(y) / h
    n = x.size
    m = np.zeros(n)
    if n == 2:
        return np.full(2, d[0])
    for k in range(1, n - 1):
        if d[k - 1] * d[k] > 0:
            w1, w2 = 2 * h[k] + h[k - 1], h[k] + 2 * h[k - 1]
            m[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k])
    m[0] = _end_slope(h[0], h[1], d[0], d[1])
    m[-1] = _end_slope(h[-1], h[-2], d[-1], d[-2])
    return m


def _end_slope(h0: float, h1: float, d0: float, d1: float) -> float:
    """One-sided three-point end slope, limited as scipy's PchipInterpolator does."""
    m = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1)
    if np.sign(m) != np.sign(d0):
        return 0.0
    if np.sign(d0) != np.sign(d1) and abs(m) > abs(3 * d0):
        return 3 * d0
    return float(m)


def hermite(x: np.ndarray, y: np.ndarray, m: np.ndarray, xq) -> tuple[np.ndarray, np.ndarray]:
    """Value and slope of the cubic Hermite spline (knots x, values y, slopes m) at xq; linear beyond the ends."""
    xq = np.asarray(xq, dtype=float)
    k = np.clip(np.searchsorted(x, xq, side="right") - 1, 0, x.size - 2)
    h = x[k + 1] - x[k]
    t = (xq - x[k]) / h
    t2, t3 = t * t, t * t * t
    v = ((2 * t3 - 3 * t2 + 1) * y[k] + (t3 - 2 * t2 + t) * h * m[k] + (-2 * t3 + 3 * t2) * y[k + 1]
         + (t3 - t2) * h * m[k + 1])
    dv = ((6 * t2 - 6 * t) * y[k] / h + (3 * t2 - 4 * t + 1) * m[k] + (-6 * t2 + 6 * t) * y[k + 1] / h
          + (3 * t2 - 2 * t) * m[k + 1])
    lo, hi = xq < x[0], xq > x[-1]
    v = np.where(lo, y[0] + m[0] * (xq - x[0]), np.where(hi, y[-1] + m[-1] * (xq - x[-1]), v))
    dv = np.where(lo, m[0], np.where(hi, m[-1], dv))
    return v, dv


def knot_indices(n: int) -> np.ndarray:
    """The points (of n, sorted) that are knots: all of them up to :data:`MAX_KNOTS`, else that many spread."""
    if n <= MAX_KNOTS:
        return np.arange(n)
    return np.unique(np.round(np.linspace(0, n - 1, MAX_KNOTS)).astype(int))


def unsure_intervals(pen_m: np.ndarray, force_N: np.ndarray, base_N: np.ndarray) -> np.ndarray:
    """Each interval's doubt (-): at the geometric midpoint of each pair of neighbouring points (Δr > 0 rising,
    forces > 0, the foundation base there, N), the relative difference between two interpolants of the correction
    through the same points, the PCHIP one (:func:`pchip_slopes`, third order) and the not-a-knot cubic spline
    (fourth order, this family's own where it rises). They disagree by about the less accurate one's error where
    the curve bends more than the knots resolve (a stiffening that the foundation base does not follow), which
    bounds the family's there; where they agree the data is resolved. Needs >= 4 points (else zeros)."""
    from scipy.interpolate import CubicSpline

    x = np.log(pen_m)
    y = np.log(force_N) - np.log(base_N)
    if x.size < 4:
        return np.zeros(max(x.size - 1, 0))
    xm = 0.5 * (x[:-1] + x[1:])
    pchip = hermite(x, y, pchip_slopes(x, y), xm)[0]
    return np.abs(np.expm1(pchip - CubicSpline(x, y, bc_type="not-a-knot")(xm)))


def refinement(pen_m: np.ndarray, force_N: np.ndarray, base_N: np.ndarray, doubt_rel: float,
               max_points: int = MAX_KNOTS) -> np.ndarray:
    """Penetrations (m) to add so that the spline resolves the curve: two per interval whose doubt
    (:func:`unsure_intervals`) exceeds ``doubt_rel``, at the interval's geometric thirds (so its geometric midpoint,
    where a held-out check sits, lies in the middle of the middle third), the most doubtful intervals first, as many
    as keep the total within ``max_points``. Sorted; empty when every interval is resolved."""
    doubt = unsure_intervals(pen_m, force_N, base_N)
    room = max(0, (max_points - pen_m.size) // 2)
    worst = [int(i) for i in np.argsort(-doubt, kind="stable") if doubt[i] > doubt_rel][:room]
    x = np.log(pen_m)
    new = [math.exp(x[i] + f * (x[i + 1] - x[i])) for i in worst for f in (1 / 3, 2 / 3)]
    return np.sort(np.array(new, dtype=float))


def parameters(pen_m: np.ndarray, force_N: np.ndarray, base_N: np.ndarray) -> dict:
    """The family's parameters from points (Δr > 0 rising, forces > 0) and the foundation base there (N)."""
    idx = knot_indices(pen_m.size)
    x = np.log(pen_m[idx])
    y = np.log(force_N[idx]) - np.log(base_N[idx])
    if x.size < 2 or np.any(np.diff(x) <= 0):
        raise InputError(f"{FAMILY}: need >= 2 distinct penetrations, got {x.size}")
    rules = sorted((smooth_slopes, pchip_slopes), key=lambda rule: leave_one_out(x, y, rule))
    for rule in rules:
        out = _stored(x, y, rule(x, y))
        if rises(out):
            break
    return out


def leave_one_out(x: np.ndarray, y: np.ndarray, rule) -> float:
    """The largest error (in y) of the Hermite spline with knot slopes ``rule(x, y)`` at each interior knot, that knot
    left out (0 with fewer than 4 knots: the spline of the others is then a straight line or parabola either way)."""
    if x.size < 4:
        return 0.0
    worst = 0.0
    for k in range(1, x.size - 1):
        keep = np.arange(x.size) != k
        xs, ys = x[keep], y[keep]
        worst = max(worst, abs(float(hermite(xs, ys, rule(xs, ys), x[k:k + 1])[0][0]) - y[k]))
    return worst


def smooth_slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Knot slopes ``dy/dx`` of the not-a-knot cubic spline through the knots (a straight line through 2, the
    parabola through 3)."""
    from scipy.interpolate import CubicSpline

    if x.size == 2:
        return np.full(2, (y[1] - y[0]) / (x[1] - x[0]))
    return CubicSpline(x, y, bc_type="not-a-knot")(x, 1)


def _stored(x: np.ndarray, y: np.ndarray, m: np.ndarray) -> dict:
    """The law file's parameters of knots ``x``, values ``y``, slopes ``m``."""
    out = {"knot_count": float(x.size)}
    for k in range(x.size):
        out[f"log_penetration_{k:02d}"] = float(x[k])
        out[f"log_correction_{k:02d}"] = float(y[k])
        out[f"log_slope_{k:02d}"] = float(m[k])
    return out


def knots(params: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(x, y, m)`` of the stored parameters (:func:`parameters`)."""
    n = int(params["knot_count"])
    return tuple(np.array([params[f"{name}_{k:02d}"] for k in range(n)], dtype=float)
                 for name in ("log_penetration", "log_correction", "log_slope"))


def correction(params: dict, pen_m: np.ndarray) -> np.ndarray:
    """``exp(c(log Δr))`` at Δr > 0 (-)."""
    x, y, m = knots(params)
    return np.exp(hermite(x, y, m, np.log(pen_m))[0])


def rises(params: dict) -> bool:
    """True if the correction's slope stays above −1 on every interval and both tails (then the force rises)."""
    x, y, m = knots(params)
    if m[0] <= -1 or m[-1] <= -1:
        return False
    t = np.linspace(0.0, 1.0, 33)
    xs = np.concatenate([x[k] + t * (x[k + 1] - x[k]) for k in range(x.size - 1)])
    return bool(np.all(hermite(x, y, m, xs)[1] > -1.0))


def kernel_slots(params: dict) -> tuple:
    """The kernel's spline slots: ``knot_count`` then x, y, m each padded to :data:`MAX_KNOTS` (``contact._kernel``)."""
    x, y, m = knots(params)
    pad = np.zeros(MAX_KNOTS - x.size)
    return (float(x.size), *np.concatenate([x, pad]), *np.concatenate([y, pad]), *np.concatenate([m, pad]))


def check_parameters(params: dict) -> str | None:
    """What is wrong with stored spline parameters (a sentence), or None."""
    n = params.get("knot_count")
    if not isinstance(n, (int, float)) or isinstance(n, bool) or not float(n).is_integer() \
            or not 2 <= n <= MAX_KNOTS:
        return f"knot_count = {n!r}: must be a whole number in [2, {MAX_KNOTS}]"
    for name in ("log_penetration", "log_correction", "log_slope"):
        for k in range(int(n)):
            v = params.get(f"{name}_{k:02d}")
            if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
                return f"{name}_{k:02d} = {v!r}: must be a finite number"
    x = knots(params)[0]
    if np.any(np.diff(x) <= 0):
        return "log_penetration_NN must rise strictly"
    return None
