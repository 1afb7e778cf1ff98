"""Analyses of the loose-support rotor: time history, periodic orbit, branch of orbits, steady-state cascade.

Each function takes a :class:`ringcontact.Scene`, a scene file's path or a bundled scene's name, and the same
loose-support overrides (``clearance_m``, ``misalignment_m``, ``mu``, ``preload_n``, ``tilt_ignored``; None keeps
the scene's value; :func:`rotor.studies.steady_state.point_system`). They call the functions the jobs call
(``simulate``: :func:`rotor.dynamics.production.simulate_production`; ``orbit`` and ``branch``:
:mod:`rotor.studies.orbit`; ``study cascade``: :func:`rotor.studies.steady_state.run_point`). Every result
carries the contact-force summary of :func:`rotor.dynamics.support_record.contact_summary`: the peak radial
force of the support's bore on the bearing ring (N), the share of the time in contact, and the share each end
face sticks (empty or None for a scene without a loose support).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

import ringcontact._checks as _checks
from ringcontact.results import ResultMethods, internal, law_validity_attrs
from ringcontact.scene import as_scene

CONTACT_KEYS = ("peak_contact_force_N", "mean_contact_force_N", "peak_contact_moment_Nm", "contact_share",
                "separation_share", "stick_share_right_face", "stick_share_left_face", "peak_face_force_N")


def _overrides(clearance_m, misalignment_m, mu, preload_n, tilt_ignored, elements) -> dict:
    """The loose-support overrides, each checked with the range of the jobs' option (None keeps the scene's)."""
    c = _checks
    return {"clearance_m": None if clearance_m is None else c.number("clearance_m", clearance_m, "--clearance-mm",
                                                                     "clearance_mm", 1e-3, "m"),
            "misalignment_m": None if misalignment_m is None else c.number(
                "misalignment_m", misalignment_m, "--misalignment-mm", "misalignment_mm", 1e-3, "m"),
            "mu": None if mu is None else c.number("mu", mu, "--mu", "mu"),
            "preload_n": None if preload_n is None else c.number("preload_n", preload_n, "--preload-N", "preload_N",
                                                                 si_unit="N"),
            "tilt_ignored": c.flag_of("tilt_ignored", tilt_ignored),
            "elements_per_segment": None if elements is None else c.whole("elements", elements, "--elements",
                                                                         "elements")}


def _speed(keyword: str, rpm, flag: str = "--speed-rpm") -> float:
    """A spin speed (rpm) in the range of the jobs' ``--speed-rpm`` (> 0: a step is a share of a revolution)."""
    return _checks.number(keyword, rpm, flag, "run_speed_rpm", si_unit="rpm")


def _orbit_budget(func: str, sc, rpm: float, ov: dict, steps_per_rev, period_revs, points: int, accept_long) -> None:
    """The shooting work at ``rpm`` (and ``points`` orbits of a branch) against the jobs' budget, as ``orbit`` and
    ``branch`` estimate it (:func:`reports.cli._budget.orbit`), before :mod:`rotor.studies.orbit` is called."""
    from reports.cli import _budget
    from rotor.studies.steady_state import SteadyStateOptions, point_system, step_per_rev
    system = point_system(sc, rpm, **ov)[2]
    n = int(steps_per_rev or step_per_rev(system, SteadyStateOptions()))
    cause = (f"steps_per_rev = {n}" if steps_per_rev else
             f"{n} steps per revolution (the contact step limit at {rpm:g} rpm)")
    est = _budget.beyond_at_table4_cost(system, n, period_revs, points)      # at once, before any probe
    _checks.budget(func, est if est is not None else _budget.orbit(system, n, period_revs, points), accept_long,
                   cause + (f" and max_points = {points}" if points else ""),
                   "fewer steps per revolution" + (" or max_points" if points else ""))


def _law_allowed(sc, allowed):
    """``sc`` when its law may run: a law its file flags is refused unless ``allowed``
    (:func:`rotor.model.law_validity.check_allowed`)."""
    from rotor.model.law_validity import ALLOW_KEYWORD, check_allowed
    check_allowed(sc.loose_support, _checks.flag_of(ALLOW_KEYWORD, allowed), f"{ALLOW_KEYWORD}=True")
    return sc


