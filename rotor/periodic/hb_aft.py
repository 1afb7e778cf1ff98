"""The harmonic-balance pieces of :mod:`rotor.periodic.harmonic_balance`: Fourier matrices, the system in the
harmonic domain, and the nonlinear forces by alternating frequency-time (AFT) with their analytic Jacobian.

Fourier series (real form, fundamental ``ω = Ω/P`` with ``P`` the period in revolutions)::

    q(t) = a_0 + Σ_{k=1..H} a_k cos(kωt) + b_k sin(kωt)

The coefficients of the reduced coordinates ``p`` (``q = T p``, ``T`` the null space of the 3a/3b lock,
:func:`rotor.dynamics.constraints.null_space_map`) are stored harmonic-major, ``Z[(2H+1), n_r]`` with rows
``a_0, a_1, b_1, …, a_H, b_H``. The linear part ``M q̈ + (C − ΩG) q̇ + K(q − Δq_m)`` is block diagonal in the
harmonics (Krack & Gross 2019, *Harmonic Balance for Nonlinear Vibration Problems*, §2.4). The support's
contact force and the cubic coupling remainder are evaluated by AFT (Cameron & Griffin 1989): the coefficients
are sampled at ``N`` instants of one period (inverse DFT as a matrix ``E``), the force is evaluated there with
the very compiled law the time integration steps with (:func:`rotor.dynamics.kernels.contact_point`, the
production scheme's call), and projected back (forward DFT as the matrix ``Π``, ``Π E = I`` for ``N ≥ 2H+1``).
Its derivative is the time-domain Jacobian of the law (``∂f/∂u``, ``∂f/∂u̇``, analytic in
:mod:`contact._kernel`) carried through the same matrices: ``∂F/∂Z = Π (J_u E + ω J_v E')`` per sample.
"""
from __future__ import annotations

import copy
import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from contact.compiled_cache import compiled_with
from contact.errors import InputError, OutsideDomainError
from rotor.dynamics import constraints as cons
from rotor.dynamics.kernels import contact_kernel, contact_point
from rotor.dynamics.system import RotorSystem, SupportLaw, coupling_map

# _law_samples inlines the law kernel (rotor.dynamics.kernels, which inlines contact._kernel).
compiled_with(__file__, ["rotor.dynamics.kernels", "contact._kernel", "contact._kernel_friction", "contact._kernel_tilt"])


@njit(cache=True)
def _law_samples(U, V, params, F, J):
    """The support law at the rows of ``U``, ``V`` (N, 4): forces into ``F`` (N, 4), ``∂f/∂(u, v)`` into ``J``
    (N, 4, 8). Raises :class:`contact.errors.OutsideDomainError` beyond the conformal law's neat-fit limit."""
    jac = np.empty((4, 8))
    for j in range(U.shape[0]):
        F[j, 0], F[j, 1], F[j, 2], F[j, 3] = contact_point(U[j, 0], U[j, 1], U[j, 2], U[j, 3], V[j, 0], V[j, 1],
                                                           V[j, 2], V[j, 3], params, jac)
        J[j] = jac


@dataclass(frozen=True)
class Fourier:
    """The DFT matrices of ``H`` harmonics on ``N`` samples of one period (phases ``θ_j = 2πj/N``).

    ``E`` (N, 2H+1): samples of the coefficients; ``dE`` (N, 2H+1): of their derivative in the phase
    (``q̇ = ω dE Z``); ``Pi`` (2H+1, N): the forward DFT (coefficients of sampled values, exact for
    trigonometric polynomials of order < N/2); ``orders`` (2H+1,): the harmonic order of each row (0, 1, 1, …)."""

    harmonics: int
    n_time: int
    E: np.ndarray
    dE: np.ndarray
    Pi: np.ndarray
    orders: np.ndarray


