"""Long work announced before it starts, and refused above a stated budget unless ``--accept-long``.

Every job that can start hours of stepping or fill the memory (``simulate``, ``orbit``, ``branch``, ``study
cascade``/``params``/``map``/``point``/``testrig``/``runup``, ``rotor campbell``, ``rotor response``) estimates
its work from its step (or eigenvalue) count times a per-step cost measured on this suite's own runs (each
constant below names where it was measured), before anything is computed, and calls :func:`check`:

* above :data:`WORK_BUDGET_S` of computing or :data:`MEMORY_BUDGET_BYTES` of records: refused (exit status 2)
  with the estimate, what it is made of, and the flag that accepts it (``--accept-long``);
* above :data:`ANNOUNCE_S`: one line on stderr with the estimate, then the work starts.

The estimates are upper bounds where the work has one (a steady-state point integrates at most ``--max-revs``
revolutions; most stop far earlier), typical values otherwise (said in the message). ``orbit`` and ``branch``
say both: "about X (at most Y: …)". Their step costs are measured on the system itself by a short probe
(:func:`map_cost`: a revolution of the period map without and a share of one with its monodromy, after the
compile, which is reported separately), a branch's orbit count follows the continuation's step control over
the branch's predicted path (:func:`branch_orbits` over :func:`reports.cli._branch_path.branch_path`: its scaled
arclength, and where it grazes and follows a contact branch), and the bound counts the whole
transient and ``--max-points`` orbits. They are refused on the typical value, or on the bound where it exceeds
:data:`BOUND_REFUSAL` budgets: a bound counts work a smooth run never does (400 orbits where 25 cover a
smooth branch; 2 000 transient revolutions where 24 usually do), so refusing on it refused 13-s branches, while a
typical value cannot see restarts, so a bound of many hours is still refused. Measured against wall times in
reports/published/perf-estimates.md (benchmarks/bench_estimates.py).
"""
from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass

from contact.errors import InputError

#: what a job may cost without ``--accept-long``: half an hour of computing, 2 GiB of records
WORK_BUDGET_S = 1800.0
MEMORY_BUDGET_BYTES = 2 * 2 ** 30
#: work estimated beyond this is announced on stderr before it starts
ANNOUNCE_S = 60.0

# Measured per-step costs (wall seconds per time step or per eigenproblem; shared 2-core machine).
#: production Newmark step of the Table 4 rotor (28 DOFs): one revolution of 256 steps in 1.08 ms,
#: reports/published/perf-period-map.md
STEP_COST_S = 1.08e-3 / 256
#: a step of the steady-state detector (rotor.studies.steady_state.run_point: stepping, Poincaré samples,
#: every step recorded for the spectrum): 7.5-23 µs measured on paper-table4 at 18, 300 and 3000 rpm
#: (load average 5.3, 2026-11-27); the bound takes the slowest
STEADY_STEP_COST_S = 23e-6
#: bytes held per step of a recorded steady-state revolution (q_all, v, a, u … of every DOF): 3.5 GB peak
#: for 32 recorded revolutions of 73 792 steps on paper-table4 (28 DOFs) at 18 rpm, 2026-11-27
STEADY_BYTES_PER_STEP_DOF = 56
#: a step of the run-up ramp (segments of constant speed, each prepared anew): 1 536 340 steps of 13.0 µs,
#: reports/published/study-runup.md
RUNUP_STEP_COST_S = 13.0e-6
#: one speed of a Campbell diagram (the dense eigenproblem of a rotor model of n DOFs, state space 2n, and its
#: whirl sorting): 125 s at n = 1036 (paper-table4 with 64 elements a segment), 2.6 ms at n = 28, 3.7 s at
#: n = 268; scaled with n^3, which joins both ends (rotor.linear.modes.campbell, 2026-11-27, load average 9)
EIG_COST_S = 125.0
EIG_COST_DOFS = 1036


