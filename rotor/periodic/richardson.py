"""Orbits of the continuous-time rotor from a branch of the scheme: Richardson extrapolation in the step.

The production scheme (Newmark average acceleration, the trapezoidal rule) is symmetric, so the error of
its periodic orbits expands in even powers of the step: ``y_N = y* + C h² + O(h⁴)`` with ``h = 2π/(Ω N)``
(on the Jeffcott rotor the whole error is the frequency warping ``Ω' = Ω tan(π/N)/(π/N) = Ω (1 + π²/(3N²) +
…)``, :mod:`rotor.periodic.jeffcott`). Each point ``y_N = (x, λ)`` of a branch computed with ``N`` steps per
revolution is corrected once more with ``2N`` steps on the hyperplane that fixes the unknown the branch moves
fastest in there (the largest component of its unit tangent, scaled; the parameter away from folds, a state
component at them, so folds are no harder than other points), and the two are combined,
``y* ≈ (4 y_2N − y_N)/3``, an O(h⁴) estimate of the continuous-time orbit (Richardson 1911; Hairer, Nørsett &
Wanner 1993, *Solving Ordinary Differential Equations I*, §II.9 on extrapolation of symmetric methods).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from rotor.periodic.continuation import Branch, ContinuationOptions, Problem, _correct, _Evaluator


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
    ev_n, ev_2n = _Evaluator(problem, s, lam_scale), _Evaluator(fine, s, lam_scale)
    n = len(branch.points)
    lam, lam2 = np.full(n, np.nan), np.full(n, np.nan)
    x, x2 = np.full((n, len(s)), np.nan), np.full((n, len(s)), np.nan)
    ok = np.zeros(n, bool)
    for i, p in enumerate(branch.points):
        y = np.concatenate([p.state / s, [p.parameter / lam_scale]])
        _, J, _ = ev_n(p.state, p.parameter)
        tau = np.linalg.svd(J)[2][-1]          # the branch's direction: the null vector of [M − I, ∂R/∂λ]
        e = np.zeros(len(y))
        e[int(np.argmax(np.abs(tau)))] = 1.0
        got = _correct(ev_2n, y, e, opts)
        if got is None:
            continue
        y2 = got[0]
        ok[i] = True
        yr = (4.0 * y2 - y) / 3.0
        lam[i], x[i] = yr[-1] * lam_scale, yr[:-1] * s
        lam2[i], x2[i] = y2[-1] * lam_scale, y2[:-1] * s
    return ExtrapolatedBranch(lam, x, lam2, x2, ok)
