"""Periodic orbits and branches of a scene's rotor, as the command line asks for them.

:func:`orbit` is one operating point: the periodic orbit by shooting (:mod:`rotor.periodic.shooting`) from a
short transient from :func:`rotor.dynamics.static_start.periodic_start`: under gravity or static loads the faces
cannot hold out of contact, the static equilibrium (the ring's contact and the faces' friction solved statically) with
the linear forced response about it; otherwise the linear periodic solution, as measured there (the JSON's
``transient_start`` says which and why), its Floquet
multipliers and stability (:mod:`rotor.periodic.floquet`) and the
1X-5X velocity amplitudes at every response station, the same quantity and key as ``simulate --steady``
(``velocity_amplitudes_mm_s_1X_to_5X``, mm/s, exact DFT bins over the whole period,
:func:`rotor.studies.steady_state.harmonic_amplitudes`). :func:`branch` follows the orbit over a speed range
by pseudo-arclength continuation (:mod:`rotor.periodic.continuation`) and lists the bifurcations met.

Steps per revolution: :func:`rotor.studies.steady_state.step_per_rev` (256 by default, more where the contact
step limit needs it), fixed along a branch at the value its lowest speed needs, so that every orbit of the
branch repeats exactly on the step grid.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from contact.errors import InputError
from contact import plausible
from contact.units import ARCMIN, check_positive
from rotor.dynamics.constraints import STICK, edge_offsets
from rotor.dynamics.initial import linear_initial_state
from rotor.dynamics.static_start import FORCED_KIND, LINEAR_KIND, forced_start, periodic_start, start_record
from rotor.dynamics.support_record import contact_summary
from rotor.model.law_validity import record as validity_record
from rotor.periodic.continuation import (COLD, GRID, SECANT, TRANSIENT, Branch, ContinuationOptions, continue_branch,
                                        speed_problem, start_modes)
from rotor.periodic.floquet import FloquetResult
from rotor.periodic.grazing import continue_through_grazing
from rotor.periodic.period_flow import Flow, make_flow, record, to_full
from rotor.periodic.richardson import extrapolate_branch
from rotor.periodic.shooting import MAX_PERIOD_REVS, ShootingOptions, ShootingResult, shoot, shoot_from_transient
from rotor.studies.steady_state import SteadyStateOptions, harmonic_amplitudes, point_system, step_per_rev

ORDERS = (1, 2, 3, 4, 5)
#: how a branch point past a stick/slip switch was reached (:mod:`rotor.periodic.continuation`); None: by the corrector
RESTART_KINDS = {SECANT: "secant", TRANSIENT: "transient", COLD: "cold", GRID: "step-grid"}


#: the words for an orbit that is one member of a continuum of orbits held by friction (JSON ``family``, tables)
FRICTION_FAMILY = "not unique: a family held by friction"


def family_held_by_friction(floquet) -> str | None:
    """:data:`FRICTION_FAMILY` where ``floquet`` has neutral multipliers (a face stuck through the period: the
    stuck-face continuum of :mod:`rotor.periodic.floquet`), else None."""
    return FRICTION_FAMILY if int(floquet.n_neutral) > 0 else None


@dataclass(frozen=True)
class OrbitResult:
    """One periodic orbit of a scene at one speed (SI inside; the amplitudes in mm/s as the CLI prints them).

    Attributes
    ----------
    speed_rpm : float
        Speed (rpm).
    period_revs : int
        Period in revolutions.
    period_s : float
        Period (s).
    steps_per_rev : int
        Newmark steps per revolution.
    converged : bool
        Newton met its tolerance.
    stable : bool
        Every non-neutral Floquet multiplier inside the unit circle.
    floquet : rotor.periodic.floquet.FloquetResult
        Multipliers and their classification.
    velocity_amplitudes_mm_s_1X_to_5X : dict
        ``<station>.<y|z>`` -> five amplitudes (mm/s).
    newton_iterations : int
        Newton iterations of the last shooting round.
    residual : float
        Periodicity residual relative to the orbit scale (–).
    transient_revs : int
        Revolutions of transient before Newton converged.
    settled (JSON key, from ``shooting.settled``) : bool
        On a continuum of orbits (a face stuck through the period), the transient's conserved levels had
        stopped drifting when the orbit was shot, so the orbit is the member the transient settles on
        (:func:`rotor.periodic.shooting.shoot_from_transient`); always True without a continuum.
    events : int
        End-face mode changes over the period.
    singular_directions : int
        Directions of M − I dropped by the Newton step (the continuum's conserved levels,
        :func:`rotor.periodic.shooting.level_step`).
    wall_s : float
        Wall time (s).
    switch_free : bool
        No end-face mode change over the period. With switches the monodromy is still the
        exact derivative of the scheme's map while every switch stays in its step, but a perturbation that
        moves a switch by a step makes the map jump (the discrete trace of the continuous system's saltation,
        :mod:`rotor.dynamics.period_map`), which the multipliers do not see.
    backend : str
        Monodromy backend used (exact or finite differences).
    shooting : rotor.periodic.shooting.ShootingResult
        The reduced state, its monodromy and scales.
    q_m, v_m_s : numpy.ndarray
        (n,) the orbit's full state at phase 0 (m, rad; m/s, rad/s): a ``start`` for a neighbouring speed.
    max_edge_penetration_m : float
        Largest penetration of a ring edge past the clearance over the period (m, every step; 0 without
        contact or without a loose support), the quantity of ``simulate``'s ``max_edge_penetration_mm``.
    contact : dict
        The loose support over the same period (every step, phase 0 to the period's end), the keys and
        quantities of ``simulate``'s summary (:func:`rotor.dynamics.support_record.contact_summary`):
        ``peak_contact_force_N`` at ``peak_contact_force_t_s`` (s after phase 0), ``mean_contact_force_N``,
        ``peak_contact_moment_Nm``, ``contact_share``, ``separation_share``, ``stick_share_right_face``,
        ``stick_share_left_face``, ``peak_face_force_N``; empty without a loose support. A ring stuck on a
        linear orbit has ``contact_share`` 0 and both faces' stick share 1; a slipping, hitting one does not.
        ``law_validity``: the record of :func:`rotor.model.law_validity.record` over the period.
    """

    speed_rpm: float
    period_revs: int
    period_s: float
    steps_per_rev: int
    converged: bool
    stable: bool
    floquet: FloquetResult
    velocity_amplitudes_mm_s_1X_to_5X: dict
    newton_iterations: int
    residual: float
    transient_revs: int
    events: int
    singular_directions: int
    wall_s: float
    backend: str
    shooting: ShootingResult
    q_m: np.ndarray
    v_m_s: np.ndarray
    max_edge_penetration_m: float = 0.0
    contact: dict = field(default_factory=dict)
    richardson: dict | None = None
    start: dict | None = None

    @property
    def switch_free(self) -> bool:
        return self.events == 0

    @property
    def unique(self) -> bool:
        """False where the orbit is one member of a family held by friction: a face stuck through the period
        leaves multipliers at +1 (``floquet.n_neutral``, :mod:`rotor.periodic.floquet`), a continuum of orbits
        that differ by where the ring stuck; this one is where the transient settled (``settled``), and
        ``simulate`` from another start may give another member (another contact share)."""
        return family_held_by_friction(self.floquet) is None

    def as_dict(self) -> dict:
        """JSON-ready summary, keys with units."""
        return {"speed_rpm": self.speed_rpm, "period_revs": self.period_revs, "period_s": self.period_s,
                "steps_per_rev": self.steps_per_rev, "converged": self.converged, "stable": self.stable,
                "multipliers": self.floquet.as_dict()["multipliers"], "spectral_radius": self.floquet.spectral_radius,
                "critical_kind": self.floquet.kind, "leading_multiplier": self.floquet.leading,
                "neutral_multipliers": self.floquet.n_neutral,
                "velocity_amplitudes_mm_s_1X_to_5X": self.velocity_amplitudes_mm_s_1X_to_5X,
                "newton_iterations": self.newton_iterations, "residual": self.residual,
                "transient_revs": self.transient_revs, "settled": self.shooting.settled,
                "face_mode_changes": self.events, "unique": self.unique, "family": family_held_by_friction(self.floquet),
                "singular_directions": self.singular_directions, "switch_free": self.switch_free,
                "max_edge_penetration_mm": self.max_edge_penetration_m * 1e3, **self.contact,
                "wall_s": self.wall_s, "backend": self.backend,
                "phase0_state": {"q_m_rad": [float(x) for x in self.q_m], "v_m_s_rad_s": [float(x) for x in self.v_m_s]},
                **({} if self.richardson is None else {"richardson": self.richardson}),
                **({} if self.start is None else {"transient_start": self.start})}


def velocity_amplitudes(flow: Flow, model, res_state, t0_s: float, modes, period_revs: int, steps_per_rev: int,
                        stations=None) -> dict:
    """1X-5X velocity amplitudes (mm/s) of ``<station>.y/z`` over one period recorded at every step from the
    reduced state at ``t0_s`` (stations: ``model.response_stations()`` by default)."""
    return period_response(flow, model, res_state, t0_s, modes, period_revs, steps_per_rev, stations)[0]


def period_response(flow: Flow, model, res_state, t0_s: float, modes, period_revs: int, steps_per_rev: int,
                    stations=None) -> tuple[dict, float, dict]:
    """:func:`velocity_amplitudes`, the largest edge penetration past the clearance over the same period (m, 0
    without contact or without a loose support; :func:`rotor.dynamics.constraints.edge_offsets`) and the
    contact force and face stick over it (:func:`rotor.dynamics.support_record.contact_summary`, the time of
    the peak counted from ``t0_s``; empty without a loose support)."""
    stations = model.response_stations() if stations is None else tuple(stations)
    names = [f"{s}.{c}" for s in stations for c in ("y", "z")]
    idx = [model.dof_index(n) for n in names]
    tr = record(flow, res_state, t0_s, period_revs * steps_per_rev, modes, 1)
    v = tr.v[:-1, idx]
    amps = np.abs(harmonic_amplitudes(v - v.mean(axis=0), period_revs, ORDERS))
    sup = flow.system.support
    pen, contact = 0.0, {}
    if sup is not None:
        r1, r2 = edge_offsets(tr.u, sup.width_m)
        pen = max(float(max(r1.max(), r2.max())) - sup.law.clearance_m, 0.0)
        one = slice(0, -1)   # one period: the last sample starts the next one
        contact = contact_summary(tr.t[one] - t0_s, tr.f_contact[one], tr.modes[one], tr.face_force[one],
                                  sup.faces()[2])
        hit = (r1 > sup.law.clearance_m) | (r2 > sup.law.clearance_m)
        tilt = np.hypot(tr.u[:, 2], tr.u[:, 3])[hit]
        contact["max_tilt_in_contact_arcmin"] = float(tilt.max()) / ARCMIN if tilt.size else 0.0
        # the law's validity over the period (rotor/model/law_validity.py: the record every rotor job carries)
        contact["law_validity"] = validity_record(model.scene.loose_support, np.maximum(r1, r2)[one] - sup.law.clearance_m,
                                                  np.hypot(tr.u[one, 2], tr.u[one, 3]))
    return {n: [float(a) * 1e3 for a in amps[:, j]] for j, n in enumerate(names)}, pen, contact


def _overrides(kw: dict) -> dict:
    keys = ("clearance_m", "misalignment_m", "tilt_ignored", "mu", "preload_n", "elements_per_segment", "law")
    return {k: kw[k] for k in keys if k in kw and kw[k] is not None}


def orbit(scene: str, speed_rpm: float, *, steps_per_rev: int | None = None, period_revs: int | None = None,
          backend: str = "auto", options: ShootingOptions | None = None, start=None, stations=None,
          period_hint: int | None = None, richardson: bool = False, friction_scheme: str | None = None,
          **overrides) -> OrbitResult:
    """The periodic orbit of ``scene`` at ``speed_rpm`` (rpm), its stability and 1X-5X velocity amplitudes.

    ``overrides``: ``clearance_m``, ``misalignment_m``, ``tilt_ignored``, ``mu``, ``preload_n``,
    ``elements_per_segment``, ``law`` (as :func:`rotor.studies.steady_state.point_system`). ``steps_per_rev`` None:
    :func:`rotor.studies.steady_state.step_per_rev`. ``period_revs`` None: found (1..8). ``start``: full
    ``(q0, v0)`` at t = 0 (e.g. a neighbouring speed's orbit), or ``"linear"`` (the linear periodic solution, support
    locked), ``"equilibrium"``; None: :func:`transient_start`'s rule.
    ``period_hint``: a period (revolutions) to try in every transient round besides those the Poincaré
    returns support (a neighbouring speed's, :func:`cascade`). ``richardson``: also the orbit with twice the steps
    from this one and the amplitudes extrapolated to continuous time (:func:`richardson_fields`, JSON
    ``richardson``). ``friction_scheme``: "active-set" or "projection"
    (:attr:`rotor.dynamics.system.NewmarkOptions.friction_scheme`); None: the scheme's default.
    """
    t_start = time.perf_counter()
    check_positive("speed_rpm", speed_rpm, "rpm", upper=plausible.top("run_speed_rpm"))    # an orbit needs a period: no zero speed
    if period_revs is not None and not (int(period_revs) == period_revs and 1 <= period_revs <= MAX_PERIOD_REVS):
        raise InputError(f"period_revs = {period_revs}: must be a whole number of revolutions, 1 to {MAX_PERIOD_REVS}")
    _, model, system = point_system(scene, speed_rpm, **_overrides(overrides))
    n = int(steps_per_rev or step_per_rev(system, SteadyStateOptions()))
    flow = make_flow(system, 2.0 * math.pi / (system.omega_rad_s * n), backend, friction_scheme=friction_scheme)
    q0, v0, start_info = transient_start(system, model, start)
    res = shoot_from_transient(flow, q0, v0, steps_per_rev=n, period_revs=period_revs, options=options,
                               period_hint=period_hint)
    if not res.converged and flow.handle.options.locate_events:
        res = _from_step_grid_orbit(flow, system, n, backend, q0, v0, res, period_revs, options, period_hint)
    amps, pen, contact = period_response(flow, model, res.state, res.t0_s, res.modes, res.period_revs, n, stations)
    q, v = to_full(flow, res.state, 0.0)
    rich = None
    if richardson and res.converged:
        fine = orbit(scene, speed_rpm, steps_per_rev=2 * n, period_revs=res.period_revs, backend=backend,
                     start=(q, v), options=ShootingOptions(transient_revs=1, round_growth=2.0), stations=stations,
                     friction_scheme=friction_scheme, **overrides)
        rich = richardson_fields(n, amps, pen, fine.converged, fine.velocity_amplitudes_mm_s_1X_to_5X,
                                 fine.max_edge_penetration_m)
    return OrbitResult(float(speed_rpm), res.period_revs, res.period_s, n, res.converged, res.floquet.stable,
                       res.floquet, amps, res.newton_iterations, res.residual, res.transient_revs, res.events,
                       res.singular_directions, time.perf_counter() - t_start, flow.backend, res, q, v, pen, contact,
                       rich, start_info)


def transient_start(system, model, start=None) -> tuple:
    """``(q0, v0, record)`` of an orbit's transient: ``start`` None: :func:`rotor.dynamics.static_start.periodic_start`
    (the static equilibrium with the linear forced response about it under gravity or static loads the faces cannot
    hold out of contact, else the linear periodic solution); ``"equilibrium"``: that equilibrium start always
    (:func:`rotor.dynamics.static_start.forced_start`); ``"linear"``: the linear periodic solution (support locked,
    :func:`rotor.dynamics.initial.linear_initial_state`); else a given full ``(q0, v0)``. ``record``: the JSON
    ``transient_start``."""
    if isinstance(start, str) and start not in ("equilibrium", "linear"):
        raise InputError(f"start = {start!r}: 'equilibrium', 'linear' or a full (q0, v0) state")
    if start is None:
        return periodic_start(system, model, 0.0)
    if start == "linear":
        return (*linear_initial_state(system, 0.0), {"kind": LINEAR_KIND, "why": "asked for"})
    if start == "equilibrium":
        q0, v0, eq = forced_start(system, 0.0)
        return q0, v0, {**start_record(system, eq), "kind": FORCED_KIND, "why": "asked for"}
    return start[0], start[1], {"kind": "given state"}


def richardson_fields(n: int, amps: dict, pen_m: float, fine_converged: bool, fine_amps: dict, fine_pen_m: float,
                      speed_rpm: float | None = None) -> dict:
    """Richardson extrapolation (Richardson 1911) of an orbit's amplitudes in the step: the scheme is symmetric, so
    a quantity of its orbit is ``y_N = y* + C h² + O(h⁴)`` on a fixed hyperplane (:mod:`rotor.periodic.richardson`)
    and ``(4 y_2N − y_N)/3`` is within ``O(h⁴)`` of the continuous-time value. ``amps``/``fine_amps``: 1X-5X
    velocity amplitudes (mm/s) with ``n`` and ``2n`` steps per revolution; ``pen_m``/``fine_pen_m``: largest edge
    penetration (m). Returns the JSON ``richardson`` (``speed_rpm``: the extrapolated speed where the branch's
    hyperplane fixed a state component instead); ``converged`` False (and no values) where the 2N orbit failed."""
    out = {"steps_per_rev": [n, 2 * n], "converged": bool(fine_converged)}
    if not fine_converged:
        return out
    ext = {k: [(4.0 * b - a) / 3.0 for a, b in zip(amps[k], fine_amps[k])] for k in amps}
    top = max(max(abs(x) for x in v) for v in ext.values()) if ext else 0.0
    out.update({**({} if speed_rpm is None else {"speed_rpm": speed_rpm}), "velocity_amplitudes_mm_s_1X_to_5X": ext,
                "max_edge_penetration_mm": max((4.0 * fine_pen_m - pen_m) / 3.0, 0.0) * 1e3,
                "largest_change_from_N": max((abs(e - a) for k in amps for a, e in zip(amps[k], ext[k])), default=0.0)
                / top if top else 0.0})
    return out


def _from_step_grid_orbit(flow: Flow, system, n: int, backend: str, q0, v0, failed: ShootingResult, period_revs,
                          options, period_hint) -> ShootingResult:
    """Where no orbit of the located map (events inside the step) was found from its transients: the orbit of the
    step-grid map (events on step boundaries, :attr:`rotor.dynamics.system.NewmarkOptions.locate_events` False)
    from its own transients, then Newton on the located map from it (the two orbits differ by the scheme's
    ``O(h²)``). Returns that orbit, with both searches' transient revolutions and wall time, or ``failed``.

    Measured on paper-table4 without friction (μ = 0, 256 steps per revolution): at 12 000 rpm the located
    search found no orbit in 2 000 transient revolutions (13 Newton attempts), the step-grid search found an
    unstable period-1 orbit (largest multiplier 21.07) after 317, and Newton on the located map converged from it
    in 2 iterations (located residual there 1.9e-2; located monodromy 5.3e-7 from central differences, largest
    multiplier 21.05); at 15 000 rpm the step-grid orbit (multiplier 2.41) is also the located map's (residual
    1.2e-11, no edge crossing in the period), which the located transients did not find. Unstable orbits are
    reached by Newton from transient states only by chance, and the two maps' transients differ."""
    plain = make_flow(system, flow.dt_s, backend, locate_events=False)
    grid = shoot_from_transient(plain, q0, v0, steps_per_rev=n, period_revs=period_revs, options=options,
                                period_hint=period_hint)
    revs, wall = failed.transient_revs + grid.transient_revs, failed.wall_s + grid.wall_s
    if grid.converged:
        res = shoot(flow, grid.state, t0_s=grid.t0_s, steps_per_rev=n, period_revs=grid.period_revs,
                    modes0=grid.modes, scales=grid.scales, options=options or ShootingOptions())
        if res.converged:
            return replace(res, transient_revs=revs, settled=grid.settled, wall_s=wall + res.wall_s)
    return replace(failed, transient_revs=revs, wall_s=wall)


def uncovered_rpm(before, speed_rpm: float, ahead: float):
    """``[farthest, speed_rpm]``: the speeds (rpm) between the farthest of the branch's speeds ``before`` in the
    direction ``ahead`` (±1) and a restarted orbit's ``speed_rpm`` beyond it, which no orbit of the branch covers;
    None where the restart lands within the speeds covered (after a run back from a fold, the restart's
    ``skipped_rpm`` starts at the orbit the branch ran back to)."""
    far = max(v * ahead for v in before) * ahead
    return [far, speed_rpm] if (speed_rpm - far) * ahead > 0 else None


@dataclass(frozen=True)
class BranchResult:
    """A branch of orbits over speed: ``points`` (dicts: ``speed_rpm``, ``stable``, ``spectral_radius``,
    ``critical_kind``, ``leading_multiplier``, ``restarted`` (None, or how a point past a stick/slip switch was
    shot: ``secant``, ``transient``, ``cold``; a restarted point also has ``skipped_rpm``, the speeds of the orbit
    before it and its own: the range the restart jumped over, and ``uncovered_rpm``, the farthest speed reached
    before it and its own where the restart lands beyond it (the speeds no orbit of the branch covers), else None), ``velocity_amplitudes_mm_s_1X_to_5X``, ``max_edge_penetration_mm``
    and the contact fields of :attr:`OrbitResult.contact`),
    ``bifurcations`` (dicts: ``kind``,
    ``speed_rpm``), ``start`` (the first orbit), ``stop`` (why it ended), ``wall_s`` (s), ``branch``
    (the :class:`rotor.periodic.continuation.Branch`); the JSON adds ``corrector_failures``: every stall of
    the corrector (speed, why, how it was passed: a smaller step, a restart, or the stop)."""

    points: tuple
    bifurcations: tuple
    start: OrbitResult
    stop: str
    wall_s: float
    branch: Branch

    def as_dict(self) -> dict:
        kinds = [p.get("restarted") for p in self.points]
        return {"points": list(self.points), "bifurcations": list(self.bifurcations), "start": self.start.as_dict(),
                "stop": self.stop, "wall_s": self.wall_s,
                "restarts": {k: kinds.count(k) for k in RESTART_KINDS.values()},
                "corrector_failures": [{"speed_rpm": lam * 30.0 / math.pi, "why": why, "outcome": outcome}
                                       for lam, why, outcome in self.branch.failures]}


def branch(scene: str, rpm_start: float, rpm_end: float, *, steps_per_rev: int | None = None, backend: str = "auto",
           options: ContinuationOptions | None = None, amplitudes: bool = True, through_grazing: bool | None = None,
           start=None, period_revs: int | None = None, locate_events: bool | None = None, richardson: bool = False,
           friction_scheme: str | None = None, **overrides) -> BranchResult:
    """Continue the orbit found at ``rpm_start`` (:func:`orbit`) in speed until ``rpm_end`` (rpm).

    The arclength is measured with the start orbit's scales and a speed scale of a tenth of the range.
    ``amplitudes``: record each point's 1X-5X velocity amplitudes (one extra period per point).
    ``through_grazing``: follow the branch through orbits that graze the ring
    (:func:`rotor.periodic.grazing.continue_through_grazing`: grazing folds reported, no restart there); None:
    on for a frictionless ring (``μ N = 0``: no stick/slip switch, a grazing is the map's only corner), off with
    end-face friction, where it is not yet measured against the published Table 4 branches (a first run, 80
    points from 600 rpm, met no grazing and reached 2 171 rpm in 338 s at a load average of 10).
    ``start``: the full ``(q0, v0)`` of a chosen orbit at ``rpm_start`` (phase 0, e.g. ``phase0_state`` of an
    ``orbit --out`` file, with its ``period_revs``): the branch starts on that orbit (one revolution of
    transient, then Newton), an unstable one included, instead of the one a transient from rest reaches;
    without ``period_revs`` (a state at phase 0, e.g. the end of a ``simulate`` run): the orbit a transient
    from that state reaches (period found).
    ``locate_events``: the continuation's maps locate friction events inside the step
    (:func:`rotor.periodic.period_flow.make_flow`; None: the scheme's default). ``friction_scheme``: as
    :func:`orbit`.
    ``richardson``: every point also corrected with twice the steps per revolution and extrapolated
    (:func:`rotor.periodic.richardson.extrapolate_branch`; each point's JSON ``richardson``, :func:`richardson_fields`).
    """
    t_start = time.perf_counter()
    check_positive("rpm_start", rpm_start, "rpm", upper=plausible.top("run_speed_rpm"))
    check_positive("rpm_end", rpm_end, "rpm", upper=plausible.top("run_speed_rpm"))
    if rpm_start == rpm_end:
        raise InputError(f"rpm_end = {rpm_end:g} rpm: must differ from rpm_start = {rpm_start:g} rpm")
    ov = _overrides(overrides)
    _, model, sys_lo = point_system(scene, min(rpm_start, rpm_end), **ov)
    n = int(steps_per_rev or step_per_rev(sys_lo, SteadyStateOptions()))
    # a chosen orbit (its period given): one revolution of transient, then Newton; a given state alone: the
    # transient from it, as from the linear periodic solution
    chosen = ({} if start is None else {"start": start} if period_revs is None else
              {"start": start, "period_revs": period_revs, "options": ShootingOptions(transient_revs=1, round_growth=2.0)})
    first = orbit(scene, rpm_start, steps_per_rev=n, backend=backend, friction_scheme=friction_scheme, **chosen, **ov)
    if not first.converged:
        return BranchResult((), (), first, "no orbit at the start", time.perf_counter() - t_start,
                            Branch((), (), first.period_revs, "no orbit at the start", 0.0))
    to_rpm = 30.0 / math.pi

    def system_at(w):
        return point_system(scene, w * to_rpm, **ov)[2]

    res = first.shooting
    # the orbit's start time is a whole number of revolutions: phase 0, where the continuation's maps start
    pb = speed_problem(system_at, n, period_revs=first.period_revs, backend=backend, modes0=res.modes,
                       locate_events=locate_events, friction_scheme=friction_scheme)
    w0, w1 = rpm_start / to_rpm, rpm_end / to_rpm
    follow = continue_through_grazing if follows_grazing(sys_lo.support, through_grazing) else continue_branch
    br = follow(pb, res.state, w0, w1, scales=res.scales, lam_scale=abs(w1 - w0) / 10.0, options=options)
    ex = (extrapolate_branch(pb, br, scales=res.scales, lam_scale=abs(w1 - w0) / 10.0, options=options)
          if richardson and br.points else None)
    pts, ahead = [], math.copysign(1.0, rpm_end - rpm_start)
    for i, p in enumerate(br.points):
        d = {"speed_rpm": p.parameter * to_rpm, "stable": bool(p.floquet.stable),
             "spectral_radius": p.floquet.spectral_radius, "critical_kind": p.floquet.kind,
             "leading_multiplier": p.floquet.leading, "restarted": RESTART_KINDS.get(int(p.restarted)),
             "switches_per_period": int(p.events), "unique": family_held_by_friction(p.floquet) is None,
             # the end-face modes its period map starts from (a restart may land on an orbit with other modes there)
             **{f"stuck_at_phase_0_{face}_face": bool(m == STICK) for face, m in zip(("right", "left"), start_modes(pb, p))}}
        if p.restarted and pts:         # the speeds the restart jumped over, from the orbit before it, and why
            d["skipped_rpm"] = [pts[-1]["speed_rpm"], d["speed_rpm"]]
            d["uncovered_rpm"] = uncovered_rpm([q["speed_rpm"] for q in pts], d["speed_rpm"], ahead)
            d["restart_reason"] = p.why
        if amplitudes:
            flow = pb.flow(p.parameter)
            amps, pen, contact = period_response(flow, model, p.state, 0.0, start_modes(pb, p), pb.period_revs, n)
            d["velocity_amplitudes_mm_s_1X_to_5X"], d["max_edge_penetration_mm"] = amps, pen * 1e3
            d.update(contact)
        if ex is not None:
            d["richardson"] = _extrapolated_point(pb, ex, i, p, model, start_modes(pb, p))
        pts.append(d)
    bifs = tuple({"kind": b.kind, "speed_rpm": b.parameter * to_rpm, "after_point": b.index,
                  **({"detail": b.detail} if b.detail else {})} for b in br.bifurcations)
    return BranchResult(tuple(pts), bifs, first, br.stop, time.perf_counter() - t_start, br)


def _extrapolated_point(pb, ex, i: int, point, model, modes) -> dict:
    """The JSON ``richardson`` of branch point ``i`` (``point``, N steps per revolution) from
    :func:`rotor.periodic.richardson.extrapolate_branch`'s result ``ex``: the amplitudes over one period of the
    point and of its 2N orbit, extrapolated (:func:`richardson_fields`)."""
    n = pb.steps_per_rev
    if not ex.converged[i]:
        return richardson_fields(n, {}, 0.0, False, {}, 0.0)
    a, pen, _ = period_response(pb.flow(point.parameter), model, point.state, 0.0, modes, pb.period_revs, n)
    b, pen2, _ = period_response(replace(pb, steps_per_rev=2 * n).flow(ex.fine_parameters[i]), model,
                                 ex.fine_states[i], 0.0, modes, pb.period_revs, 2 * n)
    return richardson_fields(n, a, pen, True, b, pen2, speed_rpm=float(ex.parameters[i]) * 30.0 / math.pi)


def follows_grazing(support, through_grazing: bool | None) -> bool:
    """Whether :func:`branch` follows grazing orbits (:func:`rotor.periodic.grazing.continue_through_grazing`):
    as asked, and by default (None) on a frictionless ring (``μ N = 0``); never without a loose support."""
    if support is None:
        return False
    return support.mu * support.preload_N == 0.0 if through_grazing is None else bool(through_grazing)


def warm_options(options: ShootingOptions | None = None) -> ShootingOptions:
    """``options`` for a start from a neighbouring speed's orbit (:func:`cascade`): 2 transient revolutions
    before Newton, then rounds doubling in length."""
    return ShootingOptions(**{**(options or ShootingOptions()).__dict__, "transient_revs": 2, "round_growth": 2.0})


def cascade(scene: str, speeds_rpm, *, steps_per_rev: int | None = None, backend: str = "auto",
            options: ShootingOptions | None = None, **overrides) -> tuple:
    """:func:`orbit` at each speed of ``speeds_rpm`` (rpm, > 0) in order, each started from the previous
    converged orbit (2 transient revolutions before Newton, then rounds doubling in length, up to
    ``max_transient_revs``; every round tries the periods its Poincaré returns support and the neighbour's
    period) or, after a failure and at the first speed, from the linear periodic solution with the
    transient rounds of ``options``. A warm start that fails is not restarted cold: its own rounds are
    already a transient of the full budget from the neighbour's orbit, so a second one from the linear
    state would only spend the budget again (it found an orbit the warm rounds missed only where the
    two transients end on different attractors; the run-up cascade follows the one reached from the
    neighbour). Returns the :class:`OrbitResult` of every
    speed; ``converged`` False marks a speed where no orbit of 1..8 revolutions was found within
    ``max_transient_revs`` (quasi-periodic or chaotic; the neighbours' multipliers say which way it was
    left: a complex pair outside the circle, Neimark-Sacker, or a real one below −1, period doubling)."""
    opts = options or ShootingOptions()
    warm = warm_options(opts)
    out, prev = [], None
    for s in speeds_rpm:
        kw = dict(steps_per_rev=steps_per_rev, backend=backend, **overrides)
        if prev is not None:
            res = orbit(scene, s, start=(prev.q_m, prev.v_m_s), options=warm, period_hint=prev.period_revs, **kw)
        else:
            res = orbit(scene, s, options=opts, **kw)
        out.append(res)
        prev = res if res.converged else None
    return tuple(out)