@dataclass(frozen=True)
class Estimate:
    """What a job will cost: ``seconds`` of computing, ``nbytes`` held in memory, ``made_of`` (words: the
    step count and the cost per step), ``bound`` (True: an upper bound, False: typical); ``upper_s``: with a
    typical ``seconds``, the bound where the work has one (said in words; ``upper_of``: what it is the cost of)."""

    seconds: float
    nbytes: float
    made_of: str
    bound: bool = True
    upper_s: float | None = None
    upper_of: str = ""


class WorkBudgetError(InputError):
    """Work estimated beyond the budget, refused before it starts (accepted with ``--accept-long``)."""


def add_accept_long(parser: argparse.ArgumentParser) -> None:
    """The ``--accept-long`` flag, the same for every job."""
    parser.add_argument("--accept-long", action="store_true",
                        help=f"run even when the estimate exceeds the budget ({WORK_BUDGET_S / 60:g} min of "
                             f"computing or {MEMORY_BUDGET_BYTES / 2 ** 30:g} GiB of records)")


def _time(seconds: float) -> str:
    if seconds >= 5400:
        return f"{seconds / 3600:.3g} h"
    return f"{seconds / 60:.3g} min" if seconds >= 90 else f"{seconds:.3g} s"


def describe(est: Estimate) -> str:
    """``estimated at most 2.1 h of computing and 3.2 GiB of records (…)``; with a typical value and its bound:
    ``estimated about 12 s (at most 9.1 min: 400 orbits …) of computing …``."""
    if est.upper_s is not None:
        what = f"about {_time(est.seconds)} (at most {_time(est.upper_s)}: {est.upper_of})"
    else:
        what = f"{'at most ' if est.bound else ''}{_time(est.seconds)}"
    return f"estimated {what} of computing and {est.nbytes / 2 ** 30:.3g} GiB of records ({est.made_of})"


def _over(est: Estimate) -> str:
    """Why ``est`` is beyond the budget ('' if it is not): its value (typical or bound), its records, or a bound
    beyond :data:`BOUND_REFUSAL` budgets (a typical value far below a bound is not trusted that far)."""
    if est.seconds > WORK_BUDGET_S or est.nbytes > MEMORY_BUDGET_BYTES:
        return f"beyond the budget of {WORK_BUDGET_S / 60:g} min and {MEMORY_BUDGET_BYTES / 2 ** 30:g} GiB"
    if est.upper_s is not None and est.upper_s > BOUND_REFUSAL * WORK_BUDGET_S:
        return (f"its bound beyond the budget of {WORK_BUDGET_S / 60:g} min {BOUND_REFUSAL:g} times over "
                f"({_time(BOUND_REFUSAL * WORK_BUDGET_S)})")
    return ""


def check(prog: str, est: Estimate, accept_long: bool, cause: str, remedy: str, *,
          override: str = "--accept-long") -> None:
    """Refuse ``est`` beyond the budget (unless ``accept_long``), announce it beyond :data:`ANNOUNCE_S`.

    ``cause``: the options the user typed that make the work (``--steps-per-rev = 100000``), ``remedy``: what
    to change instead (``fewer steps per revolution``), ``override``: how the caller accepts it (the flag, or
    the API's keyword ``accept_long=True``). Raises :class:`WorkBudgetError`.
    """
    over = _over(est)
    if over and not accept_long:
        raise WorkBudgetError(f"{cause}: {describe(est)}, {over}; {remedy}, or {override} to run it anyway")
    if est.seconds >= ANNOUNCE_S or over:
        print(f"{prog}: {describe(est)}; starting", file=sys.stderr, flush=True)


def _steps(n: float) -> str:
    return f"{n:.3g} steps"


