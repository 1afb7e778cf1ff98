"""The exact derivative of a step split at a contact onset or loss (:mod:`rotor.dynamics.contact_events`).

A located contact step from ``x₀ = (p, v, a)`` is three passes of the step body
(:func:`rotor.dynamics.production_loop.step_loop`): the plain pass of length ``Δt`` gives the end ``x̂``; the
crossing fraction ``θ`` is the root of the edge penetration along the cubic Hermite interpolant of the relative
displacement between ``x₀`` and ``x̂``; then the sub-step of length ``θΔt`` from ``x₀`` to ``x_m`` and the sub-step of
length ``(1 − θ)Δt`` from ``x_m`` to the end. So the step is ``Φ(x₀, θ(x₀))`` with ``Φ`` the two sub-steps at a given
``θ``, and its derivative is

    dx/dx₀ = ∂Φ/∂x₀ + ∂Φ/∂θ · dθ/dx₀,

the discrete form of the saltation matrix through the located time (Leine & van Campen 2002):

* ``∂Φ/∂x₀``: each sub-step carried analytically at its own length (:func:`rotor.dynamics.period_map_kernels.carry`
  with that length's Newmark matrices), as a plain step is;
* ``dθ/dx₀ = −G_y dy/dx₀ / G_θ`` by the implicit function theorem on ``G(θ, y) = Δr_k(H(θ; y))``, ``y`` the relative
  displacements and velocities at ``x₀`` and ``x̂``, ``dx̂/dx₀`` the plain pass carried analytically;
  ``G`` is written out (the Hermite basis and the edge penetration's gradient);
* ``∂Φ/∂θ = Δt (J₂ ∂x_m/∂h₁ − ∂x/∂h₂)``, ``J₂`` the second sub-step's derivative in its start and ``∂x/∂h`` a
  pass's derivative in its length at a fixed start, analytic too: differentiating the Newmark relations
  ``p' = p + hv + h²((½ − β)a + βa')``, ``v' = v + h((1 − γ)a + γa')`` and the equation of motion at ``t + h`` in
  ``h`` gives the pass's own linearisation (:func:`rotor.dynamics.period_map_kernels.carry`) driven by the predictor
  change ``(v + 2h((½ − β)a + βa'), (1 − γ)a + γa')`` and the load's rate ``A⁻¹ Q̇(t + h)``
  (:func:`_length_column`).

Nothing of the step is differenced: the ``6 · 3 n_r`` and more replays of the differenced route (a ladder of
central differences, rotor/dynamics/period_map_events.py) become its three passes and their carries. Measured
(tests/rotor/dynamics/test_contact_step_derivative.py): within 3e-10 to 2e-8 of the step's own central differences
on random Table 4 and steel-in-aluminium speeds; Table 4 at 7 000 rpm, T/2240, 24 revolutions after the linear
start: the period map with its monodromy 0.118 s CPU against 0.430 s differenced; the steel-in-aluminium orbits at
8 781 and 8 804.5 rpm: the monodromy 5.7e-7 and 1.19e-6 from central differences of its map (their references
converged to 3.7e-7 and 7.0e-7), 6.0e-7 and 3.05e-6 differenced.

:func:`contact_step_plan` returns None (the caller differences the step) where the passes replayed one by
one do not reproduce the recorded step (a friction event located in it instead, or a face released in the first
sub-step, whose memory a replay lacks) or where a face sticks in a pass (the stick-onset re-projection's load rate is
not carried).

A pass's ``status[5:7]`` (how each face's friction was held, :func:`rotor.dynamics.production_loop.step_loop`) is
decided from its start, but the pass can drop a slow slip's hold (kind 1): the held force reverses the face, the
mode update tries stick (which clears the hold), stick is rejected, and the pass ends with the regularised friction
of an ordinary slip while the status still says 1. The passes are carried with the holds they kept
(:func:`_held`): a face whose status says 1 and that ends slipping with a force other than the held one
``−μN ŵ`` (``ŵ`` its start slip direction) is carried unheld. Measured on Table 4 at 6 163.1 rpm (T/256, the
state 24 revolutions after the linear start, drawn by seed 2121 in
tests/rotor/dynamics/test_contact_step_derivative.py), step 80, the step after face 1's release, an edge onset at
0.913 of it: face 1 slips at 35.7 ``w_reg`` along its acceleration, status 1 in the plain pass and the first
sub-step, its end force (−1335, −683) N against the held (−121, −1495) N; carried held, the plain pass was 0.62
from its central differences and the step's derivative 3.74 from the reference; carried as kept, 5.8e-10 and
7.8e-9.
"""
from __future__ import annotations

