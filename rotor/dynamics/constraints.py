"""End-face stick/slip and the 3a/3b lock as constraint equations (Dai et al. 2025, Eqs. 50–58).

Everything here is plain numpy on small arrays, so the same functions serve the
reference integrator (:mod:`rotor.dynamics.reference`) and, compiled with numba, the
production integrator (:mod:`rotor.dynamics.production`).

Conventions (docs/reference/contact-laws.md §1, §9)
---------------------------------------------------
Relative coordinates of the loose support are ``u = (y, z, θy, θz)`` of the
bearing minus the support (m, rad); ``w = u̇``. A point at axial position ``x`` on
the bearing moves laterally by ``(y + x θz, z − x θy)``. The right end face sits at
``x = +l0/2`` (index 1 / "r"), the left one at ``x = −l0/2`` (index 2 / "l").
A face force ``φ = (φy, φz)`` acting on the bearing at ``x`` contributes the
generalised relative force ``Pᵀ φ = (φy, φz, −x φz, x φy)``, i.e.
``My = −x Fz, Mz = x Fy``.

Decisions on the known traps (docs/reference/contact-laws.md Q6–Q11)
--------------------------------------------------------------------
* **3a/3b lock (Q11).** The paper's ``g5 = (y3a − y3b)² + (z3a − z3b)²`` has a zero
  gradient at its own solution, so its row of Φ vanishes and the augmented matrix
  is singular. We impose the two *linear* equations ``y3a − y3b = 0``,
  ``z3a − z3b = 0`` (:func:`lock_rows`). The reference scheme carries them with two
  Lagrange multipliers; the production scheme eliminates them exactly with a
  null-space map (:func:`null_space_map`).
* **Inactive stick constraints (Q11).** ``g1..g4`` are multiplied by
  ``H(μN − |f|)``; when a face slips its rows are identically zero and Φ is rank
  deficient. We never form those rows: each face carries a mode flag (stick/slip),
  and only stuck faces contribute two velocity rows and two multipliers.
* **Stick test (Q11: at which iterate?).** Inside a time step the modes are held
  fixed while Newton converges; afterwards the converged face forces are tested
  (:func:`face_mode_update`) and the step is re-solved with the flipped modes until
  they are consistent (an active-set loop, at most a few passes). The face force of
  a stuck face is its multiplier, which equals the paper's demand split
  (:func:`face_force_demand`, Eqs. 53–56) evaluated at the converged step; the
  tests check this identity. For a face that stays stuck, the bound ``μN`` is applied to the
  **mean of the start- and end-of-step face forces**, i.e. to the friction impulse the
  trapezoidal rule transmits over the step (Moreau 1988); a slipping face that tries to stick
  is tested on its end-of-step force. Measured on the Table 4 rotor: testing the end-of-step
  force instead lets the undamped average-acceleration multipliers ring at 2Δt, and the
  number of stick/slip switches then *grows* under step refinement (244/312/382 per 10
  revolutions at T/256, T/512, T/1024, with runs of step-by-step alternation), while the
  impulse test gives 236/254/254 and no alternation.
* **Stick onset (consistent restart).** When a slipping face stops, the trapezoidal rule brings
  its velocity to zero with a jump of its acceleration, and the undamped scheme carries the
  jump on as a 2Δt oscillation of the multiplier (``f_n+1 = 2 f̄ − f_n``). So in a step where
  a face tries stick (slipping at the start), the stuck faces are tested on their *consistent*
  multipliers at the end of the step (acceleration-level constraint at fixed positions and
  velocities, as at t0: :func:`rotor.dynamics.initial.initial_acceleration`, the paper's demand split
  Eqs. 53–56 of the holding force), and once the face sticks the step's acceleration and
  multipliers are replaced by those consistent ones (positions and velocities of the step
  kept), as Newmark's scheme is restarted after any jump. A face released in the previous step
  (it starts from zero speed) is tried in stick again only on a reversal of its velocity, not
  for being slower than ``w_stick``. Measured (Table 4 rotor, 7 hard cases × 2 starts,
  10 revolutions at T/256): runs of three consecutive flips 7 → 0 (T/512: 1 → 0); Den Hartog's
  stick-slip amplitude error at T/400 2.5e-3 → 2.3e-4 (at T/3200 unchanged, 3.4e-4, the
  floor of ``w_reg``). ``NewmarkOptions.consistent_stick_onset = False`` gives the former rule.
* **Friction direction at zero relative velocity.** The slip force is
  ``−μN w/√(|w|² + w_reg²)`` (:func:`slip_force`): exactly Coulomb for ``|w| ≫ w_reg``,
  zero and differentiable at ``w = 0`` (the paper's ``H(|v|)`` gives zero there too).
  A slipping face whose velocity reverses within a step (``w_{n+1}·w_n ≤ 0``) or
  falls below ``w_stick`` is tried in stick; a stuck face whose multiplier exceeds
  ``μN`` is released into slip in the direction of the multiplier's opposite.
* **Preload bookkeeping (Q12).** Each face carries the full nut preload ``N``: the
  limit per face is ``μN`` and the total sliding resistance in translation is ``2μN``.
"""
from __future__ import annotations