class ContactSummary:
    """The contact-force summary of a result's ``contact`` dict as attributes (None without a loose support):
    ``peak_contact_force_N`` (N), ``contact_share`` (fraction of the time the ring touches its support),
    ``stick_share_right_face``, ``stick_share_left_face`` (fractions of the time each end face sticks)."""

    _summary = ("peak_contact_force_N", "contact_share", "stick_share_right_face", "stick_share_left_face")

    def _summary_value(self, key: str):
        v = self.contact.get(key)
        return None if v is None else float(v)

    @property
    def peak_contact_force_N(self) -> float | None:
        return self._summary_value("peak_contact_force_N")

    @property
    def contact_share(self) -> float | None:
        return self._summary_value("contact_share")

    @property
    def stick_share_right_face(self) -> float | None:
        return self._summary_value("stick_share_right_face")

    @property
    def stick_share_left_face(self) -> float | None:
        return self._summary_value("stick_share_left_face")


# ------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class SimulationResult(ContactSummary, ResultMethods):
    """A time history of the rotor from its static equilibrium (or from rest), as ``ringcontact simulate``.

    ``duration_revs`` the revolutions integrated; ``t_s`` (N,) sample times (s); ``displacement_m`` (N, c) the channels ``channels`` (``<station>.y|z``, m);
    ``r1_m``, ``r2_m`` the ring edges' offsets from the support's centre (m); ``contact_force_N`` (N,) the radial
    force magnitude on the bearing ring (N), ``contact_force_y_N``, ``contact_force_z_N``, ``contact_moment_Nm``;
    ``face_right_stuck``, ``face_left_stuck`` (1 stuck); the summary fields over the record (peak, shares);
    ``steady_state`` None, or with ``steady=True`` what the detector found (see :func:`simulate`);
    ``law_validity`` the run's validity record, the ``law_validity`` of ``simulate``'s summary
    (:mod:`rotor.model.law_validity`: law, file, sha256, verdict, fitted ranges, contact-time shares below,
    inside and above the fitted penetrations, the largest tilt; empty without a loose support); ``start`` how the
    run started, the summary's ``start`` (:func:`rotor.dynamics.static_start.start_record`).
    """

    scene: str
    speed_rpm: float
    duration_revs: float
    steps_per_rev: int
    dt_s: float
    channels: tuple
    t_s: np.ndarray
    displacement_m: np.ndarray
    r1_m: np.ndarray
    r2_m: np.ndarray
    contact_force_N: np.ndarray
    contact_force_y_N: np.ndarray
    contact_force_z_N: np.ndarray
    contact_moment_Nm: np.ndarray
    face_right_stuck: np.ndarray
    face_left_stuck: np.ndarray
    clearance_m: float | None
    contact: dict
    law_validity: dict
    start: dict
    steady_state: dict | None = None
    trajectory: object = internal()
    _dim = "time"

    def _rows(self) -> list[dict]:
        rows = []
        for i, t in enumerate(self.t_s):
            row = {"t_s": t, **{f"{c}_m": self.displacement_m[i, k] for k, c in enumerate(self.channels)}}
            row.update(r1_m=self.r1_m[i], r2_m=self.r2_m[i], contact_force_N=self.contact_force_N[i],
                       contact_moment_Nm=self.contact_moment_Nm[i], face_right_stuck=self.face_right_stuck[i],
                       face_left_stuck=self.face_left_stuck[i])
            rows.append(row)
        return rows

    def _draw(self, ax) -> None:
        ax.plot(self.t_s, self.contact_force_N, lw=1.0)
        ax.set_xlabel("time t (s)")
        ax.set_ylabel("radial contact force on the bearing ring (N)")
        ax.set_title(f"{self.scene} at {self.speed_rpm:g} rpm: peak {self.peak_contact_force_N or 0:.4g} N, "
                     f"contact {100 * (self.contact_share or 0):.0f} % of the time", fontsize=10)