import numpy as np

from rotor.dynamics.contact_events import crossing_fraction, edge_crossing
from rotor.dynamics.event_replays import replay_steps
from rotor.dynamics.friction_events import _substep_matrices
from rotor.dynamics.period_map_kernels import carry

#: the passes replayed one by one must reproduce the recorded step within this (relative to the scales)
REPRODUCE_TOL = 1e-10
#: a crossing closer than this fraction of the step to either of its ends is declined (differenced by the ladder of
#: rotor/dynamics/period_map_events.py): the length columns of a pass of length ``h`` scale as ``1/h``
#: (:func:`_length_column`) and the step's derivative is their difference, so a short pass loses it to round-off.
#: Measured on Table 4 at 16 841.3 rpm (T/256, the state 24 revolutions after the linear start, drawn by seed
#: 1014817851 in tests/rotor/dynamics/test_contact_step_derivative.py): a crossing at 1 - 5.9e-7 of step 105, the
#: exact derivative 1.1e-2 from central differences of the step (which agree with each other from 4e-6 to 6e-8);
#: on 38 contact steps of 14 random speeds (seed 99) the crossings from 3.2e-3 to 0.97 of the step gave 4e-10 to
#: 5e-9
THETA_MIN = 1e-3
#: a held face's end force is its held force to this (relative to ``μN``), else its hold was dropped (:func:`_held`).
#: Measured over one revolution 24 after the linear start at 25 random speeds of each scene of
#: tests/rotor/dynamics/test_contact_step_derivative.py (numpy seed 7): 16 plain steps with a slow slip's status 1,
#: 6 whose end force is the held one exactly (0 N), 10 that dropped the hold, 697 to 1 774 N from it
HELD_TOL = 1e-9


def _matrices(pm, h: float):
    """``(A⁻¹, W, S, A⁻¹K, A⁻¹D)`` of a pass of length ``h`` (s): the plain step's from ``pm`` when ``h`` is its
    step."""
    pre = pm.prepared
    if h == pm.dt:
        return pre.Ainv, pre.W, pre.S, pm.AK, pm.AD
    Ai, W, S = _substep_matrices(h, pre.Mr, pre.Dr, pre.Kr, pre.Bt, pm.options.beta, pm.options.gamma)
    return Ai, W, S, np.ascontiguousarray(Ai @ pre.Kr), np.ascontiguousarray(Ai @ pre.Dr)


def _passes(pm, starts, modes, phi, ts, h: float, mats=None):
    """One unsplit pass of the located step body of length ``h`` (s) from each row of ``starts`` (``(K, 3 n_r)``)
    with its face ``modes`` (``(K, 2)``), forces ``phi`` (``(K, 2, 2)``, N) and time ``ts`` (``(K,)``, s): the ends,
    statuses, end modes and end face forces (:func:`rotor.dynamics.event_replays.replay_steps`)."""
    pre, opts = pm.prepared, pm.options
    Ai, W, S = (mats or _matrices(pm, h))[:3]
    return replay_steps(np.ascontiguousarray(starts, dtype=float), np.ascontiguousarray(modes, dtype=np.int64),
                        np.ascontiguousarray(phi, dtype=float), np.ascontiguousarray(ts, dtype=float), 1, float(h),
                        Ai, pre.Dr, pre.Kr, pre.Bt, W, S, pre.static, pre.orders, pre.cos, pre.sin, pre.omega_force,
                        pre.P, pre.limits, pre.n_faces, pre.s_yy, pre.a1, pm.reduced.support is not None, pm.params,
                        opts.beta, opts.gamma, opts.tol, opts.max_iter, opts.w_reg, opts.w_stick, opts.max_passes,
                        float(opts.stick_mean_weight), bool(opts.consistent_stick_onset), pre.Minv, pre.WM, pre.SM,
                        pre.Mr, True, False)


def _one_pass(pm, x, modes, phi, t, h, mats=None):
    """:func:`_passes` from one start: ``(end, status, modes, face forces)``."""
    e, s, m, f = _passes(pm, x[None, :], np.asarray(modes)[None, :], np.asarray(phi)[None], np.array([t]), h, mats)
    return e[0], s[0], m[0], f[0]


