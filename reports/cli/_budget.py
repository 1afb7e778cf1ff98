"""Long work announced before it starts, and refused above a stated budget unless ``--accept-long``.

Every job that can start hours of stepping or fill the memory (``simulate``, ``orbit``, ``branch``, ``study
cascade``/``params``/``map``/``point``/``testrig``/``runup``, ``rotor campbell``, ``rotor response``) estimates
its work from its step (or eigenvalue) count times a per-step cost measured on this suite's own runs (each
constant below names where it was measured), before anything is computed, and calls :func:`check`:

* above :data:`WORK_BUDGET_S` of computing or :data:`MEMORY_BUDGET_BYTES` of records: refused (exit status 2)
  with the estimate, what it is made of, and the flag that accepts it (``--accept-long``);
* above :data:`ANNOUNCE_S`: one line on stderr with the estimate, then the work starts.

The estimates are upper bounds where the work has one (a steady-state point integrates at most ``--max-revs``
revolutions; most stop far earlier), typical values otherwise (said in the message).
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
#: a step of the shooting Newton (period map with its exact monodromy, after a transient): orbit paper-table4
#: at 10 500 rpm, 256 steps a revolution, 247 transient revolutions and 2 Newton iterations in 2.55 s
#: (2026-11-27, load average 2.0)
ORBIT_STEP_COST_S = 2.55 / (256 * 249)
#: one orbit of a branch (corrector from its neighbour): 47 orbits in 189 s at 256 steps a revolution,
#: branch paper-table4 10 500 -> 11 500 rpm (2026-11-27, load average 3-6)
BRANCH_POINT_COST_S = 189.0 / 47
#: one speed of a Campbell diagram (the dense eigenproblem of a rotor model of n DOFs, state space 2n, and its
#: whirl sorting): 125 s at n = 1036 (paper-table4 with 64 elements a segment), 2.6 ms at n = 28, 3.7 s at
#: n = 268; scaled with n^3, which joins both ends (rotor.linear.modes.campbell, 2026-11-27, load average 9)
EIG_COST_S = 125.0
EIG_COST_DOFS = 1036


@dataclass(frozen=True)
class Estimate:
    """What a job will cost: ``seconds`` of computing, ``nbytes`` held in memory, ``made_of`` (words: the
    step count and the cost per step), ``bound`` (True: an upper bound, False: typical)."""

    seconds: float
    nbytes: float
    made_of: str
    bound: bool = True


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
    """``estimated at most 2.1 h of computing and 3.2 GiB of records (…)``."""
    return (f"estimated {'at most ' if est.bound else ''}{_time(est.seconds)} of computing and "
            f"{est.nbytes / 2 ** 30:.3g} GiB of records ({est.made_of})")


def check(prog: str, est: Estimate, accept_long: bool, cause: str, remedy: str, *,
          override: str = "--accept-long") -> None:
    """Refuse ``est`` beyond the budget (unless ``accept_long``), announce it beyond :data:`ANNOUNCE_S`.

    ``cause``: the options the user typed that make the work (``--steps-per-rev = 100000``), ``remedy``: what
    to change instead (``fewer steps per revolution``), ``override``: how the caller accepts it (the flag, or
    the API's keyword ``accept_long=True``). Raises :class:`WorkBudgetError`.
    """
    over = est.seconds > WORK_BUDGET_S or est.nbytes > MEMORY_BUDGET_BYTES
    if over and not accept_long:
        raise WorkBudgetError(f"{cause}: {describe(est)}, beyond the budget of {WORK_BUDGET_S / 60:g} min and "
                              f"{MEMORY_BUDGET_BYTES / 2 ** 30:g} GiB; {remedy}, or {override} to run it anyway")
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


def orbit(system, steps_per_rev: int, period_revs: int | None, points: int = 0) -> Estimate:
    """Shooting at one speed (and ``points`` further orbits of a branch): the transient rounds, at most
    ``ShootingOptions.max_transient_revs`` revolutions, and the Newton iterations on the period map with its
    monodromy, at the measured cost per step; a branch point at the measured cost per orbit."""
    from rotor.periodic.shooting import MAX_PERIOD_REVS, ShootingOptions

    o = ShootingOptions()
    revs = o.max_transient_revs + o.max_iter * (period_revs or MAX_PERIOD_REVS)
    steps = revs * steps_per_rev
    secs = steps * ORBIT_STEP_COST_S + points * BRANCH_POINT_COST_S * steps_per_rev / 256
    made = f"{_steps(steps)} of {ORBIT_STEP_COST_S * 1e6:.3g} µs"
    if points:
        made += f" for the first orbit, then up to {points} orbits of {BRANCH_POINT_COST_S * steps_per_rev / 256:.3g} s"
    return Estimate(secs, (period_revs or MAX_PERIOD_REVS) * steps_per_rev * system.n * 8 * 6, made)


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