def fourier(harmonics: int, n_time: int) -> Fourier:
    """:class:`Fourier` of ``harmonics`` (H ≥ 1) harmonics on ``n_time`` samples (≥ 2H+1)."""
    H, N = int(harmonics), int(n_time)
    if H < 1 or H != harmonics:
        raise InputError(f"harmonics = {harmonics}: must be a whole number >= 1")
    if N < 2 * H + 1 or N != n_time:
        raise InputError(f"n_time = {n_time}: must be a whole number >= 2H+1 = {2 * H + 1} samples")
    th = 2.0 * math.pi * np.arange(N) / N
    orders = np.concatenate([[0], np.repeat(np.arange(1, H + 1), 2)]).astype(float)
    E = np.empty((N, 2 * H + 1))
    dE = np.zeros((N, 2 * H + 1))
    E[:, 0] = 1.0
    for k in range(1, H + 1):
        c, s = np.cos(k * th), np.sin(k * th)
        E[:, 2 * k - 1], E[:, 2 * k] = c, s
        dE[:, 2 * k - 1], dE[:, 2 * k] = -k * s, k * c
    Pi = E.T * np.where(orders == 0, 1.0, 2.0)[:, None] / N
    return Fourier(H, N, E, dE, Pi, orders)


@dataclass(frozen=True)
class HarmonicSystem:
    """A :class:`~rotor.dynamics.system.RotorSystem` at one speed in the harmonic domain.

    Attributes
    ----------
    system : the system; speed_rad_s : its spin speed Ω (rad/s); omega_rad_s : the fundamental ω = Ω/P
    period_revs : P; fourier : :class:`Fourier`
    T : (n, n_r) lock null space (``q = T p``)
    A : (n_h n_r, n_h n_r) linear dynamic stiffness in the harmonic domain (``n_h = 2H+1``; N/m, N/rad)
    dA_domega : its derivative in ω at fixed matrices
    load : (n_h n_r,) harmonic coefficients of ``Tᵀ(Q(t) + K Δq_m)`` (N)
    Bs : (4, n_r) support relative map ``u = B T p``, or None; law_params : the compiled law's parameters
    clearance_m : δ0 (m) or nan; width_m : ring width (m) or nan; tilt_ignored : bool
    Ec : (2, n_r) coupling map ``Δθ = E_c T p`` or None; a1 : coupling cubic coefficient (N m/rad³)
    Mr, Dr, Kr : (n_r, n_r) reduced mass, velocity (``C − ΩG``) and stiffness matrices
    """

    system: RotorSystem
    speed_rad_s: float
    omega_rad_s: float
    period_revs: int
    fourier: Fourier
    T: np.ndarray
    A: np.ndarray
    dA_domega: np.ndarray
    load: np.ndarray
    Bs: np.ndarray | None
    law_params: np.ndarray | None
    clearance_m: float
    width_m: float
    tilt_ignored: bool
    Ec: np.ndarray | None
    a1: float
    Mr: np.ndarray
    Dr: np.ndarray
    Kr: np.ndarray

    @property
    def n_r(self) -> int:
        return self.T.shape[1]


def hb_not_applicable(system: RotorSystem) -> str | None:
    """Why harmonic balance does not apply to ``system`` (one line), or None when it does: HB here takes the
    end faces frictionless (no stick/slip states; ``μ N = 0``) and the support law compiled (the production
    scheme's kernel)."""
    sup = system.support
    if sup is None:
        return None
    if sup.mu_N > 0.0:
        return (f"HB does not apply: end-face friction (stick/slip), mu = {sup.mu:g} with preload_N = "
                f"{sup.preload_N:g} N; use shooting")
    if sup.law.kernel is not contact_kernel:
        return f"HB does not apply: the support law {sup.law.name!r} has no compiled kernel; use shooting"
    return None


def linear_blocks(M, D, K, fourier_: Fourier, omega: float):
    """``A`` and ``∂A/∂ω`` (at fixed M, D, K) of the harmonic-major layout (see the module docstring)."""
    H, nr = fourier_.harmonics, M.shape[0]
    nh = 2 * H + 1
    A = np.zeros((nh * nr, nh * nr))
    dA = np.zeros_like(A)
    A[:nr, :nr] = K
    for k in range(1, H + 1):
        w = k * omega
        c, s = slice((2 * k - 1) * nr, 2 * k * nr), slice(2 * k * nr, (2 * k + 1) * nr)
        Kd = K - w * w * M
        A[c, c], A[s, s], A[c, s], A[s, c] = Kd, Kd, w * D, -w * D
        dK = -2.0 * k * w * M
        dA[c, c], dA[s, s], dA[c, s], dA[s, c] = dK, dK, k * D, -k * D
    return A, dA


