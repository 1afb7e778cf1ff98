"""The check of a period map's monodromy: central differences of the whole map, and the error in a scaled norm.

The reference of tests/rotor/dynamics/test_monodromy_random_speeds.py and benchmarks/bench_monodromy_random.py:
each state component is perturbed by ``h`` of its scale (its largest magnitude over the period, at least 1e-6 of
its block's), both ways, and the central differences at ``2h`` and ``h`` are Richardson-extrapolated; the same at
``h`` and ``h/2`` tells whether the map is smooth at that scale (a threshold of the map within ``h`` of the state
makes the two differ by O(1), rotor/dynamics/period_map_events.py).
"""
from __future__ import annotations

import numpy as np

from rotor.dynamics.period_map import period_map, reduced_state


def state_scales(pm, trajectory) -> np.ndarray:
    """Each reduced state component's largest magnitude over a recorded period, at least 1e-6 of its block's
    (displacements, velocities) largest: the scales of :func:`central_differences` and :func:`scaled_error`."""
    s = np.abs(reduced_state(pm, trajectory.q, trajectory.v)).max(axis=0)
    for part in (slice(0, pm.nr), slice(pm.nr, 2 * pm.nr)):
        s[part] = np.maximum(s[part], 1e-6 * s[part].max())
    return s


def _stencil(pm, state, t0_s: float, n_steps: int, modes0, scales, rel: float) -> dict:
    """The map's end states with column ``j`` of the state moved by ``k · rel · scales[j]``, ``k`` in ±2, ±1, ±1/2
    (``{k: (n, n) array, column j the end state}``; key 0: the unmoved end state in every column)."""
    out = {k: np.zeros((state.size, state.size)) for k in (2.0, 1.0, 0.5, -0.5, -1.0, -2.0)}
    out[0.0] = np.repeat(period_map(pm, state, t0_s, n_steps, modes0=modes0, jacobian=False).state[:, None],
                         state.size, axis=1)
    for j in range(state.size):
        for k in (2.0, 1.0, 0.5, -0.5, -1.0, -2.0):
            x = state.copy()
            x[j] += k * rel * scales[j]
            out[k][:, j] = period_map(pm, x, t0_s, n_steps, modes0=modes0, jacobian=False).state
    return out


def central_differences(pm, state, t0_s: float, n_steps: int, modes0, scales, rel: float = 1e-7):
    """``(reference, check)``: the Richardson extrapolations of central differences of the map of ``n_steps`` steps
    from ``state`` at ``t0_s`` (s) with the end-face ``modes0``, at ``2 rel`` and ``rel`` of ``scales``, and at
    ``rel`` and ``rel/2`` (``2 · 3 · 2 n_r`` maps)."""
    return _central(_stencil(pm, state, t0_s, n_steps, modes0, scales, rel), rel * np.asarray(scales, float)[None, :])


def _central(P, h):
    """``(reference, check)`` of :func:`central_differences` from the stencil ``P`` (:func:`_stencil`), steps ``h``."""
    F = {k: (P[k] - P[-k]) / (2 * k * h) for k in (2.0, 1.0, 0.5)}
    return (4 * F[1.0] - F[2.0]) / 3, (4 * F[0.5] - F[1.0]) / 3