def steady_points(tasks, workers: int = 1) -> Estimate:
    """The steady-state points of a study's sweep tasks (:func:`rotor.studies.steady_state.run_point`): each
    integrates at most ``max_revs`` + ``spectrum_revs`` revolutions at the steps per revolution it will use
    (:func:`rotor.studies.steady_state.step_per_rev`: more at low speed, where the contact step limit needs a
    step shorter than the revolution's share), the points shared among ``workers``, each holding one
    recorded point."""
    import dataclasses

    from rotor.studies.steady_state import SteadyStateOptions, point_system, step_per_rev
    from sweep import point_tasks

    keys = ("scene", "clearance_m", "misalignment_m", "tilt_ignored", "mu", "preload_n", "elements_per_segment")
    systems: dict = {}
    steps, peak, n_points = 0.0, 0.0, 0
    for t in point_tasks(tasks):
        p = dict(t.params)
        speed = float(p.get("speed_rpm", 0.0))
        if speed <= 0:
            continue                       # at rest: the static state, no stepping
        opts = SteadyStateOptions(**(p.get("options") or {}))
        kw = {k: p[k] for k in keys if k in p and p[k] is not None}
        group = repr(sorted(kw.items()))
        if group not in systems:           # the step limit does not depend on the speed: one system per group
            systems[group] = point_system(kw.pop("scene"), speed, **kw)[2]
        system = dataclasses.replace(systems[group], omega_rad_s=speed * 3.141592653589793 / 30)
        n = step_per_rev(system, opts)
        steps += (opts.max_revs + opts.spectrum_revs) * n
        peak = max(peak, opts.spectrum_revs * n * system.n * STEADY_BYTES_PER_STEP_DOF)
        n_points += 1
    w = max(1, min(int(workers), n_points))
    return Estimate(steps * STEADY_STEP_COST_S / w, peak * w,
                    f"{n_points} points, at most {_steps(steps)} of {STEADY_STEP_COST_S * 1e6:.3g} µs on {w} "
                    f"worker(s)")


def runup(spec) -> Estimate:
    """The run-up ramp of :func:`rotor.studies.runup.simulate_runup`: its step (the revolution's share at the
    top speed or half the contact step limit) over the duration, and its records (``sample_rate_hz``)."""
    import math

    from rotor.dynamics.system import largest_stable_step
    from rotor.studies.steady_state import point_system

    top = max(spec.rpm_start, spec.rpm_end)
    _, model, system = point_system(spec.scene, top, clearance_m=spec.clearance_m,
                                    misalignment_m=spec.misalignment_m, tilt_ignored=spec.tilt_ignored)
    dt = min(60.0 / top / spec.steps_per_rev, 0.5 * largest_stable_step(system)[0])
    steps = spec.duration_s / dt
    records = spec.duration_s * min(spec.sample_rate_hz, 1.0 / dt)
    per_record = (2 + 4 * len(model.response_stations()) + 14) * 8 * 2     # collected, then joined
    return Estimate(steps * RUNUP_STEP_COST_S, records * per_record,
                    f"{_steps(steps)} of {RUNUP_STEP_COST_S * 1e6:.3g} µs, {records:.3g} records", bound=False)


#: corrector iterations of a smooth branch's orbit: 3 (Friswell 5.9.1 loose aluminium 2 300 -> 2 800 rpm, 81 maps
#: with monodromy for 27 orbits) to 4.9 (a Jeffcott-ring branch through two grazings, 214 for 44), 2026-11-28
BRANCH_ITERATIONS = 3
#: corrector iterations of an orbit on a contact stretch between two grazings (the same Jeffcott-ring branch: 214
#: maps with monodromy for 44 orbits), and the map costs there are the contact branch's (:func:`orbit`)
GRAZING_ITERATIONS = 4.9
#: scaled arclength of a contact stretch between grazings over its predicted one (:mod:`reports.cli._branch_path`):
#: the contact branch folds (up, back along the unstable middle branch, on again), which the linear path cannot see
CONTACT_PATH_FACTOR = 2.0
#: a grazing crossing (:func:`rotor.periodic.grazing._cross`: the grazing orbit on the penetration's level sets
#: and the first orbit past it) in orbits of the contact stretch
CROSSING_ORBITS = 6.0
#: a first orbit (:func:`rotor.periodic.shooting.shoot_from_transient`): the first transient round, and Newton
#: iterations with monodromy on the period (typical: the first round's Newton converges)
ORBIT_ITERATIONS = 3
#: the estimate refuses on its typical value; on its bound only when the bound is this many budgets
BOUND_REFUSAL = 4.0
#: most steps the probe maps (a share of the revolution where it has more: the cost per step from them)
PROBE_JAC_STEPS = 8192
#: seconds the probe may spend on steps with the monodromy (16 steps at least)
PROBE_JAC_S = 0.5
#: seconds the probe may spend settling without the monodromy (up to the first transient round of
#: ``ShootingOptions.transient_revs``) before its steps with it: the orbit's located events (contact onsets and
#: losses, face switches) are what make a step with the monodromy dear, and the linear start has few of them.
#: Measured on Table 4 at 7 000 rpm (256 steps a revolution): 22.6 µs a step with the monodromy after 4
#: revolutions, 1.55 ms after 24 (contact 54 % of the period, each onset and loss differenced), the orbit 2.0-3.3 s
#: against the estimate's 0.083 s
PROBE_SETTLE_S = 1.0