import numpy as np

from contact.errors import InputError

STICK = 1
SLIP = 0
PROJECTED = 2   # a face whose friction is Coulomb's law solved as a projection (:func:`coulomb_projection`)


def face_maps(width_m: float) -> tuple[np.ndarray, np.ndarray]:
    """Velocity maps of the right and left end faces, ``w_k = P_k u̇`` (Eqs. 50–51).

    Parameters
    ----------
    width_m : float
        Axial width ``l0`` of the bearing outer ring (m).

    Returns
    -------
    P_right, P_left : (2, 4) arrays
        ``P_right @ (ẏ, ż, θ̇y, θ̇z) = (ẏ + θ̇z l0/2, ż − θ̇y l0/2)`` and the left face
        with ``−l0/2``. Unit: m/s per (m/s, rad/s).
    """
    h = 0.5 * float(width_m)
    right = np.array([[1.0, 0.0, 0.0, h], [0.0, 1.0, -h, 0.0]])
    left = np.array([[1.0, 0.0, 0.0, -h], [0.0, 1.0, h, 0.0]])
    return right, left


def face_layout(width_m: float, mu_N: float, tilt_ignored: bool = False) -> tuple[np.ndarray, np.ndarray, int]:
    """The end faces as the integrators see them: maps, friction limits, number of active faces.

    With the tilt (the paper's model): the two faces of :func:`face_maps`, each limited to ``μN``.
    With the tilt ignored (Dai et al. 2025 §5.2: the angular deflections are neglected,
    "including the effect on the contact width and the angular moment M_sum", M_sum = M_n + M_τ,
    Eq. 49): one face at the ring centre, ``w = (ẏ, ż)``, limited to ``2μN`` (both faces' preload,
    Q12); its force ``Pᵀφ = (φy, φz, 0, 0)`` has no moment and its stick lock has no tilt rows. The
    second slot is then inactive (zero map, zero limit) and never tried in stick.

    Returns
    -------
    P : (2, 2, 4) array, face velocity maps (m/s per m/s, rad/s)
    limits_N : (2,) array, friction limit of each face (N)
    n_faces : int, active faces (2, or 1 with the tilt ignored)
    """
    if tilt_ignored:
        P = np.zeros((2, 2, 4))
        P[0, 0, 0] = P[0, 1, 1] = 1.0
        return P, np.array([2.0 * mu_N, 0.0]), 1
    right, left = face_maps(width_m)
    return np.stack([right, left]), np.array([mu_N, mu_N]), 2


def face_force_demand(force_N, moment_Nm, width_m: float) -> tuple[np.ndarray, np.ndarray]:
    """Split a total end-face force and moment into the two face forces (Eqs. 53–56).

    The total force ``F = (Fy, Fz)`` and moment ``M = (My, Mz)`` transmitted through the
    two end faces (acting on one body, about the ring centre) are carried by the right
    face at ``x = +l0/2`` and the left one at ``x = −l0/2``::

        f_l,y = Fy/2 − Mz/l0,   f_l,z = Fz/2 + My/l0
        f_r,y = Fy/2 + Mz/l0,   f_r,z = Fz/2 − My/l0

    (the paper's equations with the signs restored by statics, docs/reference/contact-laws.md §9).
    With ``force = f_s + f_n`` and ``moment = M_s + M_n`` (support dynamics plus radial
    contact) this is the paper's stick-test demand.

    Returns
    -------
    f_right, f_left : (2,) arrays in N.
    """
    F = np.asarray(force_N, dtype=float)
    M = np.asarray(moment_Nm, dtype=float)
    l0 = float(width_m)
    right = np.array([F[0] / 2 + M[1] / l0, F[1] / 2 - M[0] / l0])
    left = np.array([F[0] / 2 - M[1] / l0, F[1] / 2 + M[0] / l0])
    return right, left


