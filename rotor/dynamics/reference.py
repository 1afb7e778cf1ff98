"""Reference time integrator: the paper's Newmark-β scheme with constraints (Dai et al. 2025, §4).

Governing system (Eq. 59)::

    M q̈ + (C − ωG) q̇ + K (q − Δq_m) = Q(t) + F_sum(q, q̇) + Φᵀ-forces,   G_c = 0

with ``Q`` the harmonic loads (unbalance 1X, misalignment 2X, any static load),
``F_sum`` the loose-support force (radial contact from a law of :mod:`contact`, plus
Coulomb friction of the *slipping* end faces) and ``G_c`` the stuck-face velocity
rows and the 3a/3b lock rows (:mod:`rotor.dynamics.constraints`).

Scheme (Eqs. 64–74), as implemented here
----------------------------------------
1. Predictor (Eq. 66): ``q_pre = q_n + Δt q̇_n + Δt²(½ − β) q̈_n``,
   ``q̇_pre = q̇_n + Δt(1 − γ) q̈_n``.
2. Newton on ``z = [q̈_{n+1}; λ_{n+1}]`` (Eqs. 67–73) with the **finite-difference
   Jacobian** of Eq. 72 (one residual evaluation per unknown), started from
   ``z_0 = [q̈_n; λ_n]`` and stopped when ``‖Δz‖ ≤ ε (‖z‖ + z_floor)`` (Eq. 73).
   The constraint Jacobian Φ is also obtained by finite differences, as the paper says.
3. Correction (Eq. 74): ``q_{n+1} = q_pre + βΔt² q̈_{n+1}``, ``q̇_{n+1} = q̇_pre + γΔt q̈_{n+1}``.

Decision: **implicit reading of Eq. 69.** The flattened Eq. 69 writes the damping and
stiffness terms with ``q̇_pre, q_pre``. Read literally the scheme would be explicit
(conditionally stable, no energy conservation) and Φ = ∂G_c/∂q̈ of the velocity
constraints would vanish. Since the same notation is used for ``G_c(q̈, q̇_pre, q_pre)``
whose q̈-dependence is the whole point, we read both as "the corrected values
expressed through q̈" (Eq. 74), i.e. the standard implicit Newmark method.

Constraint rows are scaled so that the multipliers are forces: the lock rows are
``L q_{n+1}/(βΔt²)`` and the stick rows ``P_k w_{n+1}/(γΔt)``, hence ``Φ = ∂G_c/∂q̈`` is
``L`` and ``P_k B``, and the force of a stuck face on the bearing is ``−λ_k`` (N).
Everything about modes, the stick test and the traps is in :mod:`rotor.dynamics.constraints`.

Time step too large for the contact stiffness: :func:`largest_stable_step` estimates
``2/ω_c`` from the law's tangent stiffness at a probe penetration and the relative
compliance ``B M⁻¹ Bᵀ``; :func:`check_time_step` raises :class:`InputError` naming the
step, the contact frequency and the largest stable step. (Average acceleration is
unconditionally stable for linear systems, but with ``ω_c Δt > 2`` a contact
event is crossed in fewer than about three steps: Newton then fails or the impact
energy is wrong.)

Safeguards not in the paper (identical in both schemes, so they still agree)
--------------------------------------------------------------------------
* Backtracking on ``‖F‖`` when a full Newton step does not reduce it (kinks of the contact
  law: first touch, damping clip, edge switch).
* If Newton does not converge with a face slipping (the regularised direction
  ``w/√(|w|²+w_reg²)`` is very stiff near ``w = 0``), that face is tried in stick.
* The paper's sharp one-edge selection (contact-laws.md §8, Q8) is discontinuous where the two
  edge penetrations cross; there an implicit step can have no exact root. The contact layer
  regularises it by default (``LooseSupportParams.edge_transition_m``, :mod:`contact.tilt`), which
  removed every such step of the hard cases. If Newton still fails after the fallbacks, the
  least-residual iterate is accepted and counted in ``Trajectory.unconverged_steps`` (0 on the
  hard cases of ``benchmarks/bench_integrators.py`` section 4; 0–1 % of the steps with the sharp
  rule; reported by the benchmark and the ``simulate`` job).
* Initial modes: a face asked to start stuck whose holding force exceeds ``μN`` starts slipping
  (:func:`initial_state`).

This module is the *reference*: clear and faithful, not fast. Use
:mod:`rotor.dynamics.production` for real runs; the two agree to the Newton tolerance.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from contact.errors import ConvergenceError, InputError
from contact.units import check_finite, check_positive
from rotor.dynamics import constraints as cons

# ---------------------------------------------------------------------------
# problem description
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class HarmonicForce:
    """External load ``Q(t) = s + Σ_h [c_h cos(k_h Ω t) + s_h sin(k_h Ω t)]`` (N, N m).

    Unbalance is ``k = 1``, misalignment ``k = 2`` (Dai et al. 2025, Eqs. 34, 38–39).

    Attributes
    ----------
    static : (n,) array
    orders : (H,) array of harmonic orders ``k_h`` (–)
    cos, sin : (H, n) arrays
    omega_rad_s : float, base angular frequency Ω (rad/s)
    """

    static: np.ndarray
    orders: np.ndarray
    cos: np.ndarray
    sin: np.ndarray
    omega_rad_s: float

    def __call__(self, t: float) -> np.ndarray:
        ph = self.orders * (self.omega_rad_s * t)
        return self.static + np.cos(ph) @ self.cos + np.sin(ph) @ self.sin

    @staticmethod
    def zero(n: int, omega_rad_s: float = 0.0) -> "HarmonicForce":
        return HarmonicForce(np.zeros(n), np.zeros(0), np.zeros((0, n)), np.zeros((0, n)), float(omega_rad_s))

    @staticmethod
    def from_callable(func: Callable[[float], np.ndarray], n: int, omega_rad_s: float, max_order: int = 4) -> "HarmonicForce":
        """Exact harmonic coefficients of a trigonometric polynomial ``func(t)`` of order ≤ max_order.

        Samples ``func`` at ``2·max_order + 1`` instants of one period of Ω and inverts the
        DFT, so an unbalance/misalignment callable from the rotor model becomes a
        compiled-friendly table. Raises if the callable is not such a polynomial.
        """
        if omega_rad_s <= 0:
            f0 = np.asarray(func(0.0), dtype=float)
            return HarmonicForce(f0, np.zeros(0), np.zeros((0, n)), np.zeros((0, n)), 0.0)
        m = 2 * max_order + 1
        T = 2 * math.pi / omega_rad_s
        ts = np.arange(m) * T / m
        samples = np.array([np.asarray(func(t), dtype=float) for t in ts])
        spec = np.fft.rfft(samples, axis=0) / m
        static = spec[0].real
        orders = np.arange(1, max_order + 1, dtype=float)
        cos = 2 * spec[1:].real
        sin = -2 * spec[1:].imag
        hf = HarmonicForce(static, orders, cos, sin, float(omega_rad_s))
        tcheck = 0.3717 * T
        ref = np.asarray(func(tcheck), dtype=float)
        if not np.allclose(hf(tcheck), ref, rtol=1e-9, atol=1e-12 * (1 + np.abs(ref).max())):
            raise InputError(f"external force: not a trigonometric polynomial of order <= {max_order} in Ω = {omega_rad_s:g} rad/s")
        return hf


@dataclass(frozen=True)
class SupportLaw:
    """A loose-support contact law as the integrators see it.

    Attributes
    ----------
    name : str
    clearance_m : float
        Radial clearance δ0 (m); used for r1/r2 contact flags and the step check.
    force : callable ``(u (4,), v (4,)) -> f (4,)``
        Radial-surface force and moment on the bearing ``(Fy, Fz, My, Mz)`` (N, N m)
        from relative displacement/tilt ``u`` (m, rad) and velocity ``v`` (m/s, rad/s).
        End-face friction is *not* part of it (handled as constraints here).
    kernel : numba-compiled ``(u, v, params) -> (f, Ju, Jv)`` or None
        Same law with its analytic Jacobians, for :mod:`rotor.dynamics.production`.
    params : float array passed to ``kernel``.
    """

    name: str
    clearance_m: float
    force: Callable[[np.ndarray, np.ndarray], np.ndarray]
    kernel: Callable | None = None
    params: np.ndarray = field(default_factory=lambda: np.zeros(0))


@dataclass(frozen=True)
class LooseSupport:
    """The loose support between bearing (rotor node) and support node.

    Attributes
    ----------
    bearing_dofs : 4 ints, (y, z, θy, θz) of the rotor node carrying the bearing
    support_dofs : 4 ints or None (support is ground)
    law : SupportLaw
    width_m : float, ring width l0 (m)
    mu : float, end-face friction coefficient (–)
    preload_N : float, nut preload N per face (N); face limit is μN (Q12)
    """

    bearing_dofs: tuple
    support_dofs: tuple | None
    law: SupportLaw
    width_m: float
    mu: float
    preload_N: float

    def __post_init__(self):
        check_positive("width_m", self.width_m, "m", upper=1.0)
        check_positive("mu", self.mu, "-", allow_zero=True, upper=10.0)
        check_positive("preload_N", self.preload_N, "N", allow_zero=True)
        if len(self.bearing_dofs) != 4 or (self.support_dofs is not None and len(self.support_dofs) != 4):
            raise InputError("bearing_dofs/support_dofs: need 4 DOF indices (y, z, θy, θz) each")

    @property
    def mu_N(self) -> float:
        return self.mu * self.preload_N

    def relative_map(self, n: int) -> np.ndarray:
        """``B`` (4, n) with ``u = B q`` = bearing minus support."""
        B = np.zeros((4, n))
        for r, i in enumerate(self.bearing_dofs):
            B[r, i] = 1.0
        if self.support_dofs is not None:
            for r, j in enumerate(self.support_dofs):
                B[r, j] -= 1.0
        return B


@dataclass(frozen=True)
class RotorSystem:
    """``M q̈ + (C − ωG) q̇ + K(q − Δq_m) = Q(t) + F_sum`` with lock rows ``L q = 0``.

    Attributes
    ----------
    M, C, G, K : (n, n) arrays (kg, N s/m, kg m² per rad…, N/m) in SI
    omega_rad_s : float, spin speed ω (rad/s) multiplying G
    force : HarmonicForce
    offset : (n,) array Δq_m (m, rad), the misalignment origin shift (Eq. 40)
    lock : (m, n) array L of linear equal-displacement rows (3a/3b), may have 0 rows
    support : LooseSupport or None
    dof_names : tuple of n str
    coupling : None or ``((θy_a, θz_a), (θy_b, θz_b), a1)``: the cubic remainder
        ``−a1 |Δθ|² Δθ`` (N m, Δθ = θ_a − θ_b, a1 in N m/rad³) of the transition-shaft spring
        on node a, the opposite on node b (Dai et al. 2025 Eqs. 32, 44); its linear part is in K.
    """

    M: np.ndarray
    C: np.ndarray
    G: np.ndarray
    K: np.ndarray
    omega_rad_s: float
    force: HarmonicForce
    offset: np.ndarray
    lock: np.ndarray
    support: LooseSupport | None
    dof_names: tuple
    coupling: tuple | None = None

    def __post_init__(self):
        n = self.M.shape[0]
        for name in ("M", "C", "G", "K"):
            a = getattr(self, name)
            if a.shape != (n, n):
                raise InputError(f"{name}: shape {a.shape}, expected ({n}, {n})")
            check_finite(name, a, "SI")
        if self.lock.ndim != 2 or self.lock.shape[1] != n:
            raise InputError(f"lock: shape {self.lock.shape}, expected (m, {n})")
        if len(self.dof_names) != n:
            raise InputError(f"dof_names: {len(self.dof_names)} names for {n} DOFs")

    @property
    def n(self) -> int:
        return self.M.shape[0]

    @property
    def D(self) -> np.ndarray:
        """Velocity matrix ``C − ωG``."""
        return self.C - self.omega_rad_s * self.G


@dataclass
class Trajectory:
    """Time histories written by both integrators (every recorded step).

    t (N,), q/v/a (N, n), u/w (N, 4) relative displacement/velocity of the loose support,
    f_contact (N, 4) radial-surface force on the bearing, f_elastic (N, 4) its part at zero
    velocity, face_force (N, 2, 2) end-face force on the bearing [right, left][y, z],
    modes (N, 2) 1 = stick / 0 = slip, newton_iters (N,), passes (N,) active-set passes,
    omega_dt_max: largest ω_c Δt met (contact frequency × step).
    """

    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    u: np.ndarray
    w: np.ndarray
    f_contact: np.ndarray
    f_elastic: np.ndarray
    face_force: np.ndarray
    modes: np.ndarray
    newton_iters: np.ndarray
    passes: np.ndarray
    omega_dt_max: float = float("nan")
    scheme: str = ""
    unconverged_steps: int = 0


@dataclass(frozen=True)
class NewmarkOptions:
    """β, γ (average acceleration by default), Newton tolerance ε and iteration cap,
    friction regularisation velocity ``w_reg`` and stick threshold ``w_stick`` (m/s), active-set
    passes per step, and the stick test's weight of the start-of-step face force
    (``stick_mean_weight``: 0.5 = Coulomb bound on the step's friction impulse, the default;
    0 = on the end-of-step force, which lets the undamped trapezoidal multipliers ring and the
    faces chatter, see :func:`rotor.dynamics.constraints.face_mode_update`), and ``consistent_stick_onset``
    (True: stick onsets tested on, and restarted from, the consistent multipliers and
    acceleration; no low-speed stick trial right after a release; see :mod:`rotor.dynamics.constraints`,
    "Stick onset"; False: the former rule, which chatters at stops with the face force at μN)."""

    beta: float = 0.25
    gamma: float = 0.5
    tol: float = 1e-10
    # 80, not 25: on the Table 4 hard cases (10 revolutions at T/256) every least-residual step not at
    # the law's edge crossing (r1 = r2) was a Newton stall on the steep regularised friction
    # (backtracking, w_reg = 1 µm/s), not a missing root: 25 -> 80 iterations removes them
    # (clearance 1 mm 14 -> 0, μ = 1 8 -> 0, 0.001 mm 30 -> 8); 200 removes no more.
    max_iter: int = 80
    w_reg: float = 1e-6
    w_stick: float = 1e-5
    max_passes: int = 6
    stick_mean_weight: float = 0.5
    consistent_stick_onset: bool = True


# ---------------------------------------------------------------------------
# helpers shared with the production scheme
# ---------------------------------------------------------------------------


def coupling_map(system: RotorSystem) -> np.ndarray:
    """``E_c`` (2, n) with ``Δθ = E_c q`` (θ of node a minus node b); zero rows if no coupling."""
    Ec = np.zeros((2, system.n))
    if system.coupling is not None:
        (ia, ib, _) = system.coupling
        for r in range(2):
            Ec[r, ia[r]] += 1.0
            Ec[r, ib[r]] -= 1.0
    return Ec


def coupling_force(system: RotorSystem, q) -> np.ndarray:
    """Generalised force (n,) of the cubic coupling remainder at ``q``."""
    if system.coupling is None or system.coupling[2] == 0.0:
        return np.zeros(system.n)
    Ec = coupling_map(system)
    d = Ec @ q
    return Ec.T @ (-system.coupling[2] * float(d @ d) * d)


def support_forces(system: RotorSystem, q, v, modes, lam_faces, opts: NewmarkOptions):
    """Loose-support force pieces at state (q, v).

    Returns u, w (4,), radial force f_c (4,), face forces phi (2, 2) on the bearing
    (stuck faces: from their multipliers, ``φ = −λ``) and the generalised force (n,).
    """
    sup = system.support
    n = system.n
    if sup is None:
        z4 = np.zeros(4)
        return z4, z4, z4, np.zeros((2, 2)), np.zeros(n)
    B = sup.relative_map(n)
    u = B @ q
    w = B @ v
    fc = np.asarray(sup.law.force(u, w), dtype=float)
    P = cons.face_maps(sup.width_m)
    phi = np.zeros((2, 2))
    g = fc.copy()
    for k in range(2):
        if modes[k] == cons.STICK:
            phi[k] = -lam_faces[k]
        else:
            phi[k], _ = cons.slip_force(P[k] @ w, sup.mu_N, opts.w_reg)
        g += P[k].T @ phi[k]
    return u, w, fc, phi, B.T @ g


def relative_compliance(system: RotorSystem) -> np.ndarray:
    """``B M⁻¹ Bᵀ`` (4, 4): inverse effective mass of the relative motion (1/kg)."""
    B = system.support.relative_map(system.n)
    T = cons.null_space_map(system.lock)
    Mr = T.T @ system.M @ T
    Bt = B @ T
    return Bt @ np.linalg.solve(Mr, Bt.T)


def contact_stiffness(law: SupportLaw, probe_penetration_m: float | None = None) -> float:
    """Radial tangent stiffness of ``law`` (N/m) at a probe penetration (default 0.2 δ0),
    by a central difference along y at zero tilt and velocity."""
    d0 = law.clearance_m
    pen = 0.2 * d0 if probe_penetration_m is None else probe_penetration_m
    h = 1e-3 * pen
    z = np.zeros(4)
    up = np.array([d0 + pen + h, 0, 0, 0.0])
    um = np.array([d0 + pen - h, 0, 0, 0.0])
    return abs(float(law.force(up, z)[0] - law.force(um, z)[0]) / (2 * h))


def largest_stable_step(system: RotorSystem, probe_penetration_m: float | None = None) -> tuple[float, float]:
    """``(Δt_max, ω_c)``: the largest step ``2/ω_c`` resolving a contact event, and the contact
    angular frequency ``ω_c = √(k_c · (B M⁻¹ Bᵀ)_yy)`` (rad/s)."""
    if system.support is None:
        return math.inf, 0.0
    kc = contact_stiffness(system.support.law, probe_penetration_m)
    s = relative_compliance(system)[0, 0]
    wc = math.sqrt(kc * s)
    return (2.0 / wc if wc > 0 else math.inf), wc


def check_time_step(system: RotorSystem, dt: float, probe_penetration_m: float | None = None) -> float:
    """Raise :class:`InputError` if ``dt`` exceeds :func:`largest_stable_step`; return Δt_max."""
    check_positive("dt_s", dt, "s", upper=1.0)
    dt_max, wc = largest_stable_step(system, probe_penetration_m)
    if dt > dt_max:
        raise InputError(
            f"dt_s = {dt:.3e} s: too large for the contact stiffness (contact angular frequency "
            f"{wc:.4g} rad/s); the largest stable step is {dt_max:.3e} s (2/ω_c)")
    return dt_max


def initial_acceleration(system: RotorSystem, t0: float, q0, v0, modes, opts: NewmarkOptions):
    """Consistent ``q̈_0`` and multipliers at ``t0``: lock and stuck faces at acceleration level."""
    n = system.n
    rows = [system.lock]
    if system.support is not None:
        B = system.support.relative_map(n)
        P = cons.face_maps(system.support.width_m)
        rows += [P[k] @ B for k in range(2) if modes[k] == cons.STICK]
    Phi = np.vstack(rows) if rows else np.zeros((0, n))
    _, _, _, _, gnl = support_forces(system, q0, v0, [cons.SLIP if m == cons.SLIP else cons.STICK for m in modes], np.zeros((2, 2)), opts)
    rhs = system.force(t0) - system.D @ v0 - system.K @ (q0 - system.offset) + gnl + coupling_force(system, q0)
    m = Phi.shape[0]
    A = np.block([[system.M, Phi.T], [Phi, np.zeros((m, m))]])
    z = np.linalg.solve(A, np.concatenate([rhs, np.zeros(m)]))
    return z[:n], z[n:]


def initial_state(system: RotorSystem, t0: float, q0, v0, modes0, opts: NewmarkOptions):
    """``(q̈_0, multipliers, modes)``: like :func:`initial_acceleration`, with the stick test applied
    to the requested initial modes (a face whose holding force exceeds μN starts slipping)."""
    modes = list(modes0)
    n_l = system.lock.shape[0]
    for _ in range(3):
        a0, lam = initial_acceleration(system, t0, q0, v0, modes, opts)
        if system.support is None:
            return a0, lam, modes
        j = n_l
        changed = False
        for k in range(2):
            if modes[k] == cons.STICK:
                if float(np.hypot(*lam[j:j + 2])) > system.support.mu_N * (1 + 1e-12):
                    modes[k] = cons.SLIP
                    changed = True
                j += 2
        if not changed:
            return a0, lam, modes
    return a0, lam, modes


def _allocate(n_rec: int, n: int) -> Trajectory:
    return Trajectory(
        t=np.zeros(n_rec), q=np.zeros((n_rec, n)), v=np.zeros((n_rec, n)), a=np.zeros((n_rec, n)),
        u=np.zeros((n_rec, 4)), w=np.zeros((n_rec, 4)), f_contact=np.zeros((n_rec, 4)),
        f_elastic=np.zeros((n_rec, 4)), face_force=np.zeros((n_rec, 2, 2)),
        modes=np.zeros((n_rec, 2), dtype=np.int8), newton_iters=np.zeros(n_rec, dtype=np.int32),
        passes=np.zeros(n_rec, dtype=np.int32))


def _check_inputs(system: RotorSystem, dt: float, n_steps: int, q0, v0):
    check_positive("dt_s", dt, "s", upper=1.0)
    if int(n_steps) < 1:
        raise InputError(f"n_steps = {n_steps}: must be >= 1")
    check_finite("q0", q0, "m/rad")
    check_finite("v0", v0, "m/s, rad/s")
    if np.shape(q0) != (system.n,) or np.shape(v0) != (system.n,):
        raise InputError(f"q0/v0: shapes {np.shape(q0)}/{np.shape(v0)}, expected ({system.n},)")


# ---------------------------------------------------------------------------
# the reference scheme
# ---------------------------------------------------------------------------


def _split_multipliers(lam, n_lock: int, modes, n_faces: int):
    """``(lock multipliers, (2, 2) face multipliers)`` from the stacked vector: the lock rows first,
    then two per stuck face in face order (slipping faces carry none: zero rows)."""
    lam_face = np.zeros((2, 2))
    j = n_lock
    for k in range(n_faces):
        if modes[k] == cons.STICK:
            lam_face[k] = lam[j:j + 2]
            j += 2
    return lam[:n_lock], lam_face


def simulate_reference(system: RotorSystem, dt: float, n_steps: int, q0=None, v0=None, *, t0: float = 0.0,
                       modes0=(cons.STICK, cons.STICK), options: NewmarkOptions | None = None,
                       record_every: int = 1, check_step: bool = True) -> Trajectory:
    """Integrate ``n_steps`` steps of ``dt`` (s) with the paper's scheme (Eqs. 64–74).

    Parameters
    ----------
    system : RotorSystem
    dt : float, time step (s)
    n_steps : int
    q0, v0 : (n,) initial displacement (m, rad) and velocity (m/s, rad/s); zero by default
    modes0 : initial end-face modes (right, left); STICK by default (Section 3.3)
    options : NewmarkOptions
    record_every : keep every k-th step in the Trajectory
    check_step : raise InputError if dt exceeds the largest stable step

    Raises
    ------
    ConvergenceError if Newton does not converge within ``max_iter`` iterations
    (names the step, time and reached tolerance), InputError on bad input.
    """
    opts = options or NewmarkOptions()
    n = system.n
    q0 = np.zeros(n) if q0 is None else np.asarray(q0, dtype=float).copy()
    v0 = np.zeros(n) if v0 is None else np.asarray(v0, dtype=float).copy()
    _check_inputs(system, dt, n_steps, q0, v0)
    if system.support is not None and check_step:
        check_time_step(system, dt)
    beta, gamma = opts.beta, opts.gamma
    M, K, D, L = system.M, system.K, system.D, system.lock
    off = system.offset
    sup = system.support
    B = sup.relative_map(n) if sup is not None else np.zeros((4, n))
    P = cons.face_maps(sup.width_m) if sup is not None else (np.zeros((2, 4)), np.zeros((2, 4)))
    mu_N = sup.mu_N if sup is not None else 0.0
    n_faces = 2 if sup is not None else 0
    modes = [int(m) for m in modes0][:n_faces] + [cons.SLIP] * (2 - n_faces)

    a, lam, modes = initial_state(system, t0, q0, v0, modes, opts)
    q, v = q0, v0
    lam_lock, lam_face = _split_multipliers(lam, L.shape[0], modes, n_faces)

    n_rec = n_steps // record_every + 1
    tr = _allocate(n_rec, n)
    tr.scheme = "reference (paper, FD-Newton)"
    u, w, fc, phi, _ = support_forces(system, q, v, modes, lam_face, opts)

    def record(i, t, its, passes):
        tr.t[i], tr.q[i], tr.v[i], tr.a[i] = t, q, v, a
        tr.u[i], tr.w[i], tr.f_contact[i] = u, w, fc
        if sup is not None:
            tr.f_elastic[i] = sup.law.force(u, np.zeros(4))
        tr.face_force[i] = phi
        tr.modes[i] = modes
        tr.newton_iters[i] = its
        tr.passes[i] = passes

    record(0, t0, 0, 0)
    just_released = [False, False]
    bdt2 = beta * dt * dt
    gdt = gamma * dt
    for step in range(1, n_steps + 1):
        t = t0 + step * dt
        q_pre = q + dt * v + dt * dt * (0.5 - beta) * a
        v_pre = v + dt * (1 - gamma) * a
        Q = system.force(t)
        w_old = [P[k] @ (B @ v) for k in range(2)]
        phi_old = phi.copy()
        tried_stick = [modes[k] == cons.STICK for k in range(2)]
        stuck_at_start = list(tried_stick)
        freeze = [None, None]
        passes = 0
        total_its = 0
        while True:
            passes += 1
            stuck = [k for k in range(n_faces) if modes[k] == cons.STICK]

            def constraints(acc, stuck=stuck):
                qn = q_pre + bdt2 * acc
                vn = v_pre + gdt * acc
                g = [L @ qn / bdt2]
                for k in stuck:
                    g.append(P[k] @ (B @ vn) / gdt)
                return np.concatenate(g)

            m = L.shape[0] + 2 * len(stuck)
            # Φ = ∂G_c/∂q̈ by finite differences (the paper's "analogy to Eq. 72")
            g0 = constraints(a)
            Phi = np.empty((m, n))
            for jj in range(n):
                h = 1e-7 * max(abs(a[jj]), 1.0)
                e = a.copy()
                e[jj] += h
                Phi[:, jj] = (constraints(e) - g0) / h

            def residual(z, stuck=stuck, Phi=Phi, freeze=freeze):
                acc = z[:n]
                lam_ = z[n:]
                qn = q_pre + bdt2 * acc
                vn = v_pre + gdt * acc
                r = M @ acc + D @ vn + K @ (qn - off) - Q + Phi.T @ lam_ - coupling_force(system, qn)
                if sup is not None:
                    un = B @ qn
                    wn = B @ vn
                    gl = np.asarray(sup.law.force(un, wn), dtype=float).copy()
                    for k in range(2):
                        if modes[k] == cons.SLIP:
                            if freeze[k] is not None:
                                gl += P[k].T @ freeze[k]
                            else:
                                gl += P[k].T @ cons.slip_force(P[k] @ wn, mu_N, opts.w_reg)[0]
                    r -= B.T @ gl
                return np.concatenate([r, constraints(acc)])

            # initial iterate z0 = [q̈_n; λ_n] (Eq. 70), multipliers of the current rows
            lam0 = [lam_lock]
            for k in stuck:
                lam0.append(lam_face[k])
            z = np.concatenate([a] + lam0)
            z, its, ok, err = _fd_newton(residual, z, opts.tol, opts.max_iter)
            total_its += its
            if not ok:
                # slip Newton stalls when the true answer is (near) stick: try stick on the
                # slipping faces not yet tried in this step (same rule as rotor.dynamics.production)
                flip = [k for k in range(n_faces) if modes[k] == cons.SLIP and not tried_stick[k]]
                if flip and passes < opts.max_passes + 4:
                    for k in flip:
                        modes[k] = cons.STICK
                        tried_stick[k] = True
                    freeze = [None, None]
                    continue
                if np.all(np.isfinite(z)):
                    # no exact root (e.g. the sharp one-edge selection of the law, edge_transition_m
                    # = 0): keep the least-residual iterate and count the step, as rotor.dynamics.production does
                    tr.unconverged_steps += 1
                    ok = True
            if not ok:
                raise ConvergenceError(
                    f"reference Newton (finite-difference Jacobian) did not converge at step {step}, t = {t:.6g} s: "
                    f"|dz|/|z| = {err:.3e} > tol = {opts.tol:.1e} after {opts.max_iter} iterations; reduce dt_s = {dt:.3e} s")
            a_new = z[:n]
            lam_new = z[n:]
            if any(f is not None for f in freeze):
                # second stage of a release: now with the implicit slip direction
                freeze = [None, None]
                a = a_new
                continue
            lam_lock_new = lam_new[:L.shape[0]]
            lam_face_new = np.zeros((2, 2))
            jj = L.shape[0]
            for k in stuck:
                lam_face_new[k] = lam_new[jj:jj + 2]
                jj += 2
            v_new = v_pre + gdt * a_new
            changed = False
            new_modes = list(modes)
            onset_trial = [modes[k] == cons.STICK and not stuck_at_start[k] for k in range(n_faces)]
            if opts.consistent_stick_onset and any(onset_trial):
                # a face trying stick (slipping at the start of the step) is tested on its holding force
                # at the end of the step: the consistent multiplier, not the trapezoidal one; a stuck
                # other face on its consistent multiplier too (the one the step will keep)
                _, lam_c = initial_acceleration(system, t, q_pre + bdt2 * a_new, v_new, modes, opts)
                jj = L.shape[0]
                for k in stuck:
                    lam_face_new[k] = lam_c[jj:jj + 2]
                    jj += 2
            for k in range(n_faces):
                wk = P[k] @ (B @ v_new)
                if modes[k] == cons.STICK:
                    fk = -lam_face_new[k]
                else:
                    fk = cons.slip_force(wk, mu_N, opts.w_reg)[0]
                w_stick = 0.0 if just_released[k] else opts.w_stick
                nm = cons.face_mode_update(modes[k], fk, wk, w_old[k], mu_N, w_stick, tried_stick[k],
                                           phi_old[k], opts.stick_mean_weight if stuck_at_start[k] else 0.0)
                if nm != modes[k]:
                    changed = True
                    new_modes[k] = nm
                    if nm == cons.STICK:
                        tried_stick[k] = True
                    else:
                        # release: first solve with the friction force frozen at μN along the held force
                        nrm = math.hypot(fk[0], fk[1])
                        freeze[k] = mu_N * fk / nrm if nrm > 0 else np.zeros(2)
            if not changed or passes >= opts.max_passes:
                a = a_new
                lam_lock = lam_lock_new
                lam_face = lam_face_new
                break
            modes = new_modes
            a = a_new if not any(f is not None for f in freeze) else a
        q = q_pre + bdt2 * a
        v = v_pre + gdt * a
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(v))):
            raise ConvergenceError(f"reference scheme: non-finite state at step {step}, t = {t:.6g} s; reduce dt_s = {dt:.3e} s")
        if opts.consistent_stick_onset:
            just_released = [stuck_at_start[k] and modes[k] == cons.SLIP for k in range(2)]
            if any(modes[k] == cons.STICK and not stuck_at_start[k] for k in range(n_faces)):
                # stick onset: restart from the consistent acceleration and multipliers (q, v kept)
                a, lam = initial_acceleration(system, t, q, v, modes, opts)
                lam_lock, lam_face = _split_multipliers(lam, L.shape[0], modes, n_faces)
        u, w, fc, phi, _ = support_forces(system, q, v, modes, lam_face, opts)
        if step % record_every == 0:
            record(step // record_every, t, total_its, passes)
    return tr


def _fd_newton(residual, z, tol, max_iter):
    """Discrete Newton (Eqs. 71–73): Jacobian by forward differences, one column per unknown.

    Stops when ``‖Δz‖ ≤ tol (‖z‖ + 1e-12)`` (Eq. 73). Safeguard not in the paper: when a full
    step does not decrease ``‖F‖`` (a kink of the contact law or of friction), the step is
    halved until it does (Armijo backtracking), as in :mod:`rotor.dynamics.production`.
    """
    err = math.inf
    F0 = residual(z)
    nF = np.linalg.norm(F0)
    best, best_n = z, nF
    for it in range(1, max_iter + 1):
        J = np.empty((z.size, z.size))
        for j in range(z.size):
            h = 1e-7 * max(abs(z[j]), 1e-3)
            e = z.copy()
            e[j] += h
            J[:, j] = (residual(e) - F0) / h
        try:
            dz = np.linalg.solve(J, F0)
        except np.linalg.LinAlgError:
            return z, it, False, math.inf
        err = np.linalg.norm(dz) / (np.linalg.norm(z) + 1e-12)
        if not np.isfinite(err):
            return z, it, False, err
        if err <= tol:
            return z - dz, it, True, err
        lam = 1.0
        for _ in range(40):
            zt = z - lam * dz
            Ft = residual(zt)
            nFt = np.linalg.norm(Ft)
            if nFt <= (1 - 1e-4 * lam) * nF or nFt == 0.0:
                break
            lam *= 0.5
        z, F0, nF = zt, Ft, nFt
        if nF < best_n:
            best, best_n = z, nF
    return best, max_iter, False, err


# ---------------------------------------------------------------------------
# building a system from the rotor model and a law from contact.loose_support
# ---------------------------------------------------------------------------


def support_law_from_params(params) -> SupportLaw:
    """Wrap :class:`contact.loose_support.LooseSupportParams` as a :class:`SupportLaw`.

    End-face friction is removed from the law (μN = 0 in its kernel arguments): the
    integrators treat the faces as stick/slip constraints themselves. Everything else
    (law, modulus, damping ``c_c`` in s/m, tilt geometry or ``tilt_ignored``) is the
    contact layer's.
    """
    import dataclasses

    from contact.loose_support import loose_support_force

    radial = dataclasses.replace(params, mu=0.0, preload_N=0.0, friction_smoothing_m_s=0.0)

    def force(u, v):
        r = loose_support_force(radial, u[0], u[1], u[2], u[3], v[0], v[1], v[2], v[3])
        return np.array([float(r.Fy_N), float(r.Fz_N), float(r.My_Nm), float(r.Mz_Nm)])

    from rotor.dynamics.production import contact_kernel

    law_label = getattr(params, "calibration_name", "") or params.law  # calibrated laws by their stored name
    name = f"{law_label}{' (tilt ignored)' if params.tilt_ignored else ''}"
    return SupportLaw(name, float(params.clearance_m), force, contact_kernel, np.array(radial.kernel_args, dtype=float))


def system_from_model(model, scene, speed_rad_s: float, *, law: SupportLaw | None = None, law_name: str = "conformal",
                      tilt_ignored: bool = False,
                      mu: float | None = None, preload_N: float | None = None, clearance_m: float | None = None,
                      misalignment_m: float | None = None, nonlinear_coupling: bool = True) -> RotorSystem:
    """The loose-support rotor of a scene at spin speed ``speed_rad_s`` (rad/s).

    Uses the rotor model API (``rotor.model.assembly``): ``K + K_c`` with the misalignment offset
    ``Δq_m`` (the ``K_c Δq_m`` term moves to the static load, since the coupling spring is
    not shifted), unbalance (1X) and misalignment excitation (2X), the two linear 3a/3b rows
    ``model.B`` (not the squared g5), the cubic coupling remainder, and the loose support with
    the contact law of the scene (``contact.loose_support``; the paper's conformal law as
    published by default). Overrides: ``law`` (any :class:`SupportLaw`, e.g. a calibrated one
    wrapped by :func:`support_law_from_params`), ``law_name`` (a law of
    ``contact.loose_support`` by name: "conformal", "pereira"), ``tilt_ignored``
    (paper Fig. 16), ``mu``, ``preload_N``, ``clearance_m``, ``misalignment_m`` (δ, scales
    Δq_m and the 2X excitation, which are both linear in δ for small angles; 0 removes both).
    """
    from contact.loose_support import LooseSupportParams
    from rotor.model import assembly as rm

    ls = scene.loose_support
    n = model.n_dofs
    check_positive("speed_rad_s", speed_rad_s, "rad/s", allow_zero=True, upper=1e4)
    mu_v = ls.friction_coefficient if mu is None else mu
    pre_v = ls.preload_n if preload_N is None else preload_N
    if law is None:
        params = LooseSupportParams(
            clearance_m=ls.clearance_m if clearance_m is None else clearance_m, width_m=ls.ring_width_m,
            bearing_E_Pa=ls.bearing_modulus_pa, bearing_nu=ls.bearing_poisson,
            support_E_Pa=ls.support_modulus_pa, support_nu=ls.support_poisson,
            c_c_s_per_m=ls.collision_factor_s_m, tilt_ignored=tilt_ignored, law=law_name)
        law = support_law_from_params(params)
    sup = LooseSupport(tuple(model.loose_pair.bearing), tuple(model.loose_pair.support), law,
                       ls.ring_width_m, mu_v, pre_v)
    off = rm.misalignment_offset(model)
    loads = rm.harmonic_loads(model, speed_rad_s)
    delta0 = scene.misalignment.offset_m if getattr(scene, "misalignment", None) is not None else 0.0
    scale = 1.0
    if misalignment_m is not None:
        check_positive("misalignment_m", misalignment_m, "m", allow_zero=True, upper=0.05)
        if delta0 == 0.0 and misalignment_m > 0:
            raise InputError("misalignment_m: the scene has no misalignment to scale; set it in the scene")
        scale = misalignment_m / delta0 if delta0 else 0.0
    off = off * scale
    orders = np.array(sorted(loads), dtype=float)
    cos = np.array([loads[k][0] * (scale if k == 2 else 1.0) for k in sorted(loads)]).reshape(len(orders), n)
    sin = np.array([loads[k][1] * (scale if k == 2 else 1.0) for k in sorted(loads)]).reshape(len(orders), n)
    static = -model.K_c @ off
    force = HarmonicForce(static, orders, cos, sin, float(speed_rad_s))
    L = np.asarray(model.B, dtype=float)  # the two linear 3a/3b rows (not the squared g5)
    coupling = None
    if nonlinear_coupling and model.couplings:
        cp = model.couplings[0]
        if cp.a1_n_m_rad3 != 0.0:
            coupling = ((cp.a[2], cp.a[3]), (cp.b[2], cp.b[3]), float(cp.a1_n_m_rad3))
    return RotorSystem(model.M, model.C, model.G, model.K + model.K_c, float(speed_rad_s), force, off, L, sup,
                       tuple(model.dof_names), coupling)


def linear_initial_state(system: RotorSystem, t0: float = 0.0, lock_support: bool = True):
    """``(q0, v0)``: the exact periodic solution at ``t0`` of the *linear* system with the loose
    support locked (bearing and support moving together, both end faces stuck) or free.

    A good start for a steady-state run: the 1X/2X response of the rotor is already there,
    so only the (much smaller) nonlinear correction has to decay. Static part
    ``K (q − Δq_m) = static``, harmonics ``(K − (kΩ)² M + i kΩ D) X_k = c_k − i s_k``.
    """
    n = system.n
    rows = [system.lock]
    if lock_support and system.support is not None:
        rows.append(system.support.relative_map(n))
    T = cons.null_space_map(np.vstack(rows))
    Mr, Dr, Kr = T.T @ system.M @ T, T.T @ system.D @ T, T.T @ system.K @ T
    f = system.force
    q = T @ np.linalg.solve(Kr, T.T @ (f.static + system.K @ system.offset))
    v = np.zeros(n)
    for k, c, s in zip(f.orders, f.cos, f.sin):
        wk = k * f.omega_rad_s
        X = T @ np.linalg.solve(Kr - wk * wk * Mr + 1j * wk * Dr, T.T @ (c - 1j * s))
        e = np.exp(1j * wk * t0)
        q += (X * e).real
        v += (1j * wk * X * e).real
    return q, v