@dataclass(frozen=True)
class MapCost:
    """Seconds measured on the system itself (:func:`map_cost`): one step of the period map without (``plain_s``)
    and with its monodromy (``jac_s``), one system and flow built at a new speed (``build_s``), and the probe's own
    wall time (``probe_s``)."""

    plain_s: float
    jac_s: float
    build_s: float
    probe_s: float


#: the step costs of the Table 4 rotor (28 DOFs), for a first check before the compile and the system's own probe:
#: a production step (reports/published/perf-period-map.md) and a shooting step with the monodromy (orbit
#: paper-table4 at 10 500 rpm, 256 steps a revolution: 2.55 s for 249 revolutions, 2026-11-27, load 2.0)
TABLE4_COST = MapCost(plain_s=STEP_COST_S, jac_s=2.55 / (256 * 249), build_s=0.0, probe_s=0.0)


def beyond_at_table4_cost(system, steps_per_rev: int, period_revs: int | None, points: int = 0) -> Estimate | None:
    """The estimate of :func:`orbit` at :data:`TABLE4_COST` where it is already beyond the budget (None if not): a
    request such as ``--steps-per-rev 100000`` is refused at once, before the compile (up to 95 s on a first use)
    and the probe that would measure the system's own costs."""
    est = orbit(system, steps_per_rev, period_revs, points, cost=TABLE4_COST)
    return est if _over(est) else None


def map_cost(system_at, steps_per_rev: int) -> MapCost:
    """Measure the period map on the system: ``system_at()`` builds it (three times, the median counted), one
    revolution without the monodromy from the linear periodic solution (after 16 steps without and 16 with it,
    not counted: the first calls pay dispatch and buffers), then, after up to the first transient round's
    revolutions as :data:`PROBE_SETTLE_S` allows (the orbit's located events, not the linear start's), steps with
    it: as many of :data:`PROBE_JAC_STEPS` as :data:`PROBE_JAC_S` allows. Run after the compile (:func:`rotor.dynamics.period_map.warm_up`)."""
    import math
    import time

    from contact.errors import ConvergenceError, OutsideDomainError
    from rotor.dynamics.initial import linear_initial_state
    from rotor.periodic.period_flow import advance, make_flow, to_reduced
    from rotor.periodic.shooting import ShootingOptions

    t_start = time.perf_counter()
    n = int(steps_per_rev)
    builds = []
    for _ in range(3):
        t = time.perf_counter()
        system = system_at()
        dt = 2.0 * math.pi / (system.omega_rad_s * n)
        flow = make_flow(system, dt)
        builds.append(time.perf_counter() - t)
    build = sorted(builds)[1]
    x = to_reduced(flow, *linear_initial_state(system, 0.0))
    r = advance(flow, x, 0.0, 16, jacobian=False)            # first calls (dispatch, buffers): not counted
    advance(flow, r.state, 16 * dt, 16, r.modes, jacobian=True)
    k = min(n, PROBE_JAC_STEPS)
    t = time.perf_counter()
    r = advance(flow, x, 0.0, k, jacobian=False)
    plain = (time.perf_counter() - t) / k
    # the rest of the transient's first round, as far as PROBE_SETTLE_S allows: the orbit's events, not the start's
    revs = min(ShootingOptions().transient_revs - 1, int(PROBE_SETTLE_S / (plain * n))) if k == n else 0
    try:
        settled = advance(flow, r.state, k * dt, revs * n, r.modes, jacobian=False) if revs else r
        jac = _jac_step_s(flow, settled, (k + revs * n) * dt, k)
    except (OutsideDomainError, ConvergenceError):   # a transient that leaves the law (an unstable rotor grows):
        jac = _jac_step_s(flow, r, k * dt, k)         # timed at the start; the job itself says why it fails
    return MapCost(plain, jac, build, time.perf_counter() - t_start)