def slip_force(w, mu_N: float, w_reg: float):
    """Coulomb slip force on the bearing at one face, ``−μN w/√(|w|² + w_reg²)`` (N).

    Parameters
    ----------
    w : (2,) array
        Relative sliding velocity of the face (m/s).
    mu_N : float
        Friction limit ``μ N`` of the face (N).
    w_reg : float
        Velocity (m/s) below which the direction is smoothed; makes the force zero
        and differentiable at ``w = 0`` (the 0/0 of ``w/|w|``).

    Returns
    -------
    force : (2,) array (N), jac : (2, 2) array ``∂force/∂w`` (N s/m).
    """
    s2 = w[0] * w[0] + w[1] * w[1] + w_reg * w_reg
    s = np.sqrt(s2)
    force = np.empty(2)
    force[0] = -mu_N * w[0] / s
    force[1] = -mu_N * w[1] / s
    jac = np.empty((2, 2))
    c = mu_N / (s2 * s)
    jac[0, 0] = -mu_N / s + c * w[0] * w[0]
    jac[0, 1] = c * w[0] * w[1]
    jac[1, 0] = c * w[1] * w[0]
    jac[1, 1] = -mu_N / s + c * w[1] * w[1]
    return force, jac


def coulomb_projection(fy: float, fz: float, wy: float, wz: float, mu_N: float, r: float):
    """Coulomb's law of one face as the projection ``f = proj_{|f| ≤ μN}(f − r w)`` (Alart & Curnier 1991).

    ``f`` (N) is the face's friction force over the step (the trapezoidal rule's step mean, Moreau 1988),
    ``w`` (m/s) its sliding velocity at the step's end, ``r`` (N s/m) the augmentation: any ``r > 0`` gives the
    same solution (``w = 0`` with ``|f| ≤ μN``, or ``f = −μN w/|w|``), it only scales the equation. No mode, no
    threshold and no regularisation: the map from ``(f, w)`` to the projection is Lipschitz-continuous, so a step
    solved with it has no jump (Clarke's generalised derivative at the disk's edge).

    Returns
    -------
    (py, pz, d00, d01, d11) : the projection ``p`` (N) and its derivative ``D = ∂p/∂q`` (symmetric, 2 × 2) with
    respect to ``q = f − r w``: ``I`` inside the disk (stuck), ``μN (I − q̂q̂ᵀ)/|q|`` outside (slipping).
    """
    qy = fy - r * wy
    qz = fz - r * wz
    n2 = qy * qy + qz * qz
    if mu_N > 0.0 and n2 <= mu_N * mu_N:
        return qy, qz, 1.0, 0.0, 1.0
    if n2 == 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    nq = np.sqrt(n2)
    ey = qy / nq
    ez = qz / nq
    c = mu_N / nq
    return mu_N * ey, mu_N * ez, c * (1.0 - ey * ey), -c * ey * ez, c * (1.0 - ez * ez)


