"""Steps of the compiled production loop replayed from many starts in one call (:func:`replay_steps`): the central
differences of a located event step (:func:`rotor.dynamics.period_map_events._step_jacobian`, ``6 · 3 n_r`` replays a step).

Called from Python (:func:`rotor.dynamics.period_map_events._one_step`), each replay of
:func:`rotor.dynamics.production_loop.step_loop` also paid numba's dispatch of its ~50 arguments and the allocation
of its one-step records, more than the step itself. Measured on Table 4 (n_r = 26, 640 steps per revolution, a
corrector's map at 2 417 rpm with 280 differenced steps, slow slips held, 469 replays each): 3.3 s a located monodromy
one replay at a time, 2.07 s here (medians of 3, interleaved in one process, load average 4.6 on 2 cores); the
branch 2 300 → 2 420 rpm (241 located monodromies) 431 s → 283 s. What is left is the step itself (~25 µs a replay
of a held slow slip, ~17 µs a step inside a run; about 8 µs of a replay is the step loop's set-up). Each replay is the
same compiled step from the same start, so the ends are those of the one-by-one replays (the monodromy bit-identical).
Since then the held slow-slip steps are carried analytically (rotor/dynamics/period_map_events.py, "Held steps,
carried"): a few split steps a period are differenced here.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from contact.compiled_cache import compiled_with
from rotor.dynamics.production_loop import step_loop

compiled_with(__file__, ["rotor.dynamics.production_loop", "rotor.dynamics.contact_events",
                         "rotor.dynamics.friction_events", "rotor.dynamics.production_kernels",
                         "rotor.dynamics.constraints", "rotor.dynamics.kernels", "contact._kernel",
                         "contact._kernel_friction", "contact._kernel_tilt"])


@njit(cache=True)
def replay_steps(starts, modes0, phi0, ts, n_steps, dt, Ainv, Dr, Kr, Bt, W, S, static, orders, cosm, sinm, omega_f, P, mu_N,
                 n_faces, s_yy, a1, has_support, params, beta, gamma, tol, max_iter, w_reg, w_stick, max_passes,
                 stick_mean_weight, onset_projection, Minv, WM, SM, Mr, locate_events, split_events):
    """``n_steps`` steps of length ``dt`` (s) (one call of the loop, its memory between those steps kept: a
    block of steps whose face forces carry over, rotor/dynamics/period_map_events.py "Blocks") from each row of
    ``starts`` (``(K, 3 n_r)``), each with its own face modes
    ``modes0[r]`` (2,), face forces ``phi0[r]`` (2, 2; N) and time ``ts[r]`` (s): the ends (``(K, 3 n_r)``) and each
    replay's ``status`` (``(K, 7)``, :func:`rotor.dynamics.production_loop.step_loop`'s), end face modes
    (``(K, 2)``) and end face forces (``(K, 2, 2)``, N): a record's candidate event steps, one step's central
    differences (rotor/dynamics/period_map_events.py), or the passes of a located step one by one (``split_events``
    False, ``dt`` a pass's length and ``Ainv, W, S`` its matrices: rotor/dynamics/contact_step_derivative.py), in one
    compiled call; the other arguments are :func:`rotor.dynamics.production_loop.step_loop`'s."""
    K, n3 = starts.shape
    nr = n3 // 3
    ends = np.empty((K, n3))
    statuses = np.zeros((K, 7), dtype=np.int64)
    end_modes = np.zeros((K, 2), dtype=np.int64)
    end_phi = np.zeros((K, 2, 2))
    rec_t = np.zeros(2)
    rec_p = np.zeros((2, nr))
    rec_v = np.zeros((2, nr))
    rec_a = np.zeros((2, nr))
    rec_u = np.zeros((2, 4))
    rec_w = np.zeros((2, 4))
    rec_fc = np.zeros((2, 4))
    rec_fel = np.zeros((2, 4))
    rec_face = np.zeros((2, 2, 2))
    rec_modes = np.zeros((2, 2), dtype=np.int8)
    rec_its = np.zeros(2, dtype=np.int32)
    rec_passes = np.zeros(2, dtype=np.int32)
    status = np.zeros(7, dtype=np.int64)
    one = np.int64(1)
    k = np.int64(n_steps)
    for r in range(K):
        p = starts[r, :nr].copy()
        v = starts[r, nr:2 * nr].copy()
        a = starts[r, 2 * nr:].copy()
        modes = modes0[r].copy()
        phi = phi0[r].copy()
        status[:] = 0
        step_loop(p, v, a, modes, phi, ts[r], dt, k, k, Ainv, Dr, Kr, Bt, W, S, static, orders, cosm, sinm,
                  omega_f, P, mu_N, n_faces, s_yy, a1, has_support, params, beta, gamma, tol, max_iter, w_reg,
                  w_stick, max_passes, stick_mean_weight, onset_projection, Minv, WM, SM, Mr, locate_events, split_events, rec_t,
                  rec_p, rec_v, rec_a, rec_u, rec_w, rec_fc, rec_fel, rec_face, rec_modes, rec_its, rec_passes,
                  status)
        ends[r, :nr] = p
        ends[r, nr:2 * nr] = v
        ends[r, 2 * nr:] = a
        statuses[r] = status
        end_modes[r] = modes
        end_phi[r] = phi
    return ends, statuses, end_modes, end_phi