def _jac_step_s(flow, r, t0_s: float, k: int) -> float:
    """Seconds a step of the period map with its monodromy from ``r`` (a map's result) at ``t0_s``: 16 steps, then
    as many of the ``k`` as :data:`PROBE_JAC_S` allows (its cost per step grows with the events it meets)."""
    import time

    from rotor.periodic.period_flow import advance

    t = time.perf_counter()
    advance(flow, r.state, t0_s, 16, r.modes, jacobian=True)
    jac = (time.perf_counter() - t) / 16
    m = min(k, int(PROBE_JAC_S / jac))
    if m > 16:
        t = time.perf_counter()
        advance(flow, r.state, t0_s, m, r.modes, jacobian=True)
        jac = (time.perf_counter() - t) / m
    return jac


def branch_orbits(path: float, opts=None) -> int:
    """Orbits of a smooth branch over a scaled arclength ``path`` (the parameter's 10 speed scales and the state's
    change in its own scales): ``ds`` from ``ContinuationOptions.ds``, ×1.5 after each easy corrector up to
    ``ds_max`` (:mod:`rotor.periodic.continuation`), and one orbit landing on the end (``max_points`` at most)."""
    from rotor.periodic.continuation import ContinuationOptions

    o = opts or ContinuationOptions()
    ds, done, count = o.ds, 0.0, 1
    while done < path and count < o.max_points:
        done += ds
        ds = min(1.5 * ds, o.ds_max)
        count += 1
    return count + (1 if count < o.max_points else 0)


def orbit(system, steps_per_rev: int, period_revs: int | None, points: int = 0, *, cost: MapCost | None = None,
          path=None, contact_cost: MapCost | None = None) -> Estimate:
    """Shooting at one speed (and, with ``points`` = ``--max-points``, a branch): typically the first transient
    round (``ShootingOptions.transient_revs``) and :data:`ORBIT_ITERATIONS` Newton iterations on the period map
    with its monodromy, then the branch's orbits (:func:`_branch_work` over ``path``; 10:
    the parameter alone) of :data:`BRANCH_ITERATIONS` corrector iterations each; at most the whole transient
    (``max_transient_revs``) with every round's Newton attempts at full length, and ``points`` orbits. The step
    costs are measured on ``system`` (``cost``; :func:`map_cost` when not given)."""
    from rotor.periodic.shooting import MAX_PERIOD_REVS, ShootingOptions

    n = int(steps_per_rev)
    c = cost or map_cost(lambda: system, n)
    o = ShootingOptions()
    k = period_revs or 1
    typical = (o.transient_revs * n * c.plain_s + ORBIT_ITERATIONS * k * n * c.jac_s + k * n * c.plain_s)
    rounds, done, chunk = 0, 0, o.transient_revs
    while done < o.max_transient_revs:
        done, rounds = done + chunk, rounds + 1
        chunk = max(1, round(o.round_growth * chunk))
    tries = 1 if period_revs else o.periods_per_round
    bound = (o.max_transient_revs * n * c.plain_s
             + rounds * tries * o.max_iter * (period_revs or MAX_PERIOD_REVS) * n * c.jac_s)
    per_orbit = _per_orbit(c, BRANCH_ITERATIONS, k * n)
    made = (f"{_us(c.plain_s)} a step, {_us(c.jac_s)} with the monodromy, measured on the system"
            + (f" in {c.probe_s:.2g} s" if c.probe_s >= 0.5 else ""))
    if points:
        orbits, work, said, worst = _branch_work(path, c, contact_cost, k * n)
        typical += work
        bound += points * worst
        made = f"the first orbit and about {orbits} orbits{said}; {made}"
        limit = f"{points} orbits and the longest first orbit"
    else:
        limit = f"the first orbit after {o.max_transient_revs} transient revolutions"
    return Estimate(typical, (period_revs or MAX_PERIOD_REVS) * n * system.n * 8 * 6, made, bound=False,
                    upper_s=bound, upper_of=limit)