def _load(system: RotorSystem, T, fourier_: Fourier, P: int) -> np.ndarray:
    """Harmonic coefficients (n_h n_r,) of ``Tᵀ(Q(t) + K Δq_m)``; a load order beyond H is refused."""
    f = system.force
    H, nr = fourier_.harmonics, T.shape[1]
    out = np.zeros((2 * H + 1, nr))
    out[0] = T.T @ (f.static + system.K @ system.offset)
    for order, c, s in zip(f.orders, f.cos, f.sin):
        k = float(order) * P
        if k != round(k) or k < 0:
            raise InputError(f"load order {order:g}: not a whole multiple of the HB fundamental (period {P} revs)")
        k = int(round(k))
        if k == 0:
            out[0] += T.T @ c
        elif k > H:
            if np.any(c) or np.any(s):
                raise InputError(f"harmonics = {H}: the load has order {order:g} (harmonic {k} of the period); "
                                 f"use harmonics >= {k}")
        else:
            out[2 * k - 1] += T.T @ c
            out[2 * k] += T.T @ s
    return out.reshape(-1)


def harmonic_system(system: RotorSystem, fourier_: Fourier, period_revs: int = 1) -> HarmonicSystem:
    """The system in the harmonic domain at its own speed ``system.omega_rad_s`` (rad/s, > 0)."""
    why = hb_not_applicable(system)
    if why is not None:
        raise InputError(why)
    P = int(period_revs)
    if P < 1 or P != period_revs:
        raise InputError(f"period_revs = {period_revs}: must be a whole number of revolutions >= 1")
    speed = float(system.omega_rad_s)
    if not speed > 0.0:
        raise InputError(f"speed_rad_s = {speed:g} rad/s: harmonic balance needs a spin speed > 0")
    T = cons.null_space_map(system.lock)
    omega = speed / P
    Mr, Dr, Kr = T.T @ system.M @ T, T.T @ system.D @ T, T.T @ system.K @ T
    A, dA = linear_blocks(Mr, Dr, Kr, fourier_, omega)
    sup = system.support
    Bs = lawp = None
    d0 = width = math.nan
    tilt_ignored = False
    if sup is not None:
        Bs = sup.relative_map(system.n) @ T
        lawp = np.ascontiguousarray(sup.law.params, dtype=float)
        d0, width, tilt_ignored = float(sup.law.clearance_m), float(sup.width_m), bool(sup.law.tilt_ignored)
    Ec, a1 = None, 0.0
    if system.coupling is not None and system.coupling[2] != 0.0:
        Ec, a1 = coupling_map(system) @ T, float(system.coupling[2])
    return HarmonicSystem(system, speed, omega, P, fourier_, T, A, dA, _load(system, T, fourier_, P), Bs, lawp,
                          d0, width, tilt_ignored, Ec, a1, Mr, Dr, Kr)


@dataclass(frozen=True)
class SpeedBlocks:
    """A system's harmonic-domain pieces as exact functions of the spin speed Ω, for a system whose only speed
    dependence is ``D = C − Ω G`` and a harmonic load ``∝ Ω²`` (:class:`rotor.dynamics.build.SpeedFamily`,
    ``exact``): with ``ω = Ω/P``, ``A(Ω) = A_K + ω² A_M + ω (A_C − Ω A_G)`` and ``load(Ω) = l_s + (Ω/Ω_0)² l_h``
    (:func:`linear_blocks` taken apart by matrix). ``base``: the system at ``Ω_0`` in the harmonic domain."""

    base: HarmonicSystem
    AK: np.ndarray
    AM: np.ndarray
    AC: np.ndarray
    AG: np.ndarray
    load_static: np.ndarray
    load_harmonic: np.ndarray
    Cr: np.ndarray
    Gr: np.ndarray


def speed_blocks(system: RotorSystem, fourier_: Fourier, period_revs: int = 1) -> SpeedBlocks:
    """:class:`SpeedBlocks` of ``system`` (at its own speed ``Ω_0 > 0``; every harmonic load scales as Ω²)."""
    hs = harmonic_system(system, fourier_, period_revs)
    T, Z = hs.T, np.zeros_like(hs.Mr)
    Cr, Gr = T.T @ system.C @ T, T.T @ system.G @ T
    f = system.force
    quiet = dataclasses.replace(system, force=dataclasses.replace(f, cos=0.0 * f.cos, sin=0.0 * f.sin))
    ls = _load(quiet, T, fourier_, hs.period_revs)
    return SpeedBlocks(hs, linear_blocks(Z, Z, hs.Kr, fourier_, 1.0)[0], linear_blocks(hs.Mr, Z, Z, fourier_, 1.0)[0],
                       linear_blocks(Z, Cr, Z, fourier_, 1.0)[0], linear_blocks(Z, Gr, Z, fourier_, 1.0)[0], ls,
                       hs.load - ls, Cr, Gr)


