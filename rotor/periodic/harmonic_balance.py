"""Periodic orbits by harmonic balance (HB): a second orbit method beside shooting (:mod:`rotor.periodic.shooting`).

The orbit of a :class:`~rotor.dynamics.system.RotorSystem` with a frictionless loose support is sought as a
truncated Fourier series of all DOFs, ``H`` harmonics of the fundamental ``ω = Ω/P`` (``P = period_revs``: 1 for
the synchronous orbit, more for subharmonics), whose coefficients make the equations of motion hold harmonic by
harmonic (Galerkin projection; Krack & Gross 2019, *Harmonic Balance for Nonlinear Vibration Problems*). The
linear part is block diagonal in the harmonics; the support's contact force and the coupling remainder are
evaluated by alternating frequency-time (AFT, Cameron & Griffin 1989) with the law the time integration uses,
and differentiated analytically (:mod:`rotor.periodic.hb_aft`). Time samples: ``N = 4H + 2`` by default, the
smallest count that keeps a cubic nonlinearity (the coupling remainder) free of aliasing (a cubic of an ``H``-th
order polynomial has order ``3H``; with ``N ≥ 4H + 1`` no alias of it falls on the first ``H`` harmonics); the
contact law is not a polynomial, its aliasing error falls with ``N`` (choose ``n_time`` larger for orbits that
touch the ring briefly).

* :func:`hb_orbit`: Newton at a fixed speed, analytic Jacobian, backtracking on the residual norm (the law has
  kinks: contact onset, and grazing where the conformal law has a finite stiffness at zero penetration).
* :func:`hb_branch`: pseudo-arclength continuation in speed (Keller 1977; for HB, Detroux et al. 2015): tangent
  predictor, Newton corrector on the hyperplane orthogonal to the tangent, step control on the corrector's
  iterations and the turn of the tangent; folds (the speed component of the tangent changes sign: smooth folds,
  and grazing folds, where the conformal law's curve turns at a corner) and grazings (the largest penetration
  changes sign) located by regula falsi on the arclength, each trial a corrected orbit.

Scope. End-face friction (``μ N > 0``) makes stick and slip states, which a smooth Fourier series does not
represent: :func:`hb_orbit` raises :class:`contact.errors.InputError` ("HB does not apply …; use shooting",
:func:`rotor.periodic.hb_aft.hb_not_applicable` says it without raising, for a chooser). Stability is not
computed (no Hill's method here): shooting's Floquet multipliers give it. Massless DOFs are kept (HB needs no
invertible mass matrix); the 3a/3b lock is removed by its null space as in the time integration.
"""
from __future__ import annotations

import copy
import math
import time
from dataclasses import dataclass

import numpy as np

from contact.errors import ConvergenceError, InputError, OutsideDomainError
from rotor.dynamics.system import RotorSystem
from rotor.periodic.hb_aft import (HarmonicSystem, default_n_time, fourier,  # noqa: F401 (re-exported)
                                   full_coefficients, hb_not_applicable, hs_at_speed, largest_penetration, linear_blocks,
                                   linear_guess, newton, peak_amplitudes, prepare, reduced_guess, residual,
                                   sample_series, solve, speed_blocks, speed_derivatives)
from rotor.periodic.hb_events import CORNER_DS, HBEvent, _advance, _corner, _events_between, _Point  # noqa: F401


