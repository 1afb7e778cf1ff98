"""The loose-support rotor as both time integrators see it, and the checks they share.

The problem (Dai et al. 2025, Eq. 59)::

    M q̈ + (C − ωG) q̇ + K (q − Δq_m) = Q(t) + F_sum(q, q̇) + Φᵀ-forces,   G_c = 0

is described by :class:`RotorSystem` (matrices, :class:`HarmonicForce` ``Q``, misalignment
offset, 3a/3b lock rows, cubic coupling remainder) with its :class:`LooseSupport` and the
contact :class:`SupportLaw`. Both schemes, :mod:`rotor.dynamics.reference` (the paper's) and
:mod:`rotor.dynamics.production` (condensed, compiled), take a :class:`RotorSystem` and
:class:`NewmarkOptions` and return a :class:`Trajectory`; everything here is shared by them.
A system is built from the rotor model by :func:`rotor.dynamics.build.system_from_model`.

Time step too large for the contact stiffness: :func:`largest_stable_step` estimates
``2/ω_c`` from the law's tangent stiffness at a probe penetration and the relative
compliance ``B M⁻¹ Bᵀ``; :func:`check_time_step` raises :class:`InputError` naming the
step, the contact frequency and the largest stable step. (Average acceleration is
unconditionally stable for linear systems, but with ``ω_c Δt > 2`` a contact
event is crossed in fewer than about three steps: Newton then fails or the impact
energy is wrong.)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from contact.errors import InputError
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
    tilt_ignored : bool, the law passes no moment (Dai et al. 2025 §5.2); the support then
        passes none through its end faces either (:attr:`LooseSupport.tilt_ignored`).
    """

    name: str
    clearance_m: float
    force: Callable[[np.ndarray, np.ndarray], np.ndarray]
    kernel: Callable | None = None
    params: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tilt_ignored: bool = False


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
    tilt_ignored : bool, the paper's §5.2 case: no moment of any kind between bearing and
        support (one centred face, :func:`rotor.dynamics.constraints.face_layout`)
    """

    bearing_dofs: tuple
    support_dofs: tuple | None
    law: SupportLaw
    width_m: float
    mu: float
    preload_N: float
    tilt_ignored: bool = False

    def __post_init__(self):
        check_positive("width_m", self.width_m, "m", upper=1.0)
        check_positive("mu", self.mu, "-", allow_zero=True, upper=10.0)
        check_positive("preload_N", self.preload_N, "N", allow_zero=True)
        if len(self.bearing_dofs) != 4 or (self.support_dofs is not None and len(self.support_dofs) != 4):
            raise InputError("bearing_dofs/support_dofs: need 4 DOF indices (y, z, θy, θz) each")

    @property
    def mu_N(self) -> float:
        return self.mu * self.preload_N

    def faces(self) -> tuple[np.ndarray, np.ndarray, int]:
        """``(P (2, 2, 4), limits_N (2,), n_faces)`` of :func:`rotor.dynamics.constraints.face_layout`."""
        return cons.face_layout(self.width_m, self.mu_N, self.tilt_ignored)

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
    omega_dt_max: largest ω_c Δt met (contact frequency × step), located_events: friction events
    located inside a step (production scheme with ``NewmarkOptions.locate_events``).
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
    located_events: int = 0


FRICTION_SCHEMES = ("active-set", "projection")


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
    "Stick onset"; False: the former rule, which chatters at stops with the face force at μN), and
    ``locate_events`` (production scheme only, on by default: a slip velocity reversal, stick onset or release,
    and an edge's contact onset or loss, inside a step is located and the step split there, and a slow slip's
    friction is Coulomb's, held over the step, :mod:`rotor.dynamics.friction_events`,
    :mod:`rotor.dynamics.contact_events`; False: the plain step, switches on step boundaries, as the published
    studies before the fourth session of 2026-11-27 were computed), and ``friction_scheme`` (production scheme
    only): ``"active-set"`` (the default: everything above) or ``"projection"``: each face's Coulomb law solved
    inside the step's Newton as a projection onto the disk ``|f̄| ≤ μN`` of the step-mean force
    (:func:`rotor.dynamics.constraints.coulomb_projection`): no modes, no regularisation and no thresholds, so
    the step map has no jump; no event is located (``w_reg``, ``w_stick``, ``max_passes``,
    ``stick_mean_weight``, ``consistent_stick_onset`` and ``locate_events`` do not apply;
    :mod:`rotor.dynamics.projection_start`)."""

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
    locate_events: bool = True
    friction_scheme: str = "active-set"

    def __post_init__(self):
        if self.friction_scheme not in FRICTION_SCHEMES:
            raise InputError(f"friction_scheme: {self.friction_scheme!r}; must be one of {', '.join(FRICTION_SCHEMES)}")


# ---------------------------------------------------------------------------
# forces at a state, step-size and input checks (both schemes)
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
    P, limits, _ = sup.faces()
    phi = np.zeros((2, 2))
    g = fc.copy()
    for k in range(2):
        if modes[k] == cons.STICK:
            phi[k] = -lam_faces[k]
        else:
            phi[k], _ = cons.slip_force(P[k] @ w, limits[k], opts.w_reg)
        g += P[k].T @ phi[k]
    return u, w, fc, phi, B.T @ g


def relative_compliance(system: RotorSystem) -> np.ndarray:
    """``B M⁻¹ Bᵀ`` (4, 4): inverse effective mass of the relative motion (1/kg).

    With massless DOFs (``M`` singular on the constraint null space) they follow the massive ones
    statically, as the integrators take them (``rotor.dynamics.condense``): with ``N`` the massless
    directions and ``R`` the rest, ``x = R a + N b``, ``b = −(Nᵀ K N)⁻¹ Nᵀ K R a``, and the compliance is
    that of ``a`` through the condensed map."""
    B = system.support.relative_map(system.n)
    T = cons.null_space_map(system.lock)
    Mr = T.T @ system.M @ T
    Bt = B @ T
    w, V = np.linalg.eigh(0.5 * (Mr + Mr.T))
    light = w <= 1e-12 * max(float(w.max()), 1e-300)
    if not light.any():
        return Bt @ np.linalg.solve(Mr, Bt.T)
    N, R = V[:, light], V[:, ~light]
    Kr = T.T @ system.K @ T
    try:
        slave = -np.linalg.solve(N.T @ Kr @ N, N.T @ Kr @ R)
    except np.linalg.LinAlgError:
        raise InputError("massless DOFs held by no stiffness: give them a mass or inertia, or a spring") from None
    Bc = Bt @ (R + N @ slave)
    return Bc @ np.linalg.solve(R.T @ Mr @ R, Bc.T)


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


def check_inputs(system: RotorSystem, dt: float, n_steps: int, q0, v0):
    """Raise :class:`InputError` on a bad run request: step, step count, initial state (both schemes)."""
    check_positive("dt_s", dt, "s", upper=1.0)
    if int(n_steps) < 1:
        raise InputError(f"n_steps = {n_steps}: must be >= 1")
    check_finite("q0", q0, "m/rad")
    check_finite("v0", v0, "m/s, rad/s")
    if np.shape(q0) != (system.n,) or np.shape(v0) != (system.n,):
        raise InputError(f"q0/v0: shapes {np.shape(q0)}/{np.shape(v0)}, expected ({system.n},)")

