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


def central_differences(pm, state, t0_s: float, n_steps: int, modes0, scales, rel: float = 1e-7):
    """``(reference, check)``: the Richardson extrapolations of central differences of the map of ``n_steps`` steps
    from ``state`` at ``t0_s`` (s) with the end-face ``modes0``, at ``2 rel`` and ``rel`` of ``scales``, and at
    ``rel`` and ``rel/2`` (``2 · 3 · 2 n_r`` maps)."""
    def fd(h):
        M = np.zeros((state.size, state.size))
        for j in range(state.size):
            e = np.zeros(state.size)
            e[j] = h * scales[j]
            a, b = (period_map(pm, state + d, t0_s, n_steps, modes0=modes0, jacobian=False).state for d in (e, -e))
            M[:, j] = (a - b) / (2 * e[j])
        return M

    F = {k: fd(k * rel) for k in (2.0, 1.0, 0.5)}
    return (4 * F[1.0] - F[2.0]) / 3, (4 * F[0.5] - F[1.0]) / 3


def scaled_error(M, reference, scales) -> float:
    """The largest entry of ``M − reference`` in the scaled coordinates ``x/s`` over the largest of ``reference``."""
    S = scales[None, :] / scales[:, None]
    return float(np.abs((M - reference) * S).max() / np.abs(reference * S).max())