def _held(pm, x, status, modes_end, phi_end) -> np.ndarray:
    """How each face's friction was held over a pass from ``x`` (``(p, v, a)``) that ended with face modes
    ``modes_end`` and forces ``phi_end`` (2, 2; N): its ``status[5:7]``, with a slow slip's hold (1) that the pass
    dropped set to 0 (module docstring): the face ends slipping with a force other than ``−μN ŵ``, ``ŵ`` its slip
    direction at the start (the held force, :func:`rotor.dynamics.period_map_kernels.carry`)."""
    pre, nr = pm.prepared, pm.nr
    held = np.array(status[5:7], dtype=np.int64)
    w4 = (pre.Bt @ x[nr:2 * nr])[:4]
    for k in range(2):
        if held[k] == 1 and modes_end[k] == 0:
            w = pre.P[k] @ w4
            f = -pre.limits[k] * w / np.linalg.norm(w)
            if np.max(np.abs(np.asarray(phi_end[k]) - f)) > HELD_TOL * pre.limits[k]:
                held[k] = 0
    return held


def _carry_pass(pm, x0, x1, modes0, modes1, held, phi0, Spv, Sa, h, mats, dload=None):
    """Carry ``Spv``, ``Sa`` (in place) over one pass of length ``h`` (s) from ``x0`` to ``x1`` (``(p, v, a)``) with
    its start and end modes, how its faces' friction was held (:func:`_held`) and its start forces;
    ``dload`` (n_r × ncol) the load-rate columns (:func:`_length_column`), zero if None."""
    pre, opts, nr = pm.prepared, pm.options, pm.nr
    _, W, S, AK, AD = mats
    rec_p = np.ascontiguousarray(np.vstack([x0[:nr], x1[:nr]]))
    rec_v = np.ascontiguousarray(np.vstack([x0[nr:2 * nr], x1[nr:2 * nr]]))
    rec_modes = np.ascontiguousarray(np.vstack([modes0, modes1]).astype(np.int64))
    rec_held = np.zeros((2, 2), dtype=np.int64)
    rec_held[0] = held
    rec_face = np.zeros((2, 2, 2))
    rec_face[0] = phi0
    carry(rec_p, rec_v, rec_modes, Spv, Sa, float(h), opts.beta, opts.gamma, AK, AD, pm.MK, pm.MD, pre.Bt, W, S,
          pre.WM, pre.SM, pre.P, pre.limits, pre.a1, True, pm.params, opts.w_reg, bool(opts.consistent_stick_onset),
          rec_held, rec_face, np.zeros((nr, Spv.shape[1])) if dload is None else np.ascontiguousarray(dload))


def _hermite_basis(s: float) -> tuple[np.ndarray, np.ndarray]:
    """The cubic Hermite basis ``(h00, h10, h01, h11)`` at fraction ``s`` and its derivative in ``s`` (the
    interpolant of :func:`rotor.dynamics.contact_events._hermite`, ``h10``/``h11`` without the step length)."""
    s2, s3 = s * s, s * s * s
    b = np.array([2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2])
    db = np.array([6 * s2 - 6 * s, 3 * s2 - 4 * s + 1, -6 * s2 + 6 * s, 3 * s2 - 2 * s])
    return b, db


def _penetration_gradient(r4, k: int, params) -> tuple[float, np.ndarray]:
    """Edge ``k``'s penetration ``Δr_k`` (m) at the relative displacement ``r4`` (y, z, θy, θz; m, rad) and its
    gradient (4,) (:func:`rotor.dynamics.contact_events._penetration`)."""
    d0, hl, tilt_ignored = params[0], 0.5 * params[1], params[11] != 0.0
    sg = 1.0 if k == 0 else -1.0
    if tilt_ignored:
        ry, rz = r4[0], r4[1]
    else:
        ry, rz = r4[0] + sg * hl * r4[3], r4[1] - sg * hl * r4[2]
    r = float(np.hypot(ry, rz))
    grad = np.array([ry / r, rz / r, 0.0, 0.0])
    if not tilt_ignored:
        grad[2], grad[3] = -sg * hl * rz / r, sg * hl * ry / r
    return r - d0, grad


