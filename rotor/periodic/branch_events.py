"""Bifurcations between consecutive points of a branch (:mod:`rotor.periodic.continuation`).

A fold where the parameter component of the tangent changes sign and the secants into and out of the pair
confirm the turn (:func:`confirmed_folds`); period doubling, Neimark–Sacker, and branch points (a real
multiplier through +1 with no turn: a pitchfork) where the count of multipliers outside the unit circle changes
(:func:`rotor.periodic.floquet.crossing`). Each is located by regula falsi on the arclength between the two
points, on its test quantity (``dλ/ds``, or ``|μ| − 1`` of the largest multiplier of the crossing kind), every
trial a corrected orbit.
"""
from __future__ import annotations

import numpy as np

from rotor.periodic.branch_types import Bifurcation, BranchPoint
from rotor.periodic.corrector import correct, make_point, neutral_rows, unit_tangent
from rotor.periodic.floquet import crossing


def test_quantity(kind: str, pt: BranchPoint) -> float:
    """The quantity that changes sign at a bifurcation of ``kind``: ``dλ/ds`` (fold) or ``|μ| − 1`` of the
    largest multiplier of that kind (real negative: period doubling; complex: Neimark–Sacker; real positive:
    branch point)."""
    if kind == "fold":
        return pt.dlam_ds
    mu = pt.floquet.multipliers
    real = np.abs(mu.imag) <= 1e-9 * np.maximum(1.0, np.abs(mu))
    neutral = np.abs(mu - 1.0) <= pt.floquet.tol
    if kind == "period_doubling":
        pick = mu[real & (mu.real < 0)]
    elif kind == "branch_point":
        pick = mu[real & (mu.real > 0) & ~neutral]
    else:
        pick = mu[~real]
    return float(np.abs(pick).max()) - 1.0 if len(pick) else -1.0


def fold_estimate(a: BranchPoint, b: BranchPoint, ds: float, lam_scale: float) -> float:
    """The parameter at the turn between ``a`` and ``b`` a step ``ds`` apart (scaled), with ``dλ/ds`` taken as
    linear in the arclength from ``a.dlam_ds`` to ``b.dlam_ds``: ``λ_a + λ_s f_a² ds / (2 (f_a − f_b))``, the
    vertex of the parabola ``λ(σ)`` (beyond both points, where a linear interpolation of λ would fall between
    them)."""
    fa, fb = a.dlam_ds, b.dlam_ds
    return a.parameter + lam_scale * fa * fa * ds / (2.0 * (fa - fb))


def refine(ev, y0, tau0, ds: float, kind: str, a: BranchPoint, b: BranchPoint, opts, phase, n_iter: int = 8) -> float:
    """Parameter of a bifurcation between ``a`` (at ``y0``, tangent ``tau0``) and ``b`` (a step ``ds`` on):
    regula falsi (Illinois) on the arclength ``σ`` in ``[0, ds]``, each trial corrected on the hyperplane
    ``τ0·(y − y0 − σ τ0) = 0``, until the bracket is below 10⁻⁶ ds; if a corrector fails, linear interpolation
    (a fold: :func:`fold_estimate`, the turning point itself lies beyond both points). A trial that landed on another
    stretch of the branch counts as failed (:func:`_elsewhere`)."""
    lo, hi, flo, fhi = 0.0, ds, test_quantity(kind, a), test_quantity(kind, b)
    lam = b.parameter
    side = 0
    for _ in range(n_iter):
        if flo == fhi:
            break
        sig = lo - flo * (hi - lo) / (fhi - flo)
        got = correct(ev, y0 + sig * tau0, tau0, opts, phase, y0)
        if got is not None and _elsewhere(got[0], y0 + sig * tau0, ds, kind, a, b, ev.ls):
            got = None                    # corrected onto another stretch of the branch: as if it had failed
        if got is None:
            if kind == "fold":
                return fold_estimate(a, b, ds, ev.ls)
            return a.parameter + (b.parameter - a.parameter) * min(max(-flo / (fhi - flo), 0.0), 1.0)
        y, J, M, it, res = got
        pt = make_point(ev, y, J, M, it, res, unit_tangent(J, tau0, opts.rcond, neutral_rows(J)), opts)
        lam, f = pt.parameter, test_quantity(kind, pt)
        if f * flo > 0:
            lo, flo = sig, f
            fhi = fhi / 2 if side == -1 else fhi
            side = -1
        else:
            hi, fhi = sig, f
            flo = flo / 2 if side == 1 else flo
            side = 1
        if hi - lo < 1e-6 * ds:
            break
    return float(lam)