def hs_at_speed(sb: SpeedBlocks, speed: float) -> HarmonicSystem:
    """The harmonic system of :class:`SpeedBlocks` at spin speed ``speed`` (rad/s), exact (see there)."""
    b = sb.base
    w = speed / b.period_revs
    out = copy.copy(b)          # a shallow copy: the frozen __init__'s checks cost more than the evaluation here
    for k, v in (("speed_rad_s", speed), ("omega_rad_s", w), ("A", sb.AK + w * w * sb.AM + w * (sb.AC - speed * sb.AG)),
                 ("dA_domega", 2.0 * w * sb.AM + sb.AC - speed * sb.AG), ("Dr", sb.Cr - speed * sb.Gr),
                 ("load", sb.load_static + (speed / b.speed_rad_s) ** 2 * sb.load_harmonic)):
        object.__setattr__(out, k, v)
    return out


def speed_derivatives(sb: SpeedBlocks, speed: float) -> tuple[np.ndarray, np.ndarray]:
    """``∂A/∂Ω`` at fixed ω (the gyroscopic term) and ``∂load/∂Ω`` at ``speed`` (rad/s), exact."""
    return -(speed / sb.base.period_revs) * sb.AG, (2.0 * speed / sb.base.speed_rad_s ** 2) * sb.load_harmonic


def _to_harmonics(fourier_: Fourier, Ju, Jv, omega: float, Bmap) -> np.ndarray:
    """``∂F/∂Z`` (n_h n_r, n_h n_r) of a force ``Bmapᵀ f(Bmap q, Bmap q̇)`` from its sample Jacobians
    ``Ju``, ``Jv`` (N, m, m) (Jv None: no velocity dependence)."""
    Pi, E = fourier_.Pi, fourier_.E
    G = np.einsum("kj,jrs,jm->krms", Pi, Ju, E)
    if Jv is not None:
        G += omega * np.einsum("kj,jrs,jm->krms", Pi, Jv, fourier_.dE)
    nh, nr = E.shape[1], Bmap.shape[1]
    return np.einsum("ri,krms,sl->kiml", Bmap, G, Bmap).reshape(nh * nr, nh * nr)


def support_samples(hs: HarmonicSystem, Z) -> tuple[np.ndarray, np.ndarray]:
    """Relative displacement ``u`` and velocity ``u̇`` of the support (N, 4) at the samples of ``Z`` (n_h, n_r)."""
    f = hs.fourier
    return f.E @ Z @ hs.Bs.T, hs.omega_rad_s * (f.dE @ Z @ hs.Bs.T)


def nonlinear_force(hs: HarmonicSystem, Z, jacobian: bool = True):
    """AFT: harmonic coefficients of the support's contact force and the coupling remainder on the reduced
    coordinates, ``F`` (n_h n_r,) (N), with ``∂F/∂Z`` (n_h n_r, n_h n_r) and ``∂F/∂ω`` (n_h n_r,) if
    ``jacobian`` (else None, None). ``Z`` (n_h, n_r): the coefficients (m, rad)."""
    f = hs.fourier
    nh, nr = f.E.shape[1], hs.n_r
    F = np.zeros((nh, nr))
    J = np.zeros((nh * nr, nh * nr)) if jacobian else None
    dw = np.zeros((nh, nr)) if jacobian else None
    if hs.Bs is not None:
        U, V = support_samples(hs, Z)
        Fs = np.empty((f.n_time, 4))
        Js = np.empty((f.n_time, 4, 8))
        _law_samples(np.ascontiguousarray(U), np.ascontiguousarray(V), hs.law_params, Fs, Js)
        F += f.Pi @ Fs @ hs.Bs
        if jacobian:
            Ju, Jv = Js[:, :, :4], Js[:, :, 4:]
            J += _to_harmonics(f, Ju, Jv, hs.omega_rad_s, hs.Bs)
            dw += f.Pi @ np.einsum("jrs,js->jr", Jv, V / hs.omega_rad_s) @ hs.Bs
    if hs.Ec is not None:
        d = f.E @ Z @ hs.Ec.T                                   # Δθ samples (N, 2)
        d2 = np.einsum("js,js->j", d, d)
        F += f.Pi @ (-hs.a1 * d2[:, None] * d) @ hs.Ec
        if jacobian:
            Jc = -hs.a1 * (d2[:, None, None] * np.eye(2) + 2.0 * d[:, :, None] * d[:, None, :])
            J += _to_harmonics(f, Jc, None, hs.omega_rad_s, hs.Ec)
    if not jacobian:
        return F.reshape(-1), None, None
    return F.reshape(-1), J, dw.reshape(-1)