def _theta_row(pm, theta, u_s, w_s, u_e, w_e, dU_s, dW_s, dU_e, dW_e):
    """``(dθ/dx_seed (ncol,), edge, G_θ)``: the crossing fraction's derivative, the implicit function theorem on the
    edge penetration along the Hermite interpolant (module docstring); ``dU_*``, ``dW_*`` (4, ncol) the derivatives
    of the relative displacements and velocities (``u_s, w_s`` start, ``u_e, w_e`` the plain pass's end)."""
    dt, params = pm.dt, pm.params
    b, db = _hermite_basis(theta)
    r4 = b[0] * u_s[:4] + b[1] * dt * w_s[:4] + b[2] * u_e[:4] + b[3] * dt * w_e[:4]
    edges = [k for k in range(2) if (_penetration_gradient(u_s[:4], k, params)[0] > 0.0)
             != (_penetration_gradient(u_e[:4], k, params)[0] > 0.0)]
    k = min(edges, key=lambda e: abs(_penetration_gradient(r4, e, params)[0]))
    _, grad = _penetration_gradient(r4, k, params)
    dr_dtheta = db[0] * u_s[:4] + db[1] * dt * w_s[:4] + db[2] * u_e[:4] + db[3] * dt * w_e[:4]
    g_theta = float(grad @ dr_dtheta)
    dr = b[0] * dU_s + b[1] * dt * dW_s + b[2] * dU_e + b[3] * dt * dW_e
    return -(grad @ dr) / g_theta, k, g_theta


def _load_rate(pm, t: float) -> np.ndarray:
    """``Q̇(t)`` (N/s, reduced): the rate of :func:`rotor.dynamics.production_kernels._load`'s harmonic orders."""
    pre = pm.prepared
    ph = pre.orders * pre.omega_force * t
    rate = pre.orders * pre.omega_force
    return (rate * -np.sin(ph)) @ pre.cos + (rate * np.cos(ph)) @ pre.sin


def _length_column(pm, xs, xe, t_s: float, h: float, mats) -> tuple[np.ndarray, np.ndarray]:
    """The predictor column and ``A⁻¹ Q̇`` whose carry over the pass from ``xs`` to ``xe`` (``(p, v, a)``, length
    ``h``, s, from time ``t_s``) gives ``∂x_e/∂h`` at a fixed start (module docstring): as the sensitivities
    ``(Spv (2 n_r, 1), Sa (n_r, 1))`` that :func:`rotor.dynamics.period_map_kernels.carry` turns into that predictor
    (velocity column zero, so no held slow slip's force moves), and ``dload (n_r, 1)``."""
    nr, beta, gamma = pm.nr, pm.options.beta, pm.options.gamma
    a_s, a_e = xs[2 * nr:], xe[2 * nr:]
    d_p = xs[nr:2 * nr] + 2.0 * h * ((0.5 - beta) * a_s + beta * a_e)
    d_v = (1.0 - gamma) * a_s + gamma * a_e
    sa = d_v / (h * (1.0 - gamma))
    spv = np.concatenate([d_p - h * h * (0.5 - beta) * sa, np.zeros(nr)])
    dload = mats[0] @ _load_rate(pm, t_s + h)
    return spv[:, None], sa[:, None], dload[:, None]


def contact_step_plan(pm, x0, modes0, phi0, t, ref_end, scales):
    """The passes of the recorded step from ``x0`` (``(p, v, a)`` at time ``t``, s, with face ``modes0`` and forces
    ``phi0``, N) to ``ref_end`` replayed one by one, if it is a step split at a contact onset or loss whose passes
    reproduce the record and in which no face sticks (module docstring): a dict for
    :func:`contact_step_sensitivity`, else None (the caller differences the step)."""
    nr, dt, Bt = pm.nr, pm.dt, pm.prepared.Bt
    plain, st_pl, m_pl, f_pl = _one_pass(pm, x0, modes0, phi0, t, dt)
    u_s, w_s = Bt @ x0[:nr], Bt @ x0[nr:2 * nr]
    u_e, w_e = Bt @ plain[:nr], Bt @ plain[nr:2 * nr]
    if not edge_crossing(u_s, u_e, pm.params):
        return None
    theta = float(crossing_fraction(u_s, w_s, u_e, w_e, dt, pm.params))
    if not THETA_MIN < theta < 1.0 - THETA_MIN:
        return None
    h1, h2 = theta * dt, dt - theta * dt
    m1, m2 = _matrices(pm, h1), _matrices(pm, h2)
    mid, st1, m_mid, f_mid = _one_pass(pm, x0, modes0, phi0, t, h1, m1)
    end, st2, m_end, f_end = _one_pass(pm, mid, m_mid, f_mid, t + h1, h2, m2)
    mismatch = float(np.max(np.abs(end - ref_end) / scales))
    if mismatch > REPRODUCE_TOL:
        return None
    if any(m_mid[k] == 1 and modes0[k] != 1 for k in range(2)) or any(m_end[k] == 1 and m_mid[k] != 1
                                                                       for k in range(2)):
        return None
    return dict(x0=x0, modes0=modes0, phi0=phi0, t=t, plain=plain, m_pl=m_pl, theta=theta, mid=mid, m_mid=m_mid,
                f_mid=f_mid, end=end, m_end=m_end, m1=m1, m2=m2, mismatch=mismatch,
                held_pl=_held(pm, x0, st_pl, m_pl, f_pl), held1=_held(pm, x0, st1, m_mid, f_mid),
                held2=_held(pm, mid, st2, m_end, f_end))