def simulate(scene, speed_rpm: float, *, revolutions: float = 20.0, steps_per_rev: int | None = None,
             record_per_rev: int = 64, stations=None, clearance_m: float | None = None,
             misalignment_m: float | None = None, mu: float | None = None, preload_n: float | None = None,
             tilt_ignored: bool = False, elements: int | None = None, steady: bool = False,
             max_revs: int = 8000, accept_long: bool = False, allow_flagged_law: bool = False,
             from_rest: bool = False) -> SimulationResult:
    """Integrate ``revolutions`` revolutions at ``speed_rpm`` (rpm) as ``ringcontact simulate``: from the static
    equilibrium under the scene's gravity, static loads, misalignment and preload with the ring's contact and the
    end faces' friction (:func:`rotor.dynamics.static_start.static_equilibrium`), or with ``from_rest`` from rest at the
    misalignment offset (``--from-rest``).

    ``steps_per_rev`` None: chosen as ``simulate`` and ``orbit`` choose it (256 or more where the contact step
    limit needs it, a multiple of ``record_per_rev``; :func:`rotor.studies.steady_state.step_per_rev`).
    ``stations``: recorded stations (default the scene's disks, loose-support bearing and supports).
    ``steady`` True: as ``simulate --steady``: the transient is integrated until the Poincaré detector of
    :func:`rotor.studies.steady_state.steady_state` finds a period (at most ``max_revs`` revolutions) and
    discarded; the result holds ``revolutions`` revolutions after it, rounded up to whole periods
    (:func:`rotor.studies.steady_record.record_after_steady`), and ``steady_state`` says whether a period was
    found (``converged``, ``period_revs``, ``transient_revs``, ``poincare_change``). A record that is not periodic
    is returned with ``converged`` False, not refused.

    Every argument is checked with the range of the job's option (``revolutions`` as ``--revolutions`` …), and
    the run's steps and records against the job's budget: beyond it refused unless ``accept_long``. A law its
    file flags is refused unless ``allow_flagged_law`` (``--allow-flagged-law``).
    """
    from rotor.dynamics.constraints import edge_offsets
    from rotor.dynamics.production import simulate_production
    from rotor.dynamics.support_record import contact_columns, contact_summary
    from rotor.model.law_validity import record
    from contact.errors import InputError
    from rotor.dynamics.constraints import STICK
    from rotor.dynamics.static_start import start_record, static_equilibrium
    from rotor.studies.steady_state import SAMPLES_FOR_5X, SteadyStateOptions, point_system, step_per_rev

    speed_rpm = _speed("speed_rpm", speed_rpm)
    revolutions = _checks.number("revolutions", revolutions, "--revolutions", "revolutions", si_unit="rev")
    record_per_rev = _checks.whole("record_per_rev", record_per_rev, "--record-per-rev", "record_per_rev")
    if steps_per_rev is not None:
        steps_per_rev = _checks.whole("steps_per_rev", steps_per_rev, "--steps-per-rev", "steps_per_rev")
    steady = _checks.flag_of("steady", steady)
    if _checks.flag_of("from_rest", from_rest) and steady:
        raise InputError("from_rest = True: steady = True starts from the static equilibrium with its forced response, "
                         "not from rest; give one of them")
    if steady:
        max_revs = _checks.whole("max_revs", max_revs, "--max-revs", "max_revs")
    sc = _law_allowed(as_scene(scene), allow_flagged_law)
    sc, model, system = point_system(sc, speed_rpm, **_overrides(
        clearance_m, misalignment_m, mu, preload_n, tilt_ignored, elements))
    if steps_per_rev is None:      # a multiple of record_per_rev; the detector's transient sampling too
        fives = SteadyStateOptions(samples_per_rev=int(record_per_rev)) if record_per_rev >= SAMPLES_FOR_5X else \
            SteadyStateOptions()
        steps_per_rev = math.ceil(step_per_rev(system, fives) / record_per_rev) * int(record_per_rev)
    n = int(steps_per_rev)
    if record_per_rev > n:
        raise InputError(f"record_per_rev = {record_per_rev}: must be <= steps_per_rev = {n} (a sample a step at most)")
    _simulate_budget(revolutions, n, record_per_rev, max_revs if steady else 0, model.n_dofs, accept_long)
    names = [f"{s}.{c}" for s in (stations or model.response_stations(primary_only=True)) for c in ("y", "z")]
    idx = [model.dof_index(x) for x in names]
    dt = 2 * math.pi / (system.omega_rad_s * n)
    steady_info = None
    if steady:
        tr, dt, n, revolutions, steady_info = _steady_simulate(system, model, n, revolutions, record_per_rev, max_revs)
        start = steady_info.pop("start")
    else:
        eq = None if from_rest else static_equilibrium(system)
        start = start_record(system, eq)
        tr = simulate_production(system, dt, max(1, int(round(revolutions * n))),
                                 q0=system.offset if eq is None else eq.q_m, modes0=(STICK, STICK) if eq is None else eq.modes,
                                 record_every=max(1, n // int(record_per_rev)))
    sup = system.support
    r1, r2 = edge_offsets(tr.u, sup.width_m) if sup is not None else (np.zeros(len(tr.t)),) * 2
    cols = contact_columns(tr.f_contact, tr.face_force, tr.modes)
    summary = contact_summary(tr.t, tr.f_contact, tr.modes, tr.face_force, sup.faces()[2]) if sup is not None else {}
    return SimulationResult(
        sc.name, float(speed_rpm), float(revolutions), n, dt, tuple(names), tr.t, tr.q[:, idx], r1, r2,
        cols["contact_force_N"], cols["contact_force_y_N"], cols["contact_force_z_N"], cols["contact_moment_Nm"],
        cols["face_right_stuck"], cols["face_left_stuck"], sup.law.clearance_m if sup is not None else None,
        summary, record(sc.loose_support, np.maximum(r1, r2) - sup.law.clearance_m if sup is not None else r1,
                        np.hypot(tr.u[:, 2], tr.u[:, 3])), start, steady_info, tr)


def _steady_simulate(system, model, n: int, revolutions: float, record_per_rev: int, max_revs: int):
    """``simulate(steady=True)``: the transient from :func:`rotor.dynamics.static_start.periodic_start` until the
    Poincaré detector finds a period, then whole periods; ``(trajectory, dt, steps per revolution, kept revolutions,
    steady_state)``."""
    from contact.errors import InputError
    from rotor.dynamics.static_start import periodic_start
    from rotor.studies.steady_record import record_after_steady
    from rotor.studies.steady_state import SAMPLES_FOR_5X, SteadyStateOptions, steady_state

    if n % int(record_per_rev) or int(record_per_rev) < SAMPLES_FOR_5X or int(round(revolutions)) < 1:
        raise InputError(f"simulate: steady = True needs revolutions >= 1 (got {revolutions:g} rev) and "
                         f"record_per_rev >= {SAMPLES_FOR_5X} dividing steps_per_rev {n} (got {record_per_rev})")
    opts = SteadyStateOptions(steps_per_rev=n, samples_per_rev=int(record_per_rev), spectrum_revs=1,
                              max_revs=int(max_revs))
    q_start, v_start, start = periodic_start(system, model, 0.0)
    ss = steady_state(system, model, options=opts, q0=q_start, v0=v_start)
    tr, dt, _, kept = record_after_steady(system, ss, int(round(revolutions)), int(record_per_rev))
    conv = ss.convergence
    info = {"converged": bool(conv.converged), "period_revs": int(conv.period),
            "transient_revs": int(ss.transient_revs + ss.revolutions), "poincare_change": float(conv.change),
            "start": start}
    return tr, dt, ss.steps_per_rev, kept, info


def _simulate_budget(revolutions: float, n: int, record_per_rev: int, transient_revs: int, n_dofs: int,
                     accept_long) -> None:
    """The run's steps and records against the budget of ``simulate`` (:func:`reports.cli._budget.stepping`)."""
    from reports.cli import _budget
    steps = revolutions * n + transient_revs * n
    est = _budget.stepping(steps, revolutions * record_per_rev + 1, n_dofs)
    _checks.budget("simulate", est, accept_long, f"revolutions = {revolutions:g} rev at steps_per_rev {n} and "
                   f"record_per_rev {record_per_rev}", "fewer revolutions or records")


# ------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class OrbitResult(ContactSummary, ResultMethods):
    """The periodic orbit at one speed, as ``ringcontact orbit``: period, convergence, Floquet multipliers and
    stability, 1X-5X velocity amplitudes ``velocity_amplitude_m_s[c, k]`` of channel ``channels[c]`` at order
    k + 1 (m/s), and the loose support over one period (``contact``: the keys of ``simulate``'s summary).
    ``unique`` False: the orbit is one member of a family held by friction (multipliers at +1 from a face stuck
    through the period; another start may settle on another member), as the CLI's "not unique" line says.
    ``law_validity``: the validity record over the period (:mod:`rotor.model.law_validity`, the JSON
    ``law_validity`` of ``ringcontact orbit``)."""

    scene: str
    speed_rpm: float
    period_revs: int
    period_s: float
    steps_per_rev: int
    converged: bool
    residual: float
    newton_iterations: int
    stable: bool
    spectral_radius: float
    critical_kind: str
    multipliers: np.ndarray
    channels: tuple
    velocity_amplitude_m_s: np.ndarray
    max_edge_penetration_m: float
    contact: dict
    law_validity: dict
    unique: bool
    orbit: object = internal()
    _dim = "channel"

    def _rows(self) -> list[dict]:
        return [{"channel": c, **{f"velocity_{k + 1}X_m_s": self.velocity_amplitude_m_s[i, k] for k in range(5)}}
                for i, c in enumerate(self.channels)]

    def _draw(self, ax) -> None:
        phi = np.linspace(0, 2 * math.pi, 361)
        ax.plot(np.cos(phi), np.sin(phi), color="0.5", lw=0.8)
        ax.plot(self.multipliers.real, self.multipliers.imag, "x", color="tab:red")
        ax.set_aspect("equal")
        ax.set_xlabel("Re μ (–)")
        ax.set_ylabel("Im μ (–)")
        ax.set_title(f"Floquet multipliers at {self.speed_rpm:g} rpm: {'stable' if self.stable else 'unstable'}, "
                     f"peak contact force {self.peak_contact_force_N or 0:.4g} N", fontsize=10)


def _orbit_result(name: str, res) -> OrbitResult:
    amps = res.velocity_amplitudes_mm_s_1X_to_5X
    return OrbitResult(name, res.speed_rpm, res.period_revs, res.period_s, res.steps_per_rev, bool(res.converged),
                       float(res.residual), int(res.newton_iterations), bool(res.stable),
                       float(res.floquet.spectral_radius), res.floquet.kind, np.asarray(res.floquet.multipliers),
                       tuple(amps), np.array([[a * 1e-3 for a in v] for v in amps.values()]),
                       float(res.max_edge_penetration_m), {k: v for k, v in res.contact.items() if k != "law_validity"},
                       dict(res.contact.get("law_validity") or {}), bool(res.unique), res)


def orbit(scene, speed_rpm: float, *, period_revs: int | None = None, steps_per_rev: int | None = None,
          clearance_m: float | None = None, misalignment_m: float | None = None, mu: float | None = None,
          preload_n: float | None = None, tilt_ignored: bool = False, elements: int | None = None,
          accept_long: bool = False, allow_flagged_law: bool = False) -> OrbitResult:
    """The periodic orbit at ``speed_rpm`` (rpm) by shooting, its stability and harmonics
    (:func:`rotor.studies.orbit.orbit`); ``converged`` False when no orbit of 1 to 8 revolutions was found.
    Arguments are checked with the ranges of ``ringcontact orbit``'s options, the work against its budget
    (beyond it refused unless ``accept_long``); a law its file flags refused unless ``allow_flagged_law``."""
    from rotor.studies.orbit import orbit as shoot
    speed_rpm = _speed("speed_rpm", speed_rpm)
    if period_revs is not None:
        period_revs = _checks.whole("period_revs", period_revs, "--period-revs", "period_revs")
    if steps_per_rev is not None:
        steps_per_rev = _checks.whole("steps_per_rev", steps_per_rev, "--steps-per-rev", "steps_per_rev")
    ov = _overrides(clearance_m, misalignment_m, mu, preload_n, tilt_ignored, elements)
    sc = _law_allowed(as_scene(scene), allow_flagged_law)
    _orbit_budget("orbit", sc, speed_rpm, ov, steps_per_rev, period_revs, 0, accept_long)
    res = shoot(sc, speed_rpm, steps_per_rev=steps_per_rev, period_revs=period_revs, **ov)
    return _orbit_result(sc.name, res)


# ------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class BranchResult(ResultMethods):
    """Orbits followed over speed (pseudo-arclength continuation), as ``ringcontact branch``: per point the speed,
    stability, spectral radius and the contact summary, ``unique`` (False: one member of a family held by friction,
    :class:`OrbitResult`); ``bifurcations`` (kind, speed_rpm); ``stop`` why it ended (``end reached`` when it got
    to ``rpm_end``); ``law_validity`` the validity record over every orbit of the branch
    (:func:`rotor.model.law_validity.merged`)."""

    scene: str
    rpm_start: float
    rpm_end: float
    speeds_rpm: np.ndarray
    stable: np.ndarray
    spectral_radius: np.ndarray
    peak_contact_force_N: np.ndarray
    contact_share: np.ndarray
    stick_share_right_face: np.ndarray
    stick_share_left_face: np.ndarray
    unique: np.ndarray
    bifurcations: tuple
    stop: str
    reached_end: bool
    law_validity: dict
    start: OrbitResult = internal()
    branch: object = internal()
    _dim = "point"

    def _rows(self) -> list[dict]:
        return [{"speed_rpm": s, "stable": bool(self.stable[i]), "spectral_radius": self.spectral_radius[i],
                 "peak_contact_force_N": self.peak_contact_force_N[i], "contact_share": self.contact_share[i],
                 "stick_share_right_face": self.stick_share_right_face[i],
                 "stick_share_left_face": self.stick_share_left_face[i], "unique": bool(self.unique[i])}
                for i, s in enumerate(self.speeds_rpm)]

    def _draw(self, ax) -> None:
        stable = self.stable.astype(bool)
        ax.plot(self.speeds_rpm, self.peak_contact_force_N, color="0.6", lw=0.8)
        ax.plot(self.speeds_rpm[stable], self.peak_contact_force_N[stable], "o", ms=3, label="stable")
        ax.plot(self.speeds_rpm[~stable], self.peak_contact_force_N[~stable], "o", ms=3, mfc="none", label="unstable")
        for b in self.bifurcations:
            ax.axvline(b["speed_rpm"], color="tab:red", lw=0.8, ls=":")
        ax.set_xlabel("rotor speed (rpm)")
        ax.set_ylabel("peak radial contact force (N)")
        ax.set_title(f"Branch of {self.scene}: {self.stop}", fontsize=10)
        ax.legend(fontsize=8)


@dataclass(frozen=True)
class _PointTask:
    """A cascade speed as the budget reads a study's sweep task (:func:`reports.cli._budget.steady_points`)."""

    params: dict
    outputs: tuple = ()

    @property
    def points(self) -> tuple:
        return (("", self.params),)


def _column(points, key: str) -> np.ndarray:
    return np.array([np.nan if p.get(key) is None else float(p[key]) for p in points])


def branch(scene, rpm_start: float, rpm_end: float, *, max_points: int = 400, steps_per_rev: int | None = None,
           clearance_m: float | None = None, misalignment_m: float | None = None, mu: float | None = None,
           preload_n: float | None = None, tilt_ignored: bool = False, elements: int | None = None,
           accept_long: bool = False, allow_flagged_law: bool = False) -> BranchResult:
    """Follow the orbit found at ``rpm_start`` to ``rpm_end`` (rpm) (:func:`rotor.studies.orbit.branch`), at most
    ``max_points`` orbits; arguments and work checked as ``ringcontact branch`` checks them (``accept_long``,
    ``allow_flagged_law``)."""
    from contact.errors import InputError
    from rotor.periodic.continuation import ContinuationOptions
    from rotor.model.law_validity import merged
    from rotor.studies.orbit import branch as follow
    rpm_start, rpm_end = _speed("rpm_start", rpm_start, "--rpm-start"), _speed("rpm_end", rpm_end, "--rpm-end")
    if rpm_start == rpm_end:
        raise InputError(f"rpm_end = {rpm_end:g} rpm: must differ from rpm_start = {rpm_start:g} rpm (a branch "
                         "follows the orbit over a range of speeds)")
    max_points = _checks.whole("max_points", max_points, "--max-points", "max_points")
    if steps_per_rev is not None:
        steps_per_rev = _checks.whole("steps_per_rev", steps_per_rev, "--steps-per-rev", "steps_per_rev")
    ov = _overrides(clearance_m, misalignment_m, mu, preload_n, tilt_ignored, elements)
    sc = _law_allowed(as_scene(scene), allow_flagged_law)
    _orbit_budget("branch", sc, rpm_start, ov, steps_per_rev, None, max_points, accept_long)
    res = follow(sc, rpm_start, rpm_end, steps_per_rev=steps_per_rev, options=ContinuationOptions(
        max_points=max_points), **ov)
    pts = res.points
    return BranchResult(sc.name, float(rpm_start), float(rpm_end), _column(pts, "speed_rpm"),
                        np.array([bool(p["stable"]) for p in pts], dtype=bool), _column(pts, "spectral_radius"),
                        _column(pts, "peak_contact_force_N"), _column(pts, "contact_share"),
                        _column(pts, "stick_share_right_face"), _column(pts, "stick_share_left_face"),
                        np.array([bool(p.get("unique", True)) for p in pts], dtype=bool), tuple(res.bifurcations), res.stop, res.stop == "end reached",
                        merged([p.get("law_validity") for p in pts] + [res.start.contact.get("law_validity")]),
                        _orbit_result(sc.name, res.start), res)


# ------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CascadeResult(ResultMethods):
    """Steady state at each speed, as ``ringcontact study cascade`` (one point each, in order, one process):
    ``velocity_amplitude_m_s[i, k, c]`` order k + 1 of channel ``channels[c]`` at ``speeds_rpm[i]`` (m/s),
    ``converged[i]`` whether the Poincaré test found a periodic steady state within ``max_revs``, and the
    contact summary per speed; ``law_validity`` the validity record over the recorded revolutions of every speed
    (:func:`rotor.model.law_validity.merged`)."""

    scene: str
    speeds_rpm: np.ndarray
    channels: tuple
    velocity_amplitude_m_s: np.ndarray
    displacement_amplitude_m: np.ndarray
    converged: np.ndarray
    period_revs: np.ndarray
    transient_revs: np.ndarray
    regime: tuple
    peak_contact_force_N: np.ndarray
    contact_share: np.ndarray
    stick_share_right_face: np.ndarray
    stick_share_left_face: np.ndarray
    law_validity: dict
    points: tuple = internal()
    _dim = "speed"

    def _rows(self) -> list[dict]:
        rows = []
        for i, s in enumerate(self.speeds_rpm):
            row = {"speed_rpm": s, "converged": bool(self.converged[i]), "period_revs": int(self.period_revs[i]),
                   "regime": self.regime[i], "peak_contact_force_N": self.peak_contact_force_N[i],
                   "contact_share": self.contact_share[i], "stick_share_right_face": self.stick_share_right_face[i],
                   "stick_share_left_face": self.stick_share_left_face[i]}
            for c, ch in enumerate(self.channels):
                row[f"{ch}_velocity_1X_to_5X_m_s"] = list(self.velocity_amplitude_m_s[i, :, c])
            rows.append(row)
        return rows

    def to_xarray(self):
        """An ``xarray.Dataset`` with dimensions ``speed_rpm``, ``order`` (1-5) and ``channel``: the amplitudes
        (``velocity_amplitude_m_s``, ``displacement_amplitude_m``) and, along speed, convergence and contact."""
        from sweep.export import attr, xarray
        xr = xarray()
        dims = ("speed_rpm", "order", "channel")
        data = {"velocity_amplitude_m_s": (dims, self.velocity_amplitude_m_s, {"units": "m/s"}),
                "displacement_amplitude_m": (dims, self.displacement_amplitude_m, {"units": "m"})}
        for name in ("converged", "period_revs", "transient_revs", "peak_contact_force_N", "contact_share",
                     "stick_share_right_face", "stick_share_left_face"):
            data[name] = (("speed_rpm",), np.asarray(getattr(self, name)))
        data["regime"] = (("speed_rpm",), np.array(self.regime, dtype=str))
        coords = {"speed_rpm": self.speeds_rpm, "order": np.arange(1, self.velocity_amplitude_m_s.shape[1] + 1),
                  "channel": list(self.channels)}
        return xr.Dataset(data, coords=coords, attrs={"result": type(self).__name__, "scene": attr(self.scene),
                                                      **law_validity_attrs(self)})

    def _draw(self, ax) -> None:
        ch = self.channels[0]
        for k in range(self.velocity_amplitude_m_s.shape[1]):
            ax.semilogy(self.speeds_rpm, self.velocity_amplitude_m_s[:, k, 0] * 1e3, "-o", ms=3, label=f"{k + 1}X")
        bad = ~self.converged.astype(bool)
        if bad.any():
            ax.plot(self.speeds_rpm[bad], self.velocity_amplitude_m_s[bad, 0, 0] * 1e3, "x", color="k", ms=8,
                    label="not converged")
        ax.set_xlabel("rotor speed (rpm)")
        ax.set_ylabel(f"velocity amplitude of {ch} (mm/s)")
        ax.set_title(f"Steady-state cascade: {self.scene}", fontsize=10)
        ax.legend(fontsize=8)


def cascade(scene, rpms, *, max_revs: int = 1500, steps_per_rev: int = 256, clearance_m: float | None = None,
            misalignment_m: float | None = None, mu: float | None = None, preload_n: float | None = None,
            tilt_ignored: bool = False, elements: int | None = None, accept_long: bool = False,
            allow_flagged_law: bool = False) -> CascadeResult:
    """The steady state at each speed of ``rpms`` (rpm, > 0) by integration (transient detected and discarded,
    :func:`rotor.studies.steady_state.run_point`, at most ``max_revs`` revolutions of transient a speed).
    Arguments are checked as ``study cascade`` checks its options (1 to 2000 speeds …), the work against its
    budget (beyond it refused unless ``accept_long``); a law its file flags refused unless ``allow_flagged_law``."""
    from reports.cli import _budget
    from rotor.model.law_validity import merged, stored_point_record
    from rotor.studies.steady_state import run_point
    speeds = _checks.speed_list("rpms", rpms, "--rpm-max", "run_speed_rpm", "study_speeds")
    options = {"max_revs": _checks.whole("max_revs", max_revs, "--max-revs", "max_revs"),
               "steps_per_rev": _checks.whole("steps_per_rev", steps_per_rev, "--steps-per-rev", "steps_per_rev")}
    ov = _overrides(clearance_m, misalignment_m, mu, preload_n, tilt_ignored, elements)
    sc = _law_allowed(as_scene(scene), allow_flagged_law)
    tasks = [_PointTask({"scene": sc, "speed_rpm": float(s), "options": options, **ov}) for s in speeds]
    _checks.budget("cascade", _budget.steady_points(tasks), accept_long,
                   f"{len(speeds)} speeds of at most max_revs = {options['max_revs']} revolutions",
                   "fewer speeds or max_revs")
    pts = [run_point(sc, float(s), options=options, **ov) for s in speeds]
    infos = [p[1] for p in pts]
    return CascadeResult(sc.name, speeds, tuple(str(c) for c in pts[0][0]["channels"]),
                         np.array([np.abs(a["harm_v"]) for a, _ in pts]), np.array([np.abs(a["harm_q"]) for a, _ in pts]),
                         np.array([i["converged"] for i in infos], dtype=bool),
                         np.array([i["period_revs"] for i in infos]), np.array([i["transient_revs"] for i in infos]),
                         tuple(i["label"] for i in infos), _column(infos, "peak_contact_force_N"),
                         _column(infos, "contact_share"), _column(infos, "stick_share_right_face"),
                         _column(infos, "stick_share_left_face"),
                         merged(stored_point_record(sc.loose_support, a, i["clearance_m"]) for a, i in pts), tuple(pts))
