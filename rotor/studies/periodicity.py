"""Is a once-per-revolution sequence of states periodic? The steady-state detector of the study points.

:func:`poincare_convergence` judges the Poincaré samples of :func:`rotor.studies.steady_state.steady_state`
(the lateral displacements of the primary stations at the same phase of every revolution). A response is
periodic with period ``m`` revolutions when the samples repeat every ``m`` revolutions within ``tol`` of the
peak-to-peak dynamic amplitude *and* what may still be left of a transient is below ``tol`` too. That second
part is estimated in two ways, and the orbit is accepted when either estimate is below ``tol``:

``decay``
    The per-period differences ``d_k`` of a real transient mode fall geometrically, ``d_k ≈ d_0 ρ^k``; what is
    left after the last sample is then ``d_last ρ/(1 − ρ)``, ``ρ`` fitted on ``log d`` over the window and clipped
    to ``[0, RHO_MAX]``. Quick for a transient that decays, but a plateau of differences (no decay measured:
    ρ clipped at ``RHO_MAX``) is multiplied by ``1/(1 − RHO_MAX)`` = 1 000.
``span``
    For any single transient mode, real or complex (``P_k − P* = Re(c λ^k)``, ``|λ| = ρ``), the change over a
    span of ``j`` revolutions is ``D_j = |λ^{−j} − 1| · remaining`` and ``|λ^{−j} − 1| ≥ ρ^{−j} − 1``: so
    ``remaining ≤ D_j / (RHO_MAX^{−j} − 1)`` for every mode that decays at least as fast as ``RHO_MAX`` per
    revolution (the same bound on the slowest transient as the ``decay`` estimate's clip). The spans are the
    longest whole number of periods in the samples up to :data:`SPAN_MAX` revolutions and half of it; the
    largest bound counts, and each ``D_j`` itself must be below ``tol``. A stuck linear state whose samples
    scatter by a few 1e-6 of its amplitude without drifting (no decay to measure) passes here, and so does a
    decaying transient that turns around the fixed point, whose differences do not add up.

Both rules need no model: samples in, verdict out (the caller is rotor/studies/steady_state.py).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: the slowest decay of a transient per revolution that the detector allows for (–)
RHO_MAX = 0.999
#: the longest span (revolutions) of the ``span`` estimate
SPAN_MAX = 512


@dataclass(frozen=True)
class Convergence:
    """Outcome of the Poincaré test on a sequence of once-per-revolution samples.

    converged : bool; period : int, in revolutions (0 if not converged);
    change : float, largest relative difference ``|P_k − P_{k−m}|/A`` over the window (–);
    remaining : float, estimate of the transient still to decay (relative, –): the smaller of the ``decay``
    and ``span`` estimates (module docstring);
    ratio : float, fitted decay ratio of the differences per revolution (–);
    rule : str, which estimate accepted the orbit ('decay', 'span'; '' if not converged).
    """

    converged: bool
    period: int
    change: float
    remaining: float
    ratio: float
    rule: str = ""


def span_remaining(P, scale: float, period: int) -> tuple[float, float]:
    """``(largest relative change over the spans, bound on the remaining transient)`` of the ``span`` rule.

    Parameters
    ----------
    P : (k, c) array
        Poincaré samples (m).
    scale : float
        Peak-to-peak dynamic amplitude (m).
    period : int
        Period tried (revolutions); the spans are whole numbers of it.

    Returns
    -------
    (float, float)
        ``max_j D_j`` and ``max_j D_j / (RHO_MAX^{−j} − 1)`` (both relative to ``scale``, –); ``inf`` when the
        samples hold fewer than two periods.
    """
    m = int(period)
    top = (min(P.shape[0] - 1, SPAN_MAX) // m) * m
    spans = sorted({top, (top // 2 // m) * m} - {0})
    if not spans:
        return math.inf, math.inf
    D = [float(np.abs(P[-1] - P[-1 - j]).max() / scale) for j in spans]
    return max(D), max(x / (RHO_MAX ** -j - 1.0) for x, j in zip(D, spans))


def poincare_convergence(P, scale: float, *, tol: float = 1e-4, max_period: int = 8,
                         window: int | None = None) -> Convergence:
    """Test once-per-revolution samples for a periodic steady state.

    Parameters
    ----------
    P : (k, c) array
        Poincaré samples (k revolutions, c channels, m).
    scale : float
        Peak-to-peak dynamic amplitude the tolerance is relative to (m).
    tol : float
        Relative tolerance (–).
    max_period : int
        Periods ``m = 1..max_period`` (revolutions) are tried, smallest first.
    window : int, optional
        Revolutions of differences examined (default ``max(16, 4 m)``).

    Returns
    -------
    Convergence
        For the smallest period that passes; otherwise the figures of the one-revolution test.

    Notes
    -----
    The period-``m`` differences over the window must be below ``tol``, and the remaining transient by the
    ``decay`` or the ``span`` estimate (module docstring) too. A subharmonic (``m > 1``) needs sustained
    one-revolution differences, larger than ``10 tol`` and not decaying: otherwise it is a transient near a
    sub-multiple of f that happens to pass the ``m``-revolution test first.
    """
    P = np.asarray(P, dtype=float)
    if P.ndim == 1:
        P = P[:, None]
    if not (scale > 0 and math.isfinite(scale)):
        # no dynamic motion at all: exactly steady
        if np.all(np.isfinite(P)) and P.shape[0] >= 2 and np.ptp(P, axis=0).max() == 0.0:
            return Convergence(True, 1, 0.0, 0.0, 0.0, "decay")
        return Convergence(False, 0, math.inf, math.inf, 1.0)
    best = Convergence(False, 0, math.inf, math.inf, 1.0)
    rho1, change1 = None, 0.0
    for m in range(1, int(max_period) + 1):
        w = window if window is not None else max(16, 4 * m)
        if P.shape[0] < w + m:
            break
        d = np.abs(P[m:] - P[:-m]).max(axis=1)[-w:] / scale
        change = float(d.max())
        k = np.arange(d.size, dtype=float)
        logd = np.log(np.maximum(d, 1e-300))
        slope = float(np.polyfit(k, logd, 1)[0]) if d.size > 2 else 0.0
        rho = min(max(math.exp(min(slope, 50.0)), 0.0), RHO_MAX)
        # envelope of the last few differences (an oscillating transient has zeros in d)
        last = float(d[-max(m, 3):].max())
        decay = last * rho / (1.0 - rho)
        span_change, span = span_remaining(P, scale, m)
        rule = "decay" if decay <= tol else "span" if span <= tol and span_change <= tol else ""
        remaining = min(decay, span) if span_change <= tol else decay
        if m == 1:
            rho1, change1 = rho, change
        ok = change <= tol and bool(rule)
        if ok and m > 1 and (rho1 is None or rho1 ** w < 0.5 or change1 < 10 * tol):
            ok = False
        c = Convergence(ok, m if ok else 0, change, remaining, rho, rule if ok else "")
        if c.converged:
            return c
        if m == 1:
            best = Convergence(False, 0, change, remaining, rho)
    return best