def contact_step_sensitivity(pm, plan, Spv, Sa):
    """Carry ``Spv = ∂(p, v)/∂x_seed`` (2 n_r × ncol) and ``Sa = ∂a/∂x_seed`` over the recorded step that ``plan``
    (:func:`contact_step_plan`) replayed: a step split at a contact onset or loss (module docstring). Returns the
    new ``(Spv, Sa)`` and the replay's relative mismatch against the record."""
    nr, dt, Bt = pm.nr, pm.dt, pm.prepared.Bt
    x0, modes0, phi0, t, theta = plan["x0"], plan["modes0"], plan["phi0"], plan["t"], plan["theta"]
    plain, mid, end, m_mid, m_end = plan["plain"], plan["mid"], plan["end"], plan["m_mid"], plan["m_end"]
    m1, m2, h1 = plan["m1"], plan["m2"], theta * dt
    h2 = dt - h1
    u_s, w_s = Bt @ x0[:nr], Bt @ x0[nr:2 * nr]
    u_e, w_e = Bt @ plain[:nr], Bt @ plain[nr:2 * nr]
    # dθ: the plain pass carried from copies; the start's relative motion from the sensitivities before the step
    Spv_pl, Sa_pl = Spv.copy(), Sa.copy()
    _carry_pass(pm, x0, plain, modes0, plan["m_pl"], plan["held_pl"], phi0, Spv_pl, Sa_pl, dt, _matrices(pm, dt))
    row, _, _ = _theta_row(pm, theta, u_s, w_s, u_e, w_e, (Bt @ Spv[:nr])[:4], (Bt @ Spv[nr:])[:4],
                           (Bt @ Spv_pl[:nr])[:4], (Bt @ Spv_pl[nr:])[:4])
    # ∂x_m/∂h1 carried through the second pass with the sensitivities; ∂x/∂h2 from the end of the first pass
    Spv, Sa = Spv.copy(), Sa.copy()
    held1, held2, f_mid = plan["held1"], plan["held2"], plan["f_mid"]
    _carry_pass(pm, x0, mid, modes0, m_mid, held1, phi0, Spv, Sa, h1, m1)
    c_pv, c_a, c_load = _length_column(pm, x0, mid, t, h1, m1)
    _carry_pass(pm, x0, mid, modes0, m_mid, held1, phi0, c_pv, c_a, h1, m1, c_load)
    ncol = Spv.shape[1]
    Spv, Sa = np.hstack([Spv, c_pv]), np.hstack([Sa, c_a])
    e_pv, e_a, _ = _length_column(pm, mid, end, t + h1, h2, m2)
    _carry_pass(pm, mid, end, m_mid, m_end, held2, f_mid, Spv, Sa, h2, m2)
    # the second pass ends at the step's end whatever θ: its load does not move (no load rate)
    _carry_pass(pm, mid, end, m_mid, m_end, held2, f_mid, e_pv, e_a, h2, m2)
    dphi = dt * (np.concatenate([Spv[:, ncol], Sa[:, ncol]]) - np.concatenate([e_pv[:, 0], e_a[:, 0]]))
    Spv = Spv[:, :ncol] + np.outer(dphi[:2 * nr], row)
    Sa = Sa[:, :ncol] + np.outer(dphi[2 * nr:], row)
    return np.ascontiguousarray(Spv), np.ascontiguousarray(Sa), plan["mismatch"]