def piece_reference(pm, state, t0_s: float, n_steps: int, modes0, scales, monodromy, rels=(1e-7, 1e-8),
                    bound: float = 1e-6) -> dict:
    """The reference of the derivative of the map's piece the orbit lies on, column by column, and ``monodromy``'s
    error against it (:func:`scaled_error`'s norm).

    For each column, at each relative step of ``rels`` in turn until one converges to ``bound``: the central
    differences (:func:`central_differences`); else, where a threshold of the map lies within ``2 rel`` of the state
    on one side (a stick episode born, an event moved across a step boundary: rotor/dynamics/period_map_events.py)
    and the central stencil straddles two pieces, the one-sided differences on the other side (forward or
    backward, Richardson-extrapolated from ``rel`` and ``2 rel``, checked against ``rel/2`` and ``rel``: an O(h²)
    error, larger than the central differences' O(h⁴), measured 6e-5 where those converge to 1e-7), which stay on
    the orbit's piece. Where both sides converge and differ, the state
    lies on the threshold itself (within ``rel/2``; the central differences then converge to the sides' mean,
    which is no piece's derivative): where they differ by more than ten times ``bound`` (less is not told from
    their noise, and the central differences are kept), each side is the derivative of a piece that holds the
    orbit, the nearer to ``monodromy`` is taken, and the column is counted ``on_threshold``. A finer step (``rels[1]``)
    is tried only for the columns no coarser one resolved (thresholds within ``2 rel`` on both sides). Measured on
    Table 4 at T/256 (benchmarks/bench_monodromy_random.py, seed 2426071970): at 11 805.3 rpm 7 columns straddle a
    threshold at 1e-7 (central convergence 2.0), resolved one-sided to 2.3e-7, the monodromy 8.3e-8 from them; at
    9 294.0 rpm 3 columns have thresholds on both sides at 1e-7 (1.9e-4), resolved at 1e-8.

    Returns ``{"error", "reference_convergence", "central_convergence", "one_sided_columns", "finer_columns",
    "on_threshold", "reference"}``: ``reference_convergence`` the largest column convergence of the chosen
    differences (the central one's where no choice converged), ``central_convergence`` that of the central
    differences at ``rels[0]`` alone (:func:`central_differences`); both relative to the largest entry of the
    central differences' smooth columns (:func:`_smooth_scale`)."""
    S = np.asarray(scales, float)[None, :] / np.asarray(scales, float)[:, None]
    n = len(scales)
    reference, conv, todo = np.zeros((n, n)), np.full(n, np.inf), np.arange(n)
    central_conv = norm = None
    one_sided = finer = on_threshold = 0
    for level, rel in enumerate(rels):
        P, h = _stencil(pm, state, t0_s, n_steps, modes0, scales, rel), rel * np.asarray(scales, float)[None, :]
        central, central_check = _central(P, h)
        if norm is None:
            norm = _smooth_scale(central * S, central_check * S)
            central_conv = np.abs((central - central_check) * S).max(axis=0) / norm
        options = [(central, np.abs((central - central_check) * S).max(axis=0) / norm)]
        for sign in (1.0, -1.0):
            D = {k: (P[sign * k] - P[0.0]) / (sign * k * h) for k in (2.0, 1.0, 0.5)}
            est, chk = 2 * D[1.0] - D[2.0], 2 * D[0.5] - D[1.0]
            options.append((est, np.abs((est - chk) * S).max(axis=0) / norm))
        for j in todo:
            sides = [(est[:, j], gap[j]) for est, gap in options[1:] if gap[j] <= bound]
            if len(sides) == 2 and np.abs((sides[0][0] - sides[1][0]) * S[:, j]).max() / norm > 10.0 * bound:
                # a threshold at the state: the central differences converge to the sides' mean, no piece's
                on_threshold += 1
                reference[:, j], conv[j] = min(sides, key=lambda g: np.abs((monodromy[:, j] - g[0]) * S[:, j]).max())
            elif options[0][1][j] <= bound:
                reference[:, j], conv[j] = options[0][0][:, j], options[0][1][j]
            elif sides:
                reference[:, j], conv[j] = sides[0]
                one_sided += 1
            else:
                if level == 0:          # none converged: the central differences, with their convergence
                    reference[:, j], conv[j] = options[0][0][:, j], options[0][1][j]
                continue
            finer += level > 0
        todo = np.flatnonzero(conv > bound)
        if not len(todo):
            break
    return {"error": scaled_error(monodromy, reference, scales), "reference_convergence": float(conv.max()),
            "central_convergence": float(central_conv.max()), "one_sided_columns": one_sided,
            "finer_columns": finer, "on_threshold": on_threshold, "reference": reference}


def _smooth_scale(ref, check) -> float:
    """The largest entry of ``ref`` over its columns that agree with ``check`` within 1e-3 of their own size: a
    column straddling a jump holds ``jump/h`` (measured: 36 times the monodromy's largest entry at 1e-7, Table 4
    with the steel-in-aluminium bearing at 10 017.6 rpm), which must not set the scale of every column's
    convergence. The plain largest entry where no column agrees."""
    size = np.abs(ref).max(axis=0)
    ok = np.abs(ref - check).max(axis=0) <= 1e-3 * size
    return float(size[ok].max() if np.any(ok) else size.max())


def scaled_error(M, reference, scales) -> float:
    """The largest entry of ``M − reference`` in the scaled coordinates ``x/s`` over the largest of ``reference``."""
    S = scales[None, :] / scales[:, None]
    return float(np.abs((M - reference) * S).max() / np.abs(reference * S).max())
