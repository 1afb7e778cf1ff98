"""The start of a run whose friction is solved by projection (``NewmarkOptions(friction_scheme="projection")``).

The production scheme carries the acceleration, so a run from ``(p₀, v₀)`` needs ``a₀``; with the faces' friction
set-valued at rest it must be a function of ``(p₀, v₀)`` that is continuous, or the period map would jump where a
face's velocity crosses zero. It is taken as the step's own equation with no position update: ``a₀ = M⁻¹(Q − D v −
K p + Bᵀ g)``, each face's force ``f₀ = proj_{|f| ≤ μN}(f₀ − r (w + γΔt α₀))`` (Alart & Curnier 1991, the same
projection as the step's, :func:`rotor.dynamics.constraints.coulomb_projection`), i.e. Coulomb's law at the velocity
the face would have a trapezoidal half-step on. A face at rest whose holding force is below ``μN`` gets zero
relative acceleration (stuck, exactly); a sliding face ``−μN`` along ``w + γΔt α₀``, which differs from the
direction of ``w`` by ``O(Δt)``. Solved by the step's compiled Newton
(:func:`rotor.dynamics.production_kernels._solve_support`, with ``βΔt² = 0`` and the mass's compliance
``S_M``), differentiated by :func:`rotor.dynamics.period_map_projection.projected_start_jacobian`.
"""
from __future__ import annotations

import numpy as np

from contact.errors import ConvergenceError
from rotor.dynamics.constraints import PROJECTED, SLIP, STICK
from rotor.dynamics.production_kernels import NC, VG, _load, _solve_support, newton_work


def projected_modes(n_faces: int) -> np.ndarray:
    """The face modes of the projection scheme: the active faces projected, the inactive one (tilt ignored)
    slipping with a zero limit (no force)."""
    return np.array([PROJECTED] * n_faces + [SLIP] * (2 - n_faces), dtype=np.int64)


#: a projected face is reported stuck where its sliding speed is below this (m/s): the stuck branch of the projection
#: holds it at zero to the step's Newton tolerance (about 1e-12 m/s on the Table 4 rotor), a slip is faster
STUCK_SPEED_M_S = 1e-9


def projected_branch_modes(w_rec, P, n_faces: int) -> np.ndarray:
    """The recorded modes of a projection run as its readers expect them (int8 (N, 2)): ``STICK`` where a face's
    sliding speed ``|P_k w|`` (``w_rec`` (N, 4), m/s) is below :data:`STUCK_SPEED_M_S` (the projection's stuck
    branch), else ``SLIP``; an inactive face ``SLIP``. The period map itself runs on ``PROJECTED`` faces."""
    out = np.full((w_rec.shape[0], 2), SLIP, dtype=np.int8)
    for k in range(n_faces):
        speed = np.hypot(w_rec @ P[k, 0], w_rec @ P[k, 1])
        out[speed < STUCK_SPEED_M_S, k] = STICK
    return out


def projected_start(pre, t0: float, p, v, params, opts) -> tuple[np.ndarray, np.ndarray]:
    """``(a₀ (nr,), face forces f₀ (2, 2) N)`` at reduced ``(p, v)`` and time ``t0`` (s) (module docstring).

    ``pre``: :class:`rotor.dynamics.production.Prepared`; ``params``: the support law's parameters; ``opts``:
    :class:`rotor.dynamics.system.NewmarkOptions`. Raises ConvergenceError if Newton does not converge."""
    nr = p.shape[0]
    Q = np.empty(nr)
    _load(float(t0), pre.static, pre.orders, pre.cos, pre.sin, pre.omega_force, Q)
    a_free = pre.Minv @ (Q - pre.Dr @ v - pre.Kr @ p)
    if pre.n_faces == 0 and not np.any(pre.Bt):
        return a_free, np.zeros((2, 2))
    alpha_lin = pre.Bt @ a_free
    u = pre.Bt @ p
    w = pre.Bt @ v
    modes = projected_modes(pre.n_faces)
    vec, mat, face, jac = newton_work()
    phi = np.zeros((2, 2))
    its, ok = _solve_support(alpha_lin.copy(), alpha_lin, u, w, pre.SM, pre.P, modes, np.zeros((2, 2)),
                             np.zeros(2, dtype=np.bool_), np.zeros((2, 2)), pre.limits, pre.a1, 0.0,
                             opts.gamma * pre.dt, params, opts.tol, opts.max_iter, opts.w_reg, vec, mat, face, jac,
                             phi)
    if not ok:
        raise ConvergenceError(f"projection scheme: the start's Newton did not converge at t = {t0:.6g} s "
                               f"({its} iterations, tol = {opts.tol:.1e})")
    g = vec[VG, :NC].copy()
    return a_free + pre.WM @ g, phi.copy()