def _elsewhere(y, y_pred, ds: float, kind: str, a: BranchPoint, b: BranchPoint, lam_scale: float) -> bool:
    """Whether a refinement trial corrected to ``y`` (scaled) from ``y_pred`` landed on another stretch of the branch:
    farther than ``ds`` from its predictor, or (a crossing, not a fold, which may lie beyond both points) with its
    parameter outside ``a``–``b`` by more than their distance. Measured on Table 4 (run at commit 9feddee, unstable
    orbits): crossings of 17 452-17 512 and 15 850-15 913 rpm placed at 17 781 and 16 073 rpm."""
    if np.linalg.norm(y - y_pred) > ds:
        return True
    lo, hi = sorted((a.parameter, b.parameter))
    lam = y[-1] * lam_scale
    return kind != "fold" and not lo - (hi - lo) <= lam <= hi + (hi - lo)


def bifurcations_between(ev, prev: BranchPoint, new: BranchPoint, index: int, y0, tau0, ds, opts, phase) -> list:
    """Bifurcations between ``prev`` and ``new``. A real multiplier through +1 without a turn of the
    parameter is a branch point (a pitchfork: symmetry breaking, e.g. a planar orbit starting to whirl).
    Across a restart (``new.restarted``) the tangents of two pieces of the map are not compared (no fold), and
    a multiplier crossing is placed by linear interpolation of its test quantity (no corrector joins them).

    A multiplier crossing between two points whose orbits differ in their switches (the end-face mode changes
    per period, :attr:`BranchPoint.events`) is a discontinuous bifurcation (Leine &
    van Campen 2002): where a stick/slip switch appears or leaves, the monodromy changes by a saltation and its
    multipliers jump across the unit circle instead of passing through it; it is reported as kind
    ``"discontinuous"`` with the crossing's kind and both sides in ``detail``, not as a failure."""
    fold = prev.dlam_ds * new.dlam_ds < 0 and not new.restarted
    kinds = ["fold"] if fold else []
    kind = crossing(prev.floquet, new.floquet)
    if kind == "fold" and not fold:
        kind = "branch_point"
    if kind is not None and kind not in kinds:
        kinds.append(kind)
    switched = prev.events >= 0 and new.events >= 0 and prev.events != new.events
    out = []
    for k in kinds:
        lam = (interpolated(k, prev, new) if new.restarted
               else refine(ev, y0, tau0, ds, k, prev, new, opts, phase))
        if k != "fold" and switched:
            detail = (f"{k.replace('_', ' ')}: largest |multiplier| {prev.floquet.spectral_radius:.4g} -> "
                      f"{new.floquet.spectral_radius:.4g}, switches per period {prev.events} -> {new.events}"
                      + (" (across a restart)" if new.restarted else ""))
            out.append(Bifurcation("discontinuous", index, lam, new.floquet.critical, detail))
        else:
            out.append(Bifurcation(k, index, lam, new.floquet.critical))
    return out


def interpolated(kind: str, a: BranchPoint, b: BranchPoint) -> float:
    """Parameter where the test quantity of ``kind`` crosses zero on the straight line from ``a`` to ``b``."""
    fa, fb = test_quantity(kind, a), test_quantity(kind, b)
    w = 0.5 if fa == fb else min(max(-fa / (fb - fa), 0.0), 1.0)
    return a.parameter + w * (b.parameter - a.parameter)


def confirmed_folds(points, bifs, open_end: bool = False) -> list:
    """The bifurcations with each fold kept only where the branch truly turns: the parameter components of
    the tangents at points ``i − 1`` and ``i`` have opposite signs *and* the parameter moved along each of them,
    into ``i − 1`` (from ``i − 2``; the first point has no secant in) and out of ``i`` (to ``i + 1``). A fold
    between a branch's last two points, or one the secants contradict (a tangent turned by a switch, the
    next corrector stepping on in the old direction), is not reported, except with ``open_end``: the branch
    stopped where a watch saw its next predictor, along the last point's tangent, cross to another piece of the
    map (a grazing, :mod:`rotor.periodic.grazing`, whose crossing goes on that way), so the last point's tangent
    is the secant out of it. Measured on the rotor 5 of rotor/periodic/jeffcott_scene.random_family(2276323539)
    up: its fold (2 034.4 rpm) lies 61 rpm above its grazing fold; the segment's last two points straddled it
    (2 032.9 and 2 033.7 rpm, the second unstable) and the crossing went from there to the grazing fold, so the
    fold was dropped and the middle branch not counted."""
    lam = [p.parameter for p in points]
    out = []
    for b in bifs:
        i = b.index
        if b.kind == "fold":
            into = i < 2 or (lam[i - 1] - lam[i - 2]) * points[i - 1].dlam_ds > 0
            onward = (open_end and i == len(points) - 1) or (
                i + 1 < len(points) and (lam[i + 1] - lam[i]) * points[i].dlam_ds > 0)
            if not (into and onward) or points[i].restarted or (i + 1 < len(points) and points[i + 1].restarted):
                continue
        out.append(b)
    return out