def support_forces(law: SupportLaw, u, v) -> np.ndarray:
    """The support law's force ``(Fy, Fz, My, Mz)`` (N, N m) at the rows of ``u``, ``v`` (N, 4): one compiled call
    of the kernel HB solves with (:func:`_law_samples`) where the law has it, else ``law.force`` row by row."""
    u, v = np.ascontiguousarray(u, dtype=float), np.ascontiguousarray(v, dtype=float)
    if law.kernel is not contact_kernel:
        return np.array([law.force(a, b) for a, b in zip(u, v)]).reshape(len(u), 4)
    F, J = np.empty((len(u), 4)), np.empty((len(u), 4, 8))
    _law_samples(u, v, np.ascontiguousarray(law.params, dtype=float), F, J)
    return F


def largest_penetration(hs: HarmonicSystem, Z) -> float:
    """Largest radial penetration (m) of the ring's edges over the samples of ``Z`` (negative: a gap; nan
    without support): ``max |r_k| − δ0`` with the edges of :func:`rotor.dynamics.constraints.edge_offsets`
    (the centre alone when the tilt is ignored)."""
    if hs.Bs is None:
        return math.nan
    U, _ = support_samples(hs, Z)
    if hs.tilt_ignored:
        return float(np.max(np.hypot(U[:, 0], U[:, 1])) - hs.clearance_m)
    r1, r2 = cons.edge_offsets(U, hs.width_m)
    return float(max(r1.max(), r2.max()) - hs.clearance_m)


# ---------------------------------------------------------------------------
# residual and Newton at a fixed speed
# ---------------------------------------------------------------------------


def default_n_time(harmonics: int) -> int:
    """``4H + 2`` AFT samples (module docstring: no aliasing of a cubic nonlinearity)."""
    return 4 * int(harmonics) + 2


def residual(hs: HarmonicSystem, z, jacobian: bool = True):
    """``R(Z) = A Z − load − F_nl(Z)`` (n_h n_r,) (N) of the flat reduced coefficients ``z``, its Jacobian
    ``∂R/∂Z`` and ``∂R/∂ω`` at fixed system matrices and load (None, None without ``jacobian``), and the
    residual's scale (N): the largest of load, linear and nonlinear force coefficients."""
    nh = 2 * hs.fourier.harmonics + 1
    Fn, Jn, dFw = nonlinear_force(hs, np.reshape(z, (nh, hs.n_r)), jacobian)
    Az = hs.A @ z
    R = Az - hs.load - Fn
    scale = max(float(np.max(np.abs(hs.load), initial=0.0)), float(np.max(np.abs(Az), initial=0.0)),
                float(np.max(np.abs(Fn), initial=0.0)), 1e-300)
    if not jacobian:
        return R, None, None, scale
    return R, hs.A - Jn, hs.dA_domega @ z - dFw, scale


def solve(J, rhs):
    try:
        return np.linalg.solve(J, rhs)
    except np.linalg.LinAlgError:
        return np.linalg.lstsq(J, rhs, rcond=None)[0]


