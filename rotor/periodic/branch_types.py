"""The objects of a continuation: the problem (a family of period maps over a scalar parameter), the points,
bifurcations and branches it produces, its options, and the evaluator of the scaled residual and Jacobian.

The algorithm is :mod:`rotor.periodic.continuation`; the corrector and step pieces
:mod:`rotor.periodic.corrector`, bifurcation detection :mod:`rotor.periodic.branch_events`, restarts past a switch
:mod:`rotor.periodic.restarts`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from rotor.dynamics import constraints as cons
from rotor.periodic.floquet import FloquetResult
from rotor.periodic.period_flow import Flow, advance, make_flow

#: relative step of the parameter finite difference
PARAM_REL_STEP = 1e-6
#: singular values of the scaled ``M − I`` below this fraction of the largest are a continuum's directions
NEUTRAL_TOL = 1e-8
#: shortest parameter step of a restart past a switch (scaled parameter, –)
RESTART_STEP = 1e-4
#: how a restarted point was found (``BranchPoint.restarted``; 0: by the corrector)
SECANT, TRANSIENT, COLD, GRID = 1, 2, 3, 4
#: the restarts by name
RESTART_NAMES = {SECANT: "secant", TRANSIENT: "transient", COLD: "cold", GRID: "step-grid"}
#: a restart from the linear periodic solution (a new segment's start) is tried this many times, at parameter
#: steps growing ×4 from ``COLD_STEP`` (scaled parameter; with a tenth of 600–18 000 rpm as the scale: 1.7 to 445 rpm)
COLD_TRIES, COLD_STEP = 5, 1e-3
#: most revolutions of the transient of a restart from the last orbit (four times as many from the linear start)
RESTART_TRANSIENT_REVS = 62
#: the state scales are renewed when the orbit's own scale differs from them by more than this factor
RESCALE_RATIO = 2.0


@dataclass(frozen=True)
class Problem:
    """A family of period maps over a scalar parameter λ.

    Attributes
    ----------
    system_at : callable ``λ -> RotorSystem``
    speed_at : callable ``λ -> Ω`` (rad/s): the speed whose revolution sets the period
    steps_per_rev : int; period_revs : int (1..8); backend : "auto", "fd" or "exact"
    modes0 : end-face modes the orbits start from
    name : str, the parameter's name with its unit (``speed_rad_s``, ``clearance_m``)
    locate_events : friction events located inside the step (:func:`rotor.periodic.period_flow.make_flow`;
        None: the scheme's default); friction_scheme : "active-set" or "projection"
        (:attr:`rotor.dynamics.system.NewmarkOptions.friction_scheme`; None: the default)
    """

    system_at: Callable
    speed_at: Callable
    steps_per_rev: int
    period_revs: int = 1
    backend: str = "auto"
    modes0: tuple = (cons.SLIP, cons.SLIP)
    name: str = "speed_rad_s"
    locate_events: bool | None = None
    friction_scheme: str | None = None

    def flow(self, lam: float) -> Flow:
        return make_flow(self.system_at(lam), 2.0 * math.pi / (self.speed_at(lam) * self.steps_per_rev), self.backend,
                         self.locate_events, self.friction_scheme)

    @property
    def n_steps(self) -> int:
        return self.steps_per_rev * self.period_revs


def speed_problem(system_at_speed: Callable, steps_per_rev: int, **kw) -> Problem:
    """Continuation in the spin speed (λ = Ω, rad/s): ``system_at_speed(Ω) -> RotorSystem``."""
    return Problem(system_at_speed, lambda w: w, steps_per_rev, **kw)


def parameter_problem(system_at: Callable, speed_rad_s: float, steps_per_rev: int, name: str, **kw) -> Problem:
    """Continuation in a scalar scene parameter λ (``name`` with its unit, e.g. ``clearance_m``,
    ``misalignment_m``) at the fixed spin speed ``speed_rad_s``: ``system_at(λ) -> RotorSystem``."""
    w = float(speed_rad_s)
    return Problem(system_at, lambda lam: w, steps_per_rev, name=name, **kw)


@dataclass(frozen=True)
class BranchPoint:
    """One orbit of a branch: ``parameter`` λ, reduced ``state`` at phase 0, ``floquet``, corrector
    ``iterations``, ``residual`` (scaled, –), ``dlam_ds`` (parameter component of the unit tangent), ``restarted``:
    0 reached by the corrector from the point before, else by a restart past a switch (:func:`rotor.periodic.restarts.restart`):
    :data:`SECANT`, :data:`TRANSIENT`, :data:`COLD` or :data:`GRID`, how its orbit was shot (:func:`rotor.periodic.restarts.shot`);
    ``events``: end-face mode changes over the period (−1 unknown), ``why``: for a restarted point, why the
    corrector failed before it (the last corrector's failure, :attr:`Evaluator.failure`); ``modes``: the end-face
    modes at phase 0 its period map starts from (:attr:`Evaluator.modes0` when it was found; None: the problem's)."""

    parameter: float
    state: np.ndarray
    floquet: FloquetResult
    iterations: int
    residual: float
    dlam_ds: float
    restarted: int = 0
    events: int = -1
    why: str = ""
    modes: tuple | None = None


def start_modes(problem: Problem, point: BranchPoint) -> tuple:
    """The end-face modes at phase 0 that ``point``'s period map starts from: its own, else the problem's."""
    return tuple(problem.modes0 if point.modes is None else point.modes)


@dataclass(frozen=True)
class Bifurcation:
    """``kind`` ("fold", "branch_point", "period_doubling", "neimark_sacker", "discontinuous") between points
    ``index − 1`` and ``index``, at the interpolated ``parameter``; ``multiplier`` the critical one at point
    ``index``; ``detail``: for a discontinuous (set-valued) bifurcation, the spectral radius on either side
    and the switches per period that changed between the two points (Leine & van Campen 2002)."""

    kind: str
    index: int
    parameter: float
    multiplier: complex
    detail: str = ""


@dataclass(frozen=True)
class Branch:
    """Points and bifurcations of one branch, ``period_revs``, why it stopped (``stop``), ``wall_s``,
    ``restarts``: points reached by a shooting restart past a switch (:func:`rotor.periodic.restarts.restart`),
    and ``failures``: every stall of the corrector, ``(parameter, why, outcome)`` (``outcome``: how it was passed:
    a smaller step, a restart, or the stop), so that no non-convergence is hidden."""

    points: tuple
    bifurcations: tuple
    period_revs: int
    stop: str
    wall_s: float
    restarts: int = 0
    failures: tuple = ()

    def parameters(self) -> np.ndarray:
        return np.array([p.parameter for p in self.points])


@dataclass(frozen=True)
class ContinuationOptions:
    """``ds`` initial/min/max arclength steps (scaled units), corrector ``tol`` (–) and ``max_iter``,
    ``max_points``, ``back_margin`` (stop when a branch turns back beyond the start by this fraction of the
    range), ``rcond`` of the minimum-norm solves, ``multiplier_tol`` (Floquet).

    ``pass_switches``: after ``restart_after`` failed correctors in a row (one after a restarted point) the
    branch is restarted past the switch by shooting at fixed parameter (:func:`rotor.periodic.restarts.restart`, ``restart_tries``
    parameter steps growing ×4 from the last one).
    ``follow_scales``: the state scales follow the orbit's own peak-to-peak range (never below the given
    ``scales``) once it differs from them by more than ``RESCALE_RATIO``. Both False: the plain corrector with
    the start's scales.
    ``watch``: None, or ``watch(evaluator, y) -> float`` (a contact measure, :mod:`rotor.periodic.grazing`); the
    branch stops (``stop`` "grazing", the crossing point not taken) before a predictor or a corrected point on
    the other side of its zero than the last point.
    ``turn_back``: None, or how far (scaled parameter) the branch may run back after a fold before it jumps past
    the fold's parameter (:func:`rotor.periodic.restarts.jump_past_fold`: what a run-up does; the returning
    branch is the unstable middle one of a hysteresis); ``max_wall_s``: stop ("wall time limit") after this
    long (s).
    ``centre_families``: each point of a friction-held family (faces stuck through the period) is moved to the
    member farthest from slipping and from the bore (:func:`rotor.periodic.family_centre.centred`), and a
    corrector failing there halves the step ``restart_after`` times before a restart, as off the family;
    False: each point keeps the previous point's offsets, and the first failure there restarts.
    ``back_fill``: a restart landing farther than :data:`rotor.periodic.continuation.BACK_FILL_MIN` from the last
    orbit is moved back along the branch it landed on, to its fold or the last orbit's parameter
    (:func:`rotor.periodic.continuation._back_filled`)."""

    ds: float = 0.05
    ds_min: float = 1e-5
    ds_max: float = 0.5
    tol: float = 1e-9
    max_iter: int = 10
    max_points: int = 400
    back_margin: float = 0.5
    rcond: float = 1e-10
    multiplier_tol: float = 1e-6
    pass_switches: bool = True
    restart_after: int = 3
    restart_tries: int = 6
    follow_scales: bool = True
    watch: Callable | None = None
    turn_back: float | None = None
    max_wall_s: float | None = None
    centre_families: bool = False
    back_fill: bool = False


class Evaluator:
    """``R``, ``M`` and ``∂R/∂λ`` at (x, λ) in scaled variables, with the flow cached per λ. ``events``: the
    end-face mode changes of the last map evaluated with its Jacobian; ``failure``: why the last corrector
    failed (set by :func:`rotor.periodic.corrector.correct`); ``modes_end``: the end-face modes after the period of
    that map (a fixed point's own modes at phase 0 when they repeat); ``modes0``: the end-face modes at phase 0 the maps
    start from, the problem's until a restart lands on an orbit that starts in other modes
    (:func:`rotor.periodic.restarts.shot`: a stuck face's orbit and a slipping face's are fixed points of
    different maps)."""

    def __init__(self, problem: Problem, scales: np.ndarray, lam_scale: float):
        self.pb, self.s, self.ls = problem, scales, lam_scale
        self.modes0 = tuple(problem.modes0)
        self.modes_end: tuple | None = None
        self._flows: dict = {}
        self.events, self.failure = -1, ""
        #: the iterate and the rejected full step of a stall whose maps switch the faces a different number of
        #: times, with the modes they start from (rotor/periodic/map_jump.py; reset by each stall's first corrector)
        self.straddle: tuple | None = None

    def flow(self, lam):
        if lam not in self._flows:
            if len(self._flows) > 8:
                self._flows.clear()
            self._flows[lam] = self.pb.flow(lam)
        return self._flows[lam]

    def residual_switches(self, y, modes0) -> tuple:
        """``(R, switches)``: the scaled residual at the scaled point ``y = (x/s, λ/ls)`` of the map from the end-face
        ``modes0``, without its Jacobian, and the end-face switches of that period (rotor/periodic/map_jump.py)."""
        x, lam = y[:-1] * self.s, y[-1] * self.ls
        r = advance(self.flow(lam), x, 0.0, self.pb.n_steps, modes0, jacobian=False)
        return (r.state - x) / self.s, int(r.events)

    def __call__(self, x, lam, jacobian=True):
        r = advance(self.flow(lam), x, 0.0, self.pb.n_steps, self.modes0, jacobian=jacobian)
        R = (r.state - x) / self.s
        if not jacobian:
            return R, None, None
        self.events, self.modes_end = int(r.events), tuple(int(m) for m in r.modes)
        h = PARAM_REL_STEP * max(abs(lam), 1e-12)
        Rp = advance(self.flow(lam + h), x, 0.0, self.pb.n_steps, self.modes0, jacobian=False).state
        Rm = advance(self.flow(lam - h), x, 0.0, self.pb.n_steps, self.modes0, jacobian=False).state
        Rl = (Rp - Rm) / (2.0 * h) / self.s * self.ls
        J = np.hstack([(r.monodromy - np.eye(len(x))) * (self.s[None, :] / self.s[:, None]), Rl[:, None]])
        return R, J, r.monodromy