def face_mode_update(mode: int, force, w_new, w_old, mu_N: float, w_stick: float, tried_stick: bool,
                     force_old=None, mean_weight: float = 0.0) -> int:
    """The stick test of one face after a converged step (Eqs. 57–58 with Q11 decided).

    Parameters
    ----------
    mode : int
        ``STICK`` or ``SLIP`` used for the step just solved.
    force : (2,) array
        Face force on the bearing from that solve (N): the multiplier if stuck.
    w_new, w_old : (2,) arrays
        Face sliding velocity at the end and at the start of the step (m/s).
    mu_N : float
        Static/kinetic friction limit ``μN`` of the face (N).
    w_stick : float
        A slipping face slower than this (m/s) is tried in stick.
    tried_stick : bool
        True if stick was already tried and rejected in this step (prevents cycling).
    force_old : (2,) array or None
        Face force at the start of the step (N).
    mean_weight : float
        0: test the end-of-step force (the paper's ``H(μN − |f|)`` at ``t_{n+1}``); 0.5: test the
        step mean ``(f_n + f_{n+1})/2``, i.e. Coulomb's bound on the friction *impulse* of the
        step (Moreau 1988), which is what the trapezoidal rule actually transmits. Pass a
        nonzero weight only for a face that was already stuck at the start of the step: across
        a slip→stick reversal the mean of the opposed forces would cancel and hide a slip.

    Returns
    -------
    int : the mode the step should be solved with (equal to ``mode`` if consistent).
    """
    if mode == STICK:
        fy = force[0]
        fz = force[1]
        if mean_weight != 0.0 and force_old is not None:
            fy = (1.0 - mean_weight) * fy + mean_weight * force_old[0]
            fz = (1.0 - mean_weight) * fz + mean_weight * force_old[1]
        f2 = fy * fy + fz * fz
        if f2 > mu_N * mu_N * (1.0 + 1e-12):
            return SLIP
        return STICK
    if tried_stick:
        return SLIP
    speed2 = w_new[0] * w_new[0] + w_new[1] * w_new[1]
    if speed2 <= w_stick * w_stick:
        return STICK
    if w_new[0] * w_old[0] + w_new[1] * w_old[1] <= 0.0:
        return STICK
    return SLIP


def lock_rows(n_dof: int, dofs_a, dofs_b) -> np.ndarray:
    """Linear equal-displacement constraints ``q[a_i] − q[b_i] = 0`` (the 3a/3b lock).

    Replaces the paper's squared ``g5`` (zero gradient at its solution) by one linear
    row per locked pair.

    Parameters
    ----------
    n_dof : int
        Number of generalised coordinates.
    dofs_a, dofs_b : sequences of int
        Paired DOF indices, e.g. (y3a, z3a) and (y3b, z3b).

    Returns
    -------
    (m, n_dof) array ``L`` with ``L q = 0``.
    """
    a = [int(i) for i in dofs_a]
    b = [int(i) for i in dofs_b]
    if len(a) != len(b):
        raise InputError(f"lock dofs: {len(a)} 'a' DOFs against {len(b)} 'b' DOFs: must pair up")
    L = np.zeros((len(a), int(n_dof)))
    for r, (i, j) in enumerate(zip(a, b)):
        if i == j or not (0 <= i < n_dof and 0 <= j < n_dof):
            raise InputError(f"lock dofs: pair ({i}, {j}) invalid for {n_dof} DOFs")
        L[r, i] = 1.0
        L[r, j] = -1.0
    return L


def null_space_map(L: np.ndarray) -> np.ndarray:
    """Orthonormal basis ``T`` of ``{q : L q = 0}``, so that ``q = T p`` satisfies the lock.

    Used by the production scheme to remove the linear 3a/3b rows exactly instead of
    carrying Lagrange multipliers.
    """
    L = np.atleast_2d(np.asarray(L, dtype=float))
    n = L.shape[1]
    if L.shape[0] == 0:
        return np.eye(n)
    _, s, vt = np.linalg.svd(L)
    rank = int(np.sum(s > 1e-12 * max(1.0, s.max())))
    return vt[rank:].T.copy()


def edge_offsets(u, width_m: float) -> tuple[float, float]:
    """Relative radial offsets ``|r1|, |r2|`` of the ring edges (m), docs/reference/contact-laws.md §8.

    ``r_1 = (y + θz l0/2, z − θy l0/2)`` (right edge), ``r_2`` with ``−l0/2``.
    Works on arrays of shape (..., 4) too.
    """
    u = np.asarray(u, dtype=float)
    h = 0.5 * float(width_m)
    r1 = np.hypot(u[..., 0] + h * u[..., 3], u[..., 1] - h * u[..., 2])
    r2 = np.hypot(u[..., 0] - h * u[..., 3], u[..., 1] + h * u[..., 2])
    return r1, r2