def newton(hs: HarmonicSystem, z0, *, tol: float = 1e-12, max_iter: int = 50):
    """Newton on ``R(Z) = 0`` from ``z0`` with backtracking (halving while the residual norm does not fall, or the
    trial leaves the law's domain). Converged when the Newton step is below ``tol`` of the largest coefficient
    and the residual below ``√tol`` of its scale. Returns ``(z, converged, relative residual, iterations)``."""
    z = np.asarray(z0, float).copy()
    R, J, _, sc = residual(hs, z)
    nR = float(np.linalg.norm(R))
    for it in range(1, max_iter + 1):
        dz = solve(J, -R)
        small = float(np.max(np.abs(dz))) <= tol * max(float(np.max(np.abs(z))), 1e-300)
        lam = 1.0
        for _ in range(30):
            try:
                Rt, Jt, _, sct = residual(hs, z + lam * dz)
            except OutsideDomainError:
                lam *= 0.5
                continue
            nt = float(np.linalg.norm(Rt))
            if small or nt < (1.0 - 1e-4 * lam) * nR or nt <= 1e-14 * sct:
                break
            lam *= 0.5
        else:
            return z, False, float(np.max(np.abs(R))) / sc, it
        z, R, J, sc, nR = z + lam * dz, Rt, Jt, sct, nt
        if small and float(np.max(np.abs(R))) <= math.sqrt(tol) * sc:
            return z, True, float(np.max(np.abs(R))) / sc, it
    return z, False, float(np.max(np.abs(R))) / sc, max_iter


def linear_guess(hs: HarmonicSystem) -> np.ndarray:
    """The orbit without the support force and coupling remainder (``A Z = load``), shrunk by halves into the
    law's domain if it penetrates beyond it; zeros if ``A`` is singular."""
    try:
        z = np.linalg.solve(hs.A, hs.load)
    except np.linalg.LinAlgError:
        return np.zeros_like(hs.load)
    for _ in range(60):
        try:
            residual(hs, z, jacobian=False)
            return z
        except OutsideDomainError:
            z = 0.5 * z
    return np.zeros_like(z)


def prepare(system: RotorSystem, harmonics: int = 1, n_time: int | None = None,
            period_revs: int = 1) -> HarmonicSystem:
    """The system in the harmonic domain (:func:`rotor.periodic.hb_aft.harmonic_system`) with ``harmonics`` H and
    ``n_time`` AFT samples (None: :func:`default_n_time`). Raises InputError where HB does not apply."""
    return harmonic_system(system, fourier(harmonics, default_n_time(harmonics) if n_time is None else n_time),
                           period_revs)


def sample_series(coefficients, omega_rad_s: float, n_samples: int = 128):
    """``(t, q, v)`` of Fourier ``coefficients`` (2H+1, n) of fundamental ``omega_rad_s`` (rad/s) at
    ``n_samples`` equally spaced instants of one period (s; m, rad; m/s, rad/s)."""
    c = np.asarray(coefficients, float)
    H = (c.shape[0] - 1) // 2
    k = np.arange(1, H + 1)
    t = 2.0 * math.pi / omega_rad_s * np.arange(int(n_samples)) / int(n_samples)
    ph = np.outer(omega_rad_s * t, k)
    cos, sin = np.cos(ph), np.sin(ph)
    q = c[0] + cos @ c[1::2] + sin @ c[2::2]
    v = omega_rad_s * ((-sin * k) @ c[1::2] + (cos * k) @ c[2::2])
    return t, q, v


def peak_amplitudes(coefficients, n_samples: int = 128) -> np.ndarray:
    """``max_t |q_i(t) − a_0,i|`` (n,) of Fourier ``coefficients`` (2H+1, n) on ``n_samples`` instants."""
    c = np.asarray(coefficients, float)
    _, q, _ = sample_series(c, 1.0, n_samples)
    return np.max(np.abs(q - c[0]), axis=0)


def reduced_guess(guess, hs: HarmonicSystem) -> np.ndarray:
    """Flat reduced coefficients of a full-DOF ``guess`` (an orbit with ``coefficients`` or (2H'+1, n) array), harmonics cut or padded."""
    c = np.asarray(getattr(guess, "coefficients", guess), float)
    nh = 2 * hs.fourier.harmonics + 1
    out = np.zeros((nh, hs.system.n))
    m = min(nh, c.shape[0])
    out[:m] = c[:m]
    return (out @ hs.T).reshape(-1)


def full_coefficients(hs: HarmonicSystem, z) -> np.ndarray:
    """The coefficients of all DOFs (2H+1, n) (m, rad) of the flat reduced ones ``z``."""
    return np.reshape(z, (2 * hs.fourier.harmonics + 1, hs.n_r)) @ hs.T.T
