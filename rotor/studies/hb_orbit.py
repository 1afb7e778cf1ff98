"""Periodic orbits and branches of a scene's rotor by harmonic balance, in the shapes ``orbit`` and ``branch`` report.

:func:`hb_point` is one operating point (:func:`rotor.periodic.harmonic_balance.hb_orbit` on the system of
:func:`rotor.studies.steady_state.point_system`), :func:`hb_scene_branch` a branch in speed
(:func:`rotor.periodic.harmonic_balance.hb_branch`). Both report the keys of the shooting path
(:mod:`rotor.studies.orbit`) where they apply: ``speed_rpm``, ``velocity_amplitudes_mm_s_1X_to_5X`` (order ``o`` of
the spin speed is harmonic ``oP`` of the fundamental ``Ω/P``; its velocity amplitude is ``oΩ |X_oP|`` with
``|X| = √(a² + b²)``, the quantity of :func:`rotor.studies.steady_state.harmonic_amplitudes`; an order beyond the
retained harmonics is 0, the series has none), ``max_edge_penetration_mm``, the contact summary of
:func:`rotor.dynamics.support_record.contact_summary` over one period, ``phase0_state`` (a start for shooting),
and ``method`` "hb" with ``harmonics``. Stability is not computed (no Hill's method): ``stable`` is None.

Harmonics chosen by the spectrum (:func:`spectrum_tail`): without ``harmonics`` the ladder 1, 2, 4, … up to
:data:`MAX_AUTO_HARMONICS` is climbed, each orbit started from the previous, until the highest retained block of
harmonics (orders in ``(H/2, H]``) of the ring's relative motion is below ``tail_tol`` of its largest harmonic.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from contact.errors import ConvergenceError
from rotor.dynamics.build import SpeedFamily
from rotor.dynamics.constraints import edge_offsets
from rotor.dynamics.support_record import contact_summary
from rotor.periodic.harmonic_balance import HBOrbit, hb_branch, hb_orbit, sample_series
from rotor.periodic.hb_aft import support_forces
from rotor.studies.steady_state import point_system

ORDERS = (1, 2, 3, 4, 5)
#: the largest H the spectrum ladder climbs to (AFT samples 4H + 2 = 130, Jacobian (2H+1) n_r square)
MAX_AUTO_HARMONICS = 32
#: default bound of the spectrum's tail (highest retained block over the largest harmonic), see :func:`spectrum_tail`
TAIL_TOL = 1e-6
#: samples of one period for amplitudes, penetration and the contact summary
N_SAMPLES = 512
TO_RPM = 30.0 / math.pi


def relative_motion(system, coefficients) -> np.ndarray:
    """Fourier coefficients (2H+1, 4) of the ring's motion relative to its support (bearing minus support DOFs:
    y, z, θy, θz; m, rad) from the coefficients of all DOFs."""
    return np.asarray(coefficients, float) @ system.support.relative_map(system.n).T


def relative_radius(system, coefficients) -> float:
    """Radius (m) of the first harmonic's relative whirl ``√((a_y² + b_y² + a_z² + b_z²)/2)``: the relative orbit
    radius of a circular whirl (``a_z = −b_y``, ``b_z = a_y``), which is what one harmonic of it holds."""
    u = relative_motion(system, coefficients)
    return float(math.sqrt(0.5 * float(np.sum(u[1:3, :2] ** 2))))


def spectrum_tail(system, coefficients) -> float:
    """The largest amplitude among the highest retained block of harmonics (orders in ``(H/2, H]``) of the
    ring's relative displacement (y, z) over the largest harmonic amplitude (–; 1 for H = 1: one harmonic
    says nothing of its own truncation). Without a loose support: of every DOF's displacement."""
    c = np.asarray(coefficients, float)
    u = relative_motion(system, c)[:, :2] if system.support is not None else c
    H = (c.shape[0] - 1) // 2
    amp = np.array([np.max(np.hypot(u[2 * k - 1], u[2 * k])) for k in range(1, H + 1)])
    top = float(np.max(amp))
    if top == 0.0:
        return 0.0
    return float(np.max(amp[H // 2:])) / top


@dataclass(frozen=True)
class HBPoint:
    """One HB orbit of a scene at ``speed_rpm`` (rpm, as asked): ``orbit`` (:class:`rotor.periodic.harmonic_balance.HBOrbit`), ``fields`` (the JSON
    fields of :func:`orbit_fields`), ``ladder`` (``(H, tail, converged, cpu_s)`` of every rung climbed),
    ``tail`` (the spectrum tail of the orbit returned), ``wall_s``, ``cpu_s`` (the whole point)."""

    speed_rpm: float
    orbit: HBOrbit
    fields: dict
    ladder: tuple
    tail: float
    wall_s: float
    cpu_s: float

    def as_dict(self) -> dict:
        o = self.orbit
        return {"speed_rpm": self.speed_rpm, "period_revs": o.period_revs,
                "period_s": 2.0 * math.pi * o.period_revs / o.speed_rad_s, "converged": o.converged,
                "stable": None, "stability": "not computed (harmonic balance: no Hill's method; use --method shooting)",
                "method": "hb", "harmonics": o.harmonics, "n_time": o.n_time, "spectrum_tail": self.tail,
                "harmonic_ladder": [{"harmonics": h, "spectrum_tail": t, "converged": ok, "cpu_s": c}
                                    for h, t, ok, c in self.ladder],
                "newton_iterations": o.newton_iterations, "residual": o.residual, **self.fields,
                "wall_s": self.wall_s, "cpu_s": self.cpu_s}


def orbit_fields(system, model, coefficients, speed_rad_s: float, period_revs: int = 1, stations=None) -> dict:
    """The JSON fields of an HB orbit shared with shooting (see the module docstring): velocity amplitudes of
    ``<station>.<y|z>`` (mm/s), ``max_edge_penetration_mm``, the contact summary over one period sampled at
    :data:`N_SAMPLES` instants, and ``phase0_state`` (full q, v at t = 0)."""
    c = np.asarray(coefficients, float)
    H, P = (c.shape[0] - 1) // 2, int(period_revs)
    stations = model.response_stations() if stations is None else tuple(stations)
    names = [f"{s}.{x}" for s in stations for x in ("y", "z")]
    amps = {}
    for n in names:
        i = model.dof_index(n)
        amps[n] = [float(o * speed_rad_s * math.hypot(c[2 * o * P - 1, i], c[2 * o * P, i]) * 1e3)
                   if o * P <= H else 0.0 for o in ORDERS]
    t, q, v = sample_series(c, speed_rad_s / P, N_SAMPLES)
    out = {"velocity_amplitudes_mm_s_1X_to_5X": amps, "max_edge_penetration_mm": 0.0,
           "phase0_state": {"q_m_rad": [float(x) for x in c[0] + c[1::2].sum(axis=0)],
                            "v_m_s_rad_s": [float(x) for x in v[0]]}}
    sup = system.support
    if sup is not None:
        B = sup.relative_map(system.n)
        u, du = q @ B.T, v @ B.T
        r1, r2 = edge_offsets(u, sup.width_m)
        out["max_edge_penetration_mm"] = max(float(max(r1.max(), r2.max())) - sup.law.clearance_m, 0.0) * 1e3
        f = support_forces(sup.law, u, du)
        out.update(contact_summary(t, f, np.zeros((len(t), 2), int), None, sup.faces()[2]))
    return out


def min_harmonics(system, period_revs: int = 1) -> int:
    """The fewest harmonics that hold every load order of ``system`` (order × ``period_revs``), at least 1."""
    f = system.force
    return max([1] + [int(round(float(o) * period_revs)) for o, c, s_ in zip(f.orders, f.cos, f.sin)
                      if np.any(c) or np.any(s_)])


def _ladder(system, harmonics, n_time, period_revs, tail_tol, guess, max_cpu_s):
    """The orbit at fixed ``harmonics``, or climbing 1, 2, 4 … :data:`MAX_AUTO_HARMONICS` (from the fewest that
    hold the load) until the tail is below ``tail_tol`` or the next rung's predicted CPU (the last one's × 8)
    exceeds ``max_cpu_s``: ``(orbit, ladder, tail)``; the last converged orbit when no rung met the tail."""
    low = min_harmonics(system, period_revs)
    rungs = [int(harmonics)] if harmonics else [h for h in (2 ** k for k in range(12)) if h <= MAX_AUTO_HARMONICS]
    rungs = rungs if harmonics else [h for h in rungs if h >= low] or [low]
    ladder, orbit, tail = [], None, math.inf
    if not harmonics and math.isfinite(max_cpu_s):
        # the first rung once before the clock: a first use compiles the AFT path (measured in a fresh clone: the
        # compile made rung 1 look over 30/8 s, the ladder stopped at 1 harmonic and auto chose shooting)
        hb_orbit(system, rungs[0], n_time, period_revs=period_revs, guess=guess)
    for H in rungs:
        if ladder and 8.0 * ladder[-1][3] > max_cpu_s:
            break
        c0 = time.process_time()
        o = hb_orbit(system, H, n_time, period_revs=period_revs, guess=orbit if orbit is not None else guess)
        t = spectrum_tail(system, o.coefficients) if o.converged else math.inf
        ladder.append((H, t, bool(o.converged), time.process_time() - c0))
        if not o.converged:
            break
        orbit, tail = o, t
        if tail < tail_tol:
            break
    return orbit if orbit is not None else o, tuple(ladder), tail


def hb_point(scene: str, speed_rpm: float, *, harmonics: int | None = None, n_time: int | None = None,
             period_revs: int = 1, tail_tol: float = TAIL_TOL, max_cpu_s: float = math.inf, stations=None, guess=None,
             **overrides) -> HBPoint:
    """The HB orbit of ``scene`` at ``speed_rpm`` (rpm) with its reported fields.

    Parameters
    ----------
    harmonics : int or None
        H; None: climbed by the spectrum (module docstring) to :data:`MAX_AUTO_HARMONICS`.
    n_time : int or None
        AFT samples per period (None: 4H + 2).
    period_revs : int
        Period in revolutions (the fundamental is ``Ω/period_revs``).
    tail_tol : float
        Bound of the spectrum tail for the ladder (–).
    max_cpu_s : float
        No rung of the ladder started whose predicted CPU (the last rung's × 8) exceeds it (s).
    overrides
        As :func:`rotor.studies.steady_state.point_system`. Raises InputError where HB does not apply.
    """
    w0, c0 = time.perf_counter(), time.process_time()
    _, model, system = point_system(scene, speed_rpm, **overrides)
    orbit, ladder, tail = _ladder(system, harmonics, n_time, period_revs, tail_tol, guess, max_cpu_s)
    fields = orbit_fields(system, model, orbit.coefficients, orbit.speed_rad_s, period_revs, stations)
    return HBPoint(float(speed_rpm), orbit, fields, ladder, tail, time.perf_counter() - w0, time.process_time() - c0)


def hb_scene_branch(scene: str, rpm_start: float, rpm_end: float, *, harmonics: int | None = None,
                    n_time: int | None = None, max_points: int = 5000, tail_tol: float = TAIL_TOL,
                    **overrides) -> dict:
    """An HB branch of ``scene`` from ``rpm_start`` to ``rpm_end`` (rpm) as ``branch`` reports it: ``points``
    (``speed_rpm``, ``stable`` None, the fields of :func:`orbit_fields` but ``phase0_state``, ``residual``),
    ``bifurcations`` (``kind``: fold, grazing_fold, corner, grazing; ``speed_rpm``; ``after_point``), ``stop``,
    ``method`` "hb", ``harmonics`` (given, or chosen by the ladder at ``rpm_start``), ``start`` (the start orbit's
    :meth:`HBPoint.as_dict`), ``wall_s``, ``cpu_s``. Raises ConvergenceError where no HB orbit is found at the
    start."""
    from rotor.periodic.harmonic_balance import HBContinuationOptions

    w0, c0 = time.perf_counter(), time.process_time()
    start = hb_point(scene, rpm_start, harmonics=harmonics, n_time=n_time, tail_tol=tail_tol, **overrides)
    if not start.orbit.converged:
        raise ConvergenceError(f"harmonic balance at {rpm_start:g} rpm: no orbit (Newton stalled at relative "
                               f"residual {start.orbit.residual:.2e})")
    H = start.orbit.harmonics
    _, model, system = point_system(scene, rpm_start, **overrides)     # the support and stations: as at any speed
    # built once: the gyroscopic term and the Ω² loads exact at every speed; speed-table bearings rebuilt per speed
    family = SpeedFamily(system, (lambda w: point_system(scene, w * TO_RPM, **overrides)[2])
                         if model.speed_bearings else None)
    br = hb_branch(family, rpm_start / TO_RPM, rpm_end / TO_RPM, H, n_time, guess=start.orbit,
                   options=HBContinuationOptions(max_points=int(max_points)))
    pts = []
    for w, c, res in zip(br.speeds_rad_s, br.coefficients, br.residuals):
        f = orbit_fields(system, model, c, float(w))
        f.pop("phase0_state")
        pts.append({"speed_rpm": float(w) * TO_RPM, "stable": None, **f, "residual": float(res)})
    bifs = [{"kind": e.kind, "speed_rpm": e.speed_rad_s * TO_RPM, "after_point": int(e.index)} for e in br.events]
    stop = "end reached" if br.stop == "reached the end speed" else br.stop
    return {"method": "hb", "harmonics": H, "n_time": br.n_time, "points": pts, "bifurcations": bifs, "stop": stop,
            "hb_stop": br.stop, "rejected_steps": br.rejected_steps, "start": start.as_dict(),
            "wall_s": time.perf_counter() - w0, "cpu_s": time.process_time() - c0, "branch": br}
