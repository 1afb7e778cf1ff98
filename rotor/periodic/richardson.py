"""Orbits of the continuous-time rotor from a branch of the scheme: Richardson extrapolation in the step.

The production scheme (Newmark average acceleration, the trapezoidal rule) is symmetric, so the error of
its periodic orbits expands in even powers of the step: ``y_N = y* + C h² + O(h⁴)`` with ``h = 2π/(Ω N)``
(on the Jeffcott rotor the whole error is the frequency warping ``Ω' = Ω tan(π/N)/(π/N) = Ω (1 + π²/(3N²) +
…)``, :mod:`rotor.periodic.jeffcott`). Each point ``y_N = (x, λ)`` of a branch computed with ``N`` steps per
revolution is corrected once more with ``2N`` steps on the hyperplane that fixes the unknown the branch moves
fastest in there (the largest component of the secant through its neighbours, scaled: the parameter away
from folds, a state component at them, so folds are no harder than other points), by a chord Newton (the ``2N`` Jacobian of the first
iterate kept: the ``N`` orbit is within the step's O(h²) of the ``2N`` one), and the two are combined,
``y* ≈ (4 y_2N − y_N)/3``, an O(h⁴) estimate of the continuous-time orbit (Richardson 1911; Hairer, Nørsett &
Wanner 1993, *Solving Ordinary Differential Equations I*, §II.9 on extrapolation of symmetric methods).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from contact.errors import ConvergenceError, InputError, OutsideDomainError
from rotor.periodic.branch_types import Branch, ContinuationOptions, Evaluator, Problem
from rotor.periodic.shooting import min_norm_step

#: most chord iterations of a 2N orbit
CHORD_MAX_ITER = 15


@dataclass(frozen=True)
class ExtrapolatedBranch:
    """``parameters`` (λ, the problem's unit) and ``states`` (reduced state at phase 0) of the extrapolated
    orbits, ``fine_parameters``/``fine_states`` the ``2N`` orbits they come from, and ``converged`` per point
    (False: the ``2N`` corrector failed; that point's entries are NaN)."""

    parameters: np.ndarray
    states: np.ndarray
    fine_parameters: np.ndarray
    fine_states: np.ndarray
    converged: np.ndarray


def extrapolate_branch(problem: Problem, branch: Branch, *, scales, lam_scale: float,
                       options: ContinuationOptions | None = None) -> ExtrapolatedBranch:
    """Richardson-extrapolate every point of ``branch`` (computed on ``problem``, ``N`` steps per revolution) with
    its ``2N`` orbit (see the module docstring). ``scales``, ``lam_scale``: the scaling of the branch's unknowns."""
    opts = options or ContinuationOptions()
    fine = replace(problem, steps_per_rev=2 * problem.steps_per_rev)
    s = np.asarray(scales, float)
    ev_2n = Evaluator(fine, s, lam_scale)
    pts = branch.points
    n = len(pts)
    ys = [np.concatenate([p.state / s, [p.parameter / lam_scale]]) for p in pts]
    lam, lam2 = np.full(n, np.nan), np.full(n, np.nan)
    x, x2 = np.full((n, len(s)), np.nan), np.full((n, len(s)), np.nan)
    ok = np.zeros(n, bool)
    for i in range(n):
        y = ys[i]
        e = np.zeros(len(y))
        if n == 1:
            e[-1] = 1.0
        else:                                   # the unknown the branch moves fastest in: its neighbours' secant
            e[int(np.argmax(np.abs(ys[min(i + 1, n - 1)] - ys[max(i - 1, 0)])))] = 1.0
        y2 = _chord(ev_2n, y, e, opts)
        if y2 is None:
            continue
        ok[i] = True
        yr = (4.0 * y2 - y) / 3.0
        lam[i], x[i] = yr[-1] * lam_scale, yr[:-1] * s
        lam2[i], x2[i] = y2[-1] * lam_scale, y2[:-1] * s
    return ExtrapolatedBranch(lam, x, lam2, x2, ok)


def _chord(ev: Evaluator, y0, e, opts: ContinuationOptions):
    """The orbit of ``ev``'s problem on the hyperplane ``e·(y − y0) = 0`` near the scaled ``y0``: Newton with the
    Jacobian of the first iterate kept (chord). Returns the scaled ``y`` or None."""
    y, J = np.asarray(y0, float).copy(), None
    for _ in range(CHORD_MAX_ITER):
        try:
            R, Jn, _ = ev(y[:-1] * ev.s, y[-1] * ev.ls, jacobian=J is None)
        except (OutsideDomainError, ConvergenceError, InputError):
            return None
        J = Jn if J is None else J
        res = float(np.max(np.abs(R)))
        if not np.isfinite(res):
            return None
        dy, _ = min_norm_step(np.vstack([J, e[None, :]]), -np.concatenate([R, [e @ (y - y0)]]), opts.rcond)
        if res < opts.tol and np.max(np.abs(dy)) < 1e3 * opts.tol:
            return y
        y = y + dy
    return None