@dataclass(frozen=True)
class HBOrbit:
    """A periodic orbit by harmonic balance.

    Attributes
    ----------
    speed_rad_s : float, spin speed Ω (rad/s); period_revs : int, period in revolutions P
    harmonics : int, H; n_time : int, AFT samples per period
    coefficients : (2H+1, n) Fourier coefficients of all DOFs (m, rad), rows ``a_0, a_1, b_1, …, a_H, b_H`` of
        ``q(t) = a_0 + Σ a_k cos(kΩt/P) + b_k sin(kΩt/P)``
    dof_names : tuple of n str
    converged : bool; residual : float, largest harmonic residual over the largest of load, linear and contact
        force coefficients (–); newton_iterations : int
    penetration_m : float, largest penetration of the ring over the samples (m; negative: a gap; nan: no support)
    wall_s, cpu_s : float, wall-clock and process CPU time of the solve (s)
    """

    speed_rad_s: float
    period_revs: int
    harmonics: int
    n_time: int
    coefficients: np.ndarray
    dof_names: tuple
    converged: bool
    residual: float
    newton_iterations: int
    penetration_m: float
    wall_s: float
    cpu_s: float

    def time_series(self, n_samples: int = 128) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(t (s), q (m, rad), v (m/s, rad/s))`` at ``n_samples`` instants of one period."""
        return sample_series(self.coefficients, self.speed_rad_s / self.period_revs, n_samples)

    def amplitudes(self, n_samples: int = 128) -> np.ndarray:
        """Peak of the oscillating part of each DOF, ``max_t |q_i(t) − a_0,i|`` (m, rad), on ``n_samples``."""
        return peak_amplitudes(self.coefficients, n_samples)


def hb_orbit(system: RotorSystem, harmonics: int = 1, n_time: int | None = None, *, period_revs: int = 1,
             guess=None, tol: float = 1e-12, max_iter: int = 50) -> HBOrbit:
    """The periodic orbit of ``system`` at its spin speed ``system.omega_rad_s`` (rad/s) by harmonic balance.

    Parameters
    ----------
    system : RotorSystem
        Frictionless loose support (``μ N = 0``; else InputError: "HB does not apply …; use shooting").
    harmonics : int
        H, harmonics of the fundamental ``Ω/period_revs`` kept (≥ every load order × period_revs).
    n_time : int or None
        AFT samples per period (≥ 2H+1); None: ``4H + 2``.
    period_revs : int
        Period in revolutions (1: synchronous; 2, 3 …: subharmonic orbits).
    guess : HBOrbit or (2H'+1, n) array or None
        Start of Newton (any number of harmonics); None: the linear orbit without the support force.
    tol : float
        Newton step below ``tol`` of the largest coefficient (–).
    max_iter : int
        Newton iterations at most.

    Returns
    -------
    HBOrbit
        ``converged`` False (and the last iterate) when Newton stalled.
    """
    w0, c0 = time.perf_counter(), time.process_time()
    hs = prepare(system, harmonics, n_time, period_revs)
    z0 = linear_guess(hs) if guess is None else reduced_guess(guess, hs)
    z, ok, res, its = newton(hs, z0, tol=tol, max_iter=max_iter)
    if not ok and guess is None:
        z, ok, res, more = _homotopy(hs, tol)
        its += more
    nh = 2 * hs.fourier.harmonics + 1
    return HBOrbit(hs.speed_rad_s, hs.period_revs, hs.fourier.harmonics, hs.fourier.n_time, full_coefficients(hs, z),
                   tuple(system.dof_names), bool(ok), float(res), int(its),
                   largest_penetration(hs, z.reshape(nh, hs.n_r)), time.perf_counter() - w0,
                   time.process_time() - c0)


def require_converged(orbit: HBOrbit) -> HBOrbit:
    """``orbit`` if it converged, else ConvergenceError naming the speed and the residual reached."""
    if not orbit.converged:
        raise ConvergenceError(f"harmonic balance at {orbit.speed_rad_s:g} rad/s: Newton stalled at relative "
                               f"residual {orbit.residual:.2e} after {orbit.newton_iterations} iterations")
    return orbit


# ---------------------------------------------------------------------------
# continuation in speed
# ---------------------------------------------------------------------------


#: corrector: iterations at most, converged below this scaled step (–) and this relative residual (–)
CORRECTOR_MAX_ITER = 12
CORRECTOR_TOL = 1e-10
RESIDUAL_TOL = 1e-9
#: the corrector re-anchors its speed model until the orbit's speed is the anchor's to this (relative); the model's
#: error is of the order of its square, amplified near a fold. At 1e-6 a random Pereira rotor of
#: tests/rotor/periodic/test_harmonic_balance.py (seed 454714306 + 2) landed 1.1e-10 from the closed form, past the
#: issue's 1e-10
ANCHOR_RTOL = 1e-7


@dataclass(frozen=True)
class HBContinuationOptions:
    """Pseudo-arclength continuation of :func:`hb_branch` (scaled unknowns: coefficients over the state scale,
    speed over the speed scale).

    ds, ds_min, ds_max : first, smallest and largest step in scaled arclength (–); ds grows ×1.5 after a corrector
        of ≤ 3 iterations, shrinks ×0.6 after ≥ 7, is halved and retried on failure or on a tangent turn above
        ``max_turn_deg`` (down to :data:`CORNER_DS`, below which the turn is accepted: a corner of the curve,
        where the conformal law grazes, turns the tangent by a finite angle at any step)

    max_points : int, accepted points at most
    """

    ds: float = 0.05
    ds_min: float = 1e-7
    ds_max: float = 1.0
    max_points: int = 5000
    max_turn_deg: float = 15.0


@dataclass(frozen=True)
class HBBranch:
    """A branch of HB orbits over the speed.

    Attributes
    ----------
    speeds_rad_s : (m,) (rad/s); coefficients : (m, 2H+1, n) (m, rad), as :attr:`HBOrbit.coefficients`
    amplitudes : (m, n) peak of each DOF's oscillating part (m, rad), :func:`peak_amplitudes`
    residuals : (m,) relative residual (–); newton_iterations : (m,) corrector iterations (the start: Newton's)
    penetration_m : (m,) largest penetration (m; negative: a gap); dspeed_ds : (m,) speed component of the tangent
    events : tuple of :class:`HBEvent`; stop : why the branch ended; rejected_steps : steps halved and retried
    harmonics, n_time, period_revs, dof_names; wall_s, cpu_s : wall-clock and process CPU time (s)
    """

    speeds_rad_s: np.ndarray
    coefficients: np.ndarray
    amplitudes: np.ndarray
    residuals: np.ndarray
    newton_iterations: np.ndarray
    penetration_m: np.ndarray
    dspeed_ds: np.ndarray
    events: tuple
    stop: str
    rejected_steps: int
    harmonics: int
    n_time: int
    period_revs: int
    dof_names: tuple
    wall_s: float
    cpu_s: float

    def folds(self) -> list[HBEvent]:
        """The turning points (smooth folds, grazing folds and corners) in branch order."""
        return [e for e in self.events if e.kind != "grazing"]


def _with(hs: HarmonicSystem, **fields) -> HarmonicSystem:
    """A copy of ``hs`` with ``fields`` replaced (a shallow copy: ``dataclasses.replace`` re-runs the frozen
    ``__init__``, which costs more than the corrector's evaluation here)."""
    out = copy.copy(hs)
    for k, v in fields.items():
        object.__setattr__(out, k, v)
    return out


class _Tracer:
    """The scaled augmented problem of :func:`hb_branch`: systems by speed (cached), the residual in scaled unknowns
    ``y = (z/s_z, Ω/s_Ω)`` and its Jacobian, the corrector and the tangent."""

    def __init__(self, system_at_speed, harmonics, n_time, period_revs, opts: HBContinuationOptions):
        self.at, self.H, self.N, self.P, self.opts = system_at_speed, harmonics, n_time, period_revs, opts
        self.cache: dict = {}
        self.dA_sys = self.dload = self.anchor = None
        exact = getattr(system_at_speed, "exact", False)       # a SpeedFamily (rotor.dynamics.build) without tables
        self.exact = speed_blocks(system_at_speed.base, fourier(harmonics, n_time), period_revs) if exact else None
        self.modelled, self.locate = self.exact is None, True   # anchored model (see hs) unless exact; events located
        self.free = False                                       # the support's force left out (_gap_grazing)
        self.w_factor = 1.0 / period_revs        # ∂ω/∂λ: the fundamental moves with the speed

    def true_hs(self, speed: float) -> HarmonicSystem:
        """The system at ``speed`` built by ``system_at_speed`` (cached), or exact from its speed blocks."""
        if self.exact is not None:
            return hs_at_speed(self.exact, speed)
        if speed not in self.cache:
            if len(self.cache) > 8:
                self.cache.clear()
            self.cache[speed] = prepare(self.at(speed), self.H, self.N, self.P)
        return self.cache[speed]

    def hs(self, speed: float) -> HarmonicSystem:
        """The system at ``speed`` as the corrector sees it: the anchor's matrices with the harmonics' frequencies
        at ``speed`` exactly, the system's own speed dependence (matrices, load) to first order from the anchor
        (:meth:`sensitivities`); the corrector re-anchors at its result until the two speeds agree, so every
        point returned is the built system's (building a system costs more than an AFT evaluation)."""
        a = self.anchor
        if a is None or speed == a.speed_rad_s:
            return self.true_hs(speed) if a is None else a
        A, dA = linear_blocks(a.Mr, a.Dr, a.Kr, a.fourier, speed / self.P)
        d = speed - a.speed_rad_s
        return _with(a, speed_rad_s=speed, omega_rad_s=speed / self.P, A=A + self.dA_sys * d, dA_domega=dA,
                     load=a.load + self.dload * d)

    def set_anchor(self, speed: float):
        if self.exact is not None:          # exact at every speed: no anchor
            return
        self.anchor = None
        self.sensitivities(speed)
        self.anchor = self.true_hs(speed)

    def set_scales(self, z0, speed0: float, speed1: float, state_scale, speed_scale):
        hs = self.hs(speed0)
        d0 = hs.clearance_m if math.isfinite(hs.clearance_m) else 0.0
        self.sz = float(state_scale) if state_scale else max(float(np.max(np.abs(z0))), d0, 1e-300)
        self.sw = float(speed_scale) if speed_scale else max(abs(speed1 - speed0) / 20.0, 1e-6 * abs(speed0))
        self.sr = max(float(np.max(np.abs(hs.load))), 1e-300)

    def sensitivities(self, speed: float):
        """``∂A/∂Ω`` and ``∂load/∂Ω`` of the system's own speed dependence (matrices, load; ω held) by a forward
        difference (h = 1e-7 Ω), held through the next step's corrector."""
        h = 1e-7 * speed
        a, b = self.true_hs(speed), prepare(self.at(speed + h), self.H, self.N, self.P)
        self.dA_sys = (b.A - b.dA_domega * (h / self.P) - a.A) / h
        self.dload = (b.load - a.load) / h

    def evaluate(self, y):
        """``(R/s_r, ∂(R/s_r)/∂y, hs, z, relative residual)`` at scaled ``y``."""
        speed = float(y[-1]) * self.sw
        hs = self.hs(speed)
        z = y[:-1] * self.sz
        R, J, dRw, sc = residual(_with(hs, Bs=None) if self.free else hs, z)
        dA_sys, dload = (self.dA_sys, self.dload) if self.exact is None else speed_derivatives(self.exact, speed)
        dRs = self.w_factor * dRw + dA_sys @ z - dload
        Jy = np.hstack([J * self.sz, (dRs * self.sw)[:, None]]) / self.sr
        return R / self.sr, Jy, hs, z, float(np.max(np.abs(R))) / sc

    def tangent(self, Jy, tau_prev):
        t = solve(np.vstack([Jy, tau_prev[None, :]]), np.concatenate([np.zeros(Jy.shape[0]), [1.0]]))
        return t / np.linalg.norm(t)

    def correct(self, y_pred, tau):
        """Newton on ``R = 0``, ``τ·(y − y_pred) = 0`` from ``y_pred``: ``(y, Jy, hs, z, res, iterations)`` or None.
        Converged on the anchored model (:meth:`hs`), it re-anchors at the result and goes on until the result's
        speed is the anchor's to 1e-9 (the model's error there: of the order of that squared)."""
        y = np.asarray(y_pred, float).copy()
        first = 0                   # iterations to the first convergence (on the model): the step control's count
        try:
            R, Jy, hs, z, res = self.evaluate(y)
            for it in range(1, CORRECTOR_MAX_ITER + 1):
                F = np.concatenate([R, [tau @ (y - y_pred)]])
                dy = solve(np.vstack([Jy, tau[None, :]]), -F)
                y = y + dy
                R, Jy, hs, z, res = self.evaluate(y)
                if not np.all(np.isfinite(R)):
                    return None
                if float(np.max(np.abs(dy))) < CORRECTOR_TOL and res < RESIDUAL_TOL:
                    speed = float(y[-1]) * self.sw
                    first = first or it
                    if not self.modelled or abs(speed - self.anchor.speed_rad_s) <= ANCHOR_RTOL * abs(speed):
                        return y, Jy, hs, z, res, first
                    self.set_anchor(speed)
                    R, Jy, hs, z, res = self.evaluate(y)
        except (OutsideDomainError, InputError):
            return None
        return None


class _LoadTracer(_Tracer):
    """The tracer of a load homotopy at a fixed speed: parameter λ scales the whole load (0: at rest, 1: the
    system's), ``R = A z − λ load − F(z)``; :func:`hb_orbit`'s way to an orbit where Newton from the linear guess
    stalls (kinks of the law far from the orbit)."""

    def __init__(self, base: HarmonicSystem, opts: HBContinuationOptions):
        super().__init__(None, base.fourier.harmonics, base.fourier.n_time, base.period_revs, opts)
        self.base, self.w_factor, self.modelled, self.locate = base, 0.0, False, False
        self.dA_sys, self.dload = np.zeros_like(base.A), base.load
        d0 = base.clearance_m if math.isfinite(base.clearance_m) else 0.0
        self.sz = max(float(np.max(np.abs(linear_guess(base)))), d0, 1e-300)
        self.sw, self.sr = 0.05, max(float(np.max(np.abs(base.load))), 1e-300)

    def true_hs(self, lam: float) -> HarmonicSystem:
        return self.hs(lam)

    def hs(self, lam: float) -> HarmonicSystem:
        if lam not in self.cache:
            if len(self.cache) > 8:
                self.cache.clear()
            self.cache[lam] = _with(self.base, load=lam * self.base.load)
        return self.cache[lam]

    def sensitivities(self, lam: float):
        return None


def _homotopy(hs: HarmonicSystem, tol: float):
    """The orbit of ``hs`` by continuation of the load from 0 (the rest state, no force) to 1:
    ``(z, converged, relative residual, corrector iterations)``."""
    tr = _LoadTracer(hs, HBContinuationOptions(ds=0.2, ds_max=2.0))
    z0, ok, res, its = newton(tr.hs(0.0), np.zeros_like(hs.load), tol=tol)
    if not ok:
        return z0, False, res, its
    y0 = np.concatenate([z0 / tr.sz, [0.0]])
    e = np.zeros(len(y0))
    e[-1] = 1.0
    start = _Point(y0, tr.tangent(tr.evaluate(y0)[1], e), tr.hs(0.0), z0, res, its,
                   largest_penetration(hs, z0.reshape(2 * hs.fourier.harmonics + 1, hs.n_r)))
    pts, _, stop, _ = _trace(tr, start, 0.0, 1.0, tol)
    end = pts[-1]
    done = stop == "reached the end speed"
    return end.z, done, end.res, int(sum(p.its for p in pts))


def _finish_at(tr: _Tracer, a: _Point, b: _Point, speed1: float, tol: float) -> _Point | None:
    """The orbit at exactly ``speed1`` between ``a`` and ``b`` (Newton at that speed from the interpolation)."""
    wa, wb = a.y[-1] * tr.sw, b.y[-1] * tr.sw
    f = (speed1 - wa) / (wb - wa)
    hs = tr.true_hs(speed1)
    z, ok, res, its = newton(hs, (1.0 - f) * a.z + f * b.z, tol=tol)
    if not ok:
        return None
    nh = 2 * hs.fourier.harmonics + 1
    y = np.concatenate([z / tr.sz, [speed1 / tr.sw]])
    return _Point(y, b.tau, hs, z, res, its, largest_penetration(hs, z.reshape(nh, hs.n_r)))


def _start(tr: _Tracer, speed0, speed1, guess, tol, state_scale, speed_scale) -> _Point:
    orbit = require_converged(hb_orbit(tr.at(speed0), tr.H, tr.N, period_revs=tr.P, guess=guess, tol=tol))
    hs = tr.true_hs(speed0)
    z = reduced_guess(orbit, hs)
    tr.set_scales(z, speed0, speed1, state_scale, speed_scale)
    tr.set_anchor(speed0)
    y = np.concatenate([z / tr.sz, [speed0 / tr.sw]])
    _, Jy, _, _, res = tr.evaluate(y)
    e = np.zeros(len(y))
    e[-1] = 1.0 if speed1 > speed0 else -1.0
    return _Point(y, tr.tangent(Jy, e), hs, z, res, orbit.newton_iterations, orbit.penetration_m)


def hb_branch(system_at_speed, speed0_rad_s: float, speed1_rad_s: float, harmonics: int = 1,
              n_time: int | None = None, *, period_revs: int = 1, guess=None, tol: float = 1e-12,
              state_scale: float | None = None, speed_scale_rad_s: float | None = None,
              options: HBContinuationOptions | None = None) -> HBBranch:
    """A branch of HB orbits from ``speed0_rad_s`` towards ``speed1_rad_s`` (rad/s) by pseudo-arclength continuation.

    Parameters
    ----------
    system_at_speed : callable ``Ω (rad/s) -> RotorSystem``
        The rotor at each spin speed (load, and any speed-dependent matrices); frictionless support.
    speed0_rad_s, speed1_rad_s : float
        Start and end speed (rad/s); the branch may turn at folds in between and ends where it passes
        ``speed1_rad_s`` (that orbit computed at exactly that speed) or turns back beyond ``speed0_rad_s``.
    harmonics, n_time, period_revs, guess, tol
        As :func:`hb_orbit` (the start orbit at ``speed0_rad_s``).
    state_scale : float or None
        Scale of the coefficients in the arclength (m); None: the start orbit's largest coefficient, at least
        the clearance.
    speed_scale_rad_s : float or None
        Scale of the speed (rad/s); None: a twentieth of the interval.
    options : HBContinuationOptions

    Returns
    -------
    HBBranch
    """
    w0, c0 = time.perf_counter(), time.process_time()
    opts = options or HBContinuationOptions()
    N = default_n_time(harmonics) if n_time is None else int(n_time)
    tr = _Tracer(system_at_speed, int(harmonics), N, int(period_revs), opts)
    start = _start(tr, float(speed0_rad_s), float(speed1_rad_s), guess, tol, state_scale, speed_scale_rad_s)
    pts, events, stop, rejected = _trace(tr, start, float(speed0_rad_s), float(speed1_rad_s), tol)
    return _branch_result(tr, pts, events, stop, rejected, w0, c0)


def _trace(tr: _Tracer, start: _Point, lam0: float, lam1: float, tol: float):
    """The continuation loop from ``start`` (parameter ``lam0``) towards ``lam1``: ``(points, events, stop,
    rejected steps)``; ends at ``lam1`` exactly, or where it turns back beyond ``lam0``, or stalls."""
    opts = tr.opts
    pts, events, rejected, ds, stop = [start], [], 0, opts.ds, f"{opts.max_points} points"
    direction = 1.0 if lam1 > lam0 else -1.0
    cos_max = math.cos(math.radians(opts.max_turn_deg))
    while len(pts) < opts.max_points:
        new, used, rej = _advance(tr, pts[-1], ds, corner_first=True)
        rejected += rej
        cornered = False
        if new is None:
            passed = _corner(tr, pts)
            if passed is not None:
                (new, event), used, cornered = passed, opts.ds, True
                events.append(event)
            elif used >= opts.ds_min:              # not a corner's: on by halving
                new, used, rej = _advance(tr, pts[-1], 0.5 * used)
                rejected += rej + 1
            if new is None:
                stop = f"step below ds_min = {opts.ds_min:g} at {pts[-1].y[-1] * tr.sw:.6g} rad/s"
                break
        lam = new.y[-1] * tr.sw
        if (lam - lam1) * direction >= 0.0:
            end = _finish_at(tr, pts[-1], new, lam1, tol)
            events += [e for e in _events_between(tr, pts[-1], new, used, len(pts))
                       if (e.speed_rad_s - lam1) * direction < 0]
            if end is not None:
                pts.append(end)
            stop = "reached the end speed" if end is not None else "no orbit at the end speed"
            break
        if not cornered:
            events += _events_between(tr, pts[-1], new, used, len(pts))
        turned = cornered or float(new.tau @ pts[-1].tau) < cos_max     # a corner: the step cut for it, not the curve
        pts.append(new)
        if (lam - lam0) * direction < 0.0:
            stop = "turned back beyond the start speed"
            break
        if turned:
            ds = max(ds, used)
        else:
            ds = min(1.5 * used, opts.ds_max) if new.its <= 3 else (0.6 * used if new.its >= 7 else used)
    return pts, events, stop, rejected


def _branch_result(tr: _Tracer, pts: list, events: list, stop: str, rejected: int, w0: float, c0: float) -> HBBranch:
    coefs = np.array([full_coefficients(p.hs, p.z) for p in pts])
    return HBBranch(np.array([p.y[-1] * tr.sw for p in pts]), coefs, np.array([peak_amplitudes(c) for c in coefs]),
                    np.array([p.res for p in pts]), np.array([p.its for p in pts]), np.array([p.pen for p in pts]),
                    np.array([p.tau[-1] for p in pts]), tuple(events), stop, rejected, tr.H, tr.N, tr.P,
                    tuple(pts[0].hs.system.dof_names), time.perf_counter() - w0, time.process_time() - c0)