def _per_orbit(c: MapCost, iterations: float, steps: int) -> float:
    """Seconds of a branch's orbit of ``iterations`` corrector iterations on maps of ``steps`` steps at the costs
    ``c``: per iteration the map with its monodromy and three systems built, two maps without; two more per orbit."""
    return iterations * (steps * c.jac_s + 3 * c.build_s) + (2 * iterations + 2) * steps * c.plain_s


def _branch_work(path, c: MapCost, contact_cost: MapCost | None, steps: int) -> tuple[int, float, str, float]:
    """``(orbits, seconds, words, seconds of the costliest orbit)`` of a branch past its first orbit. ``path``: None (the parameter's 10 scales
    alone), a scaled arclength, or a predicted path with grazings (:class:`reports.cli._branch_path.BranchPath`):
    each segment counted from the first step again (the continuation starts anew past a grazing), a contact
    stretch between grazings at :data:`CONTACT_PATH_FACTOR` times its path, :data:`GRAZING_ITERATIONS` and the
    map costs ``contact_cost`` (measured there; else ``c``), and :data:`CROSSING_ORBITS` of its orbits a grazing."""
    if not hasattr(path, "segments"):
        orbits = branch_orbits(10.0 if path is None else path)
        per = _per_orbit(c, BRANCH_ITERATIONS, steps)
        return orbits, orbits * per, f" of {per:.2g} s", per
    touching = _per_orbit(contact_cost or c, GRAZING_ITERATIONS, steps)
    smooth = _per_orbit(c, BRANCH_ITERATIONS, steps)
    orbits = seconds = 0.0
    for p, contact in path.segments:
        m = branch_orbits(p * CONTACT_PATH_FACTOR if contact else p)
        orbits, seconds = orbits + m, seconds + m * (touching if contact else smooth)
    seconds += len(path.grazing_rpm) * CROSSING_ORBITS * touching
    if not path.grazing_rpm:
        return int(orbits), seconds, f" of {smooth:.2g} s", smooth
    return (int(orbits), seconds, f" of {smooth:.2g} s, {touching:.2g} s in contact, and {len(path.grazing_rpm)} "
            f"grazing(s) near {', '.join(f'{g:.0f}' for g in path.grazing_rpm)} rpm", max(smooth, touching))


def _us(seconds: float) -> str:
    return f"{seconds * 1e6:.3g} µs" if seconds < 1e-3 else f"{seconds * 1e3:.3g} ms"


def campbell(n_dofs: int, speeds: int) -> Estimate:
    """``speeds`` eigenproblems of a model of ``n_dofs`` (:data:`EIG_COST_S`, scaled with n^3)."""
    per = EIG_COST_S * (n_dofs / EIG_COST_DOFS) ** 3
    return Estimate(speeds * per, (2 * n_dofs) ** 2 * 16 * 4,     # one complex eigenproblem and its vectors
                    f"{speeds} eigenproblems of {2 * n_dofs} states, {per:.3g} s each", bound=False)


def stepping(n_steps: float, n_records: float, n_dofs: int, factor: float = 1.0) -> Estimate:
    """A Newmark run of ``n_steps`` (the production step of :data:`STEP_COST_S`, dense products scaled with the
    square of the DOFs, times ``factor``) keeping ``n_records`` samples of every DOF (time, q, v, the support's
    relative motion and forces: 8 bytes each) and their CSV text (about 16 bytes a number)."""
    per_step = STEP_COST_S * max(1.0, (n_dofs / 28) ** 2) * factor
    per_record = (1 + 2 * n_dofs + 4 + 4 + 4 + 4 + 2) * 8 + (2 * n_dofs + 30) * 16
    return Estimate(n_steps * per_step, n_records * per_record,
                    f"{_steps(n_steps)}, {n_records:.3g} records of {n_dofs} DOFs", bound=False)
