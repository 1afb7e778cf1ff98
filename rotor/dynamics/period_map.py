"""The production scheme's period map and its exact derivative (the monodromy matrix), for shooting.

``period_map(pm, state0, t0, n_steps)`` integrates ``n_steps`` steps of
:func:`rotor.dynamics.production.simulate_production` from the reduced state ``[p, v]`` at ``t0``
and returns the end state and ``∂ state_N / ∂ state_0``.

* **Stepping** is production's own compiled loop (:func:`rotor.dynamics.production_kernels.step_loop`,
  through ``simulate_production``, every step recorded), so the end state is production's to
  round-off (same predictor, condensed Newton, active-set and stick rules, stick-onset restart; only
  the way back from the recorded ``q = T p`` to ``p`` rounds differently).
* **Derivative** is carried afterwards along the recorded steps
  (:func:`rotor.dynamics.period_map_kernels.sensitivity_pass`): the linear Newmark part is a
  constant matrix, the support enters through the six condensed coordinates that Newton solved,
  differentiated by the implicit function theorem with the support law's analytic Jacobian
  (rank-6 correction per step). Stuck faces are differentiated as the scheme imposes them (end-of-step
  relative face velocity zero, the multipliers unknowns); slipping faces through the regularised
  friction ``−μN w/√(|w|² + w_reg²)``, which is smooth. A step in which a face changes mode is
  differentiated with the modes it ended in (and through the stick-onset restart). In this scheme a
  switch falls on a step boundary, so while a perturbation leaves every switch in its step the map is
  smooth and the monodromy is its exact derivative (tested against central differences through
  revolutions with switches). There is **no saltation matrix**: a perturbation that moves a switch by a
  step makes the map jump instead (the discrete trace of the continuous system's saltation), which the
  derivative does not see; ``PeriodMapResult.events`` counts the switches so a caller knows when
  that can happen. With ``options.locate_events`` the friction events are located inside the step, the map
  is continuous through them, and its event steps are differentiated as located
  (:mod:`rotor.dynamics.period_map_events`: the event time's derivative included).
* **Initial acceleration**: as production, ``a₀`` is the consistent acceleration at ``(p₀, v₀, t₀)``
  (equilibrium with the stuck faces' relative acceleration zero, :func:`rotor.dynamics.initial.initial_state`);
  its derivative enters the monodromy, so the map is a function of ``(p₀, v₀)`` alone.

Coordinates. Massless DOFs are condensed out (:mod:`rotor.dynamics.condense`) and the 3a/3b lock
eliminated, ``q = T p`` (:func:`rotor.dynamics.constraints.null_space_map`), as in :func:`rotor.dynamics.production.prepare`;
the state is ``[p, v]`` with ``v = Tᵀ q̇``, ``2 nr`` numbers (``nr = PeriodMap.nr``).
:func:`full_state` and :func:`reduced_state` map to and from the full DOFs.

For the Newmark average-acceleration rule (β = 1/4, γ = 1/2) on a linear system the step is the
trapezoidal rule, whose amplification of an eigenvalue ``λ`` is the Cayley map
``(1 + λΔt/2)/(1 − λΔt/2)`` (Hairer & Wanner 1996, *Solving Ordinary Differential Equations II*, the
trapezoidal rule's stability function), so the monodromy's eigenvalues over N steps are its N-th
powers, ``exp(λT) + O(Δt²)``.
"""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
from contact.loose_support import N_PARAMS
from rotor.dynamics import constraints as cons
from rotor.dynamics.condense import Condensed, condense, expand
from rotor.dynamics.period_map_events import located_monodromy
from rotor.dynamics.period_map_kernels import sensitivity_pass
from rotor.dynamics.period_map_projection import sensitivity_pass_projected
from rotor.dynamics.production import Prepared, prepare, simulate_production
from rotor.dynamics.projection_start import projected_modes
from rotor.dynamics.production import warm_up as production_warm_up
from rotor.dynamics.system import NewmarkOptions, RotorSystem, Trajectory, check_time_step


@dataclass(frozen=True)
class PeriodMap:
    """One (system, Δt) pair made ready for :func:`period_map` (build with :func:`period_map_setup`).

    Fields: ``system`` (as given), ``reduced`` (the system actually integrated: massless DOFs
    condensed), ``condensed`` (:class:`rotor.dynamics.condense.Condensed` or None), ``dt`` (s),
    ``options``, ``prepared`` (:class:`rotor.dynamics.production.Prepared`), ``T`` (lock null-space
    map, ``q_keep = T p``), ``nr`` (reduced coordinates; the state has ``2 nr``), ``MK``, ``MD``
    (``M⁻¹K``, ``M⁻¹D`` reduced), ``AK``, ``AD`` (``A⁻¹K``, ``A⁻¹D``, ``A`` the Newmark matrix),
    ``params`` (support law parameters), ``n_faces`` (active end faces, 0 without support).
    """

    system: RotorSystem
    reduced: RotorSystem
    condensed: Condensed | None
    dt: float
    options: NewmarkOptions
    prepared: Prepared
    T: np.ndarray
    nr: int
    MK: np.ndarray
    MD: np.ndarray
    AK: np.ndarray
    AD: np.ndarray
    params: np.ndarray
    n_faces: int


@dataclass(frozen=True)
class PeriodMapResult:
    """Result of :func:`period_map`.

    Attributes
    ----------
    state : numpy.ndarray
        (2 nr,) ``[p, v]`` at ``t0 + n_steps Δt`` (m, rad; m/s, rad/s in reduced coordinates).
    monodromy : numpy.ndarray or None
        (2 nr, 2 nr) ``∂ state / ∂ state0``, None with ``jacobian=False``: the exact derivative
        of the scheme's map as long as every stick/slip switch stays in its step; no saltation term for
        a switch that moves (see the module docstring), so with ``events > 0`` it is the derivative of
        the smooth piece the state lies on.
    modes : numpy.ndarray
        (2,) int64 face modes at the end (1 stick, 0 slip), to pass as the next ``modes0``.
    phi_face : numpy.ndarray
        (2, 2) end-face forces at the end (N): stuck faces' multipliers, slip forces.
    trajectory : rotor.dynamics.system.Trajectory or None
        Full DOFs, as ``simulate_production`` with ``record_every``, or None.
    events : int
        Number of face mode changes met: the initial stick test's changes of ``modes0`` plus
        the changes from step to step.
    unconverged_steps : int
        Steps accepted at the least residual (see ``simulate_production``); the
        derivative of such a step is only approximate.
    t : float
        End time (s).
    replay_mismatch : float
        With ``locate_events``: the largest relative difference between an event step replayed for its
        derivative and the recorded step (:mod:`rotor.dynamics.period_map_events`); 0 otherwise.
    unsmooth_columns : int
        With ``locate_events``: event-step columns of the monodromy whose central differences did not settle down
        to a differencing step of 1e-9 of the component's scale (a threshold of the step lies at the recorded
        state, :func:`rotor.dynamics.period_map_events._step_jacobian`); where it is not 0 the monodromy is not the
        map's derivative and its multipliers do not decide stability. 0 otherwise.
    """

    state: np.ndarray
    monodromy: np.ndarray | None
    modes: np.ndarray
    phi_face: np.ndarray
    trajectory: Trajectory | None
    events: int
    unconverged_steps: int
    t: float
    replay_mismatch: float = 0.0
    unsmooth_columns: int = 0


def period_map_setup(system: RotorSystem, dt: float, options: NewmarkOptions | None = None, *,
                     check_step: bool = True) -> PeriodMap:
    """Prepare ``system`` for period maps of step ``dt`` (s): production's :func:`prepare` plus the
    constant matrices of the derivative. ``check_step`` refuses a step above the contact limit
    (:func:`rotor.dynamics.system.check_time_step`), as ``simulate_production`` does."""
    opts = options or NewmarkOptions()
    if not (np.isfinite(dt) and dt > 0):
        raise InputError(f"dt_s: {dt!r} s; must be a finite positive step")
    c = condense(system)
    red = c.system if c is not None else system
    if red.support is not None and check_step:
        check_time_step(red, dt)
    pre = prepare(red, dt, opts)
    T, Mr = pre.T, pre.Mr
    Minv = pre.Minv
    Kr, Dr = pre.Kr, pre.Dr
    A = Mr + opts.gamma * dt * Dr + opts.beta * dt * dt * Kr
    sup = red.support
    params = np.asarray(sup.law.params, float) if sup is not None else np.zeros(N_PARAMS)
    return PeriodMap(system, red, c, float(dt), opts, pre, T, T.shape[1], Minv @ Kr, Minv @ Dr,
                     np.linalg.solve(A, Kr), np.linalg.solve(A, Dr), params, int(pre.n_faces))


def full_state(pm: PeriodMap, state, t: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """``(q, q̇)`` on all DOFs of ``pm.system`` from the reduced ``state`` ``[p, v]``; condensed
    (massless) DOFs are recovered from their static equation at time ``t`` (s)."""
    x = np.asarray(state, float)
    nr = pm.nr
    if x.shape != (2 * nr,):
        raise InputError(f"state: shape {x.shape}; must be ({2 * nr},) = [p, v] in reduced coordinates")
    q, v = pm.T @ x[:nr], pm.T @ x[nr:]
    if pm.condensed is None:
        return q, v
    tr = _single_sample(t, q, v)
    full = expand(pm.condensed, tr)
    return full.q[0], full.v[0]


def reduced_state(pm: PeriodMap, q, v) -> np.ndarray:
    """The reduced state ``[Tᵀ q, Tᵀ q̇]`` (2 nr,) of full-DOF ``q``, ``q̇`` (lock-consistent)."""
    q = np.asarray(q, float)
    v = np.asarray(v, float)
    if pm.condensed is not None and q.shape[-1] == pm.system.n:
        q, v = q[..., pm.condensed.keep], v[..., pm.condensed.keep]
    if q.shape[-1] != pm.reduced.n or v.shape[-1] != pm.reduced.n:
        raise InputError(f"q, v: {q.shape[-1]} and {v.shape[-1]} DOFs; the system has {pm.system.n}")
    return np.concatenate([q @ pm.T, v @ pm.T], axis=-1)


def period_map(pm: PeriodMap, state0, t0: float, n_steps: int, *, modes0=None, jacobian: bool = True,
               record_every: int = 0) -> PeriodMapResult:
    """Integrate ``n_steps`` production steps from ``state0`` ``[p, v]`` at ``t0`` (s).

    Parameters
    ----------
    pm : from :func:`period_map_setup`.
    state0 : (2 nr,) reduced state (see :func:`reduced_state`).
    t0 : start time (s); the harmonic forces are functions of time.
    n_steps : steps (≥ 1); a period of ``m`` revolutions is ``m · steps_per_rev``.
    modes0 : (2,) requested face modes at ``t0`` (1 stick, 0 slip); None: both stuck, as
        ``simulate_production``. The initial stick test may release a face (counted in ``events``).
    jacobian : also compute the monodromy.
    record_every : > 0: return the trajectory sampled every that many steps (full DOFs).

    Returns
    -------
    PeriodMapResult
    """
    x0 = np.asarray(state0, float)
    nr = pm.nr
    if x0.shape != (2 * nr,) or not np.all(np.isfinite(x0)):
        raise InputError(f"state0: shape {x0.shape}; must be ({2 * nr},) finite = [p, v] in reduced coordinates")
    if int(n_steps) < 1:
        raise InputError(f"n_steps: {n_steps}; must be at least 1")
    n_steps = int(n_steps)
    record_every = int(record_every)
    modes_req = (cons.STICK, cons.STICK) if modes0 is None else tuple(int(m) for m in modes0)
    red = pm.reduced
    tr = simulate_production(red, pm.dt, n_steps, pm.T @ x0[:nr], pm.T @ x0[nr:], t0=float(t0), modes0=modes_req,
                             options=pm.options, record_every=1, check_step=False, prepared=pm.prepared)
    rec_p, rec_v = tr.q @ pm.T, tr.v @ pm.T
    modes_rec = tr.modes
    events = 0
    projected = pm.options.friction_scheme == "projection" and red.support is not None
    if projected:           # one map for every start: no modes, and a stick or slip onset is a kink, not a jump
        modes_rec = np.tile(projected_modes(pm.n_faces), (tr.modes.shape[0], 1))
    elif pm.n_faces:
        events = int(sum(modes_req[k] != modes_rec[0, k] for k in range(pm.n_faces)))
        events += int(np.count_nonzero(np.diff(modes_rec[:, :pm.n_faces].astype(np.int64), axis=0)))
    mismatch, unsmooth = 0.0, 0
    if jacobian and projected:
        mono = _monodromy_projected(pm, tr, rec_p, rec_v)
    elif jacobian and pm.options.locate_events:      # event steps differentiated as located (period_map_events)
        mono, mismatch, unsmooth = located_monodromy(pm, tr, rec_p, rec_v)
    else:
        mono = _monodromy(pm, tr, rec_p, rec_v) if jacobian else None
    out_tr = None
    if record_every > 0:
        out_tr = tr if record_every == 1 else _subsample(tr, record_every)
        if pm.condensed is not None:
            out_tr = expand(pm.condensed, out_tr)
    return PeriodMapResult(np.concatenate([rec_p[-1], rec_v[-1]]), mono, modes_rec[-1].astype(np.int64),
                           tr.face_force[-1].copy(), out_tr, events, int(tr.unconverged_steps), float(tr.t[-1]),
                           mismatch, unsmooth)


def _monodromy(pm: PeriodMap, tr: Trajectory, rec_p, rec_v) -> np.ndarray:
    """``∂(p_N, v_N)/∂(p₀, v₀)`` along the every-step record ``tr`` (reduced ``rec_p``, ``rec_v``)."""
    pre, opts = pm.prepared, pm.options
    modes = np.ascontiguousarray(tr.modes.astype(np.int64))
    return sensitivity_pass(np.ascontiguousarray(rec_p), np.ascontiguousarray(rec_v), modes, pm.dt, opts.beta,
                            opts.gamma, pm.AK, pm.AD, pm.MK, pm.MD, pre.Bt, pre.W, pre.S, pre.WM, pre.SM, pre.P,
                            pre.limits, pre.a1, pm.reduced.support is not None, pm.params, opts.w_reg,
                            bool(opts.consistent_stick_onset))


def _monodromy_projected(pm: PeriodMap, tr: Trajectory, rec_p, rec_v) -> np.ndarray:
    """The monodromy of the projection scheme's record (:mod:`rotor.dynamics.period_map_projection`)."""
    pre, opts = pm.prepared, pm.options
    return sensitivity_pass_projected(np.ascontiguousarray(rec_p), np.ascontiguousarray(rec_v),
                                      np.ascontiguousarray(tr.a @ pm.T), np.ascontiguousarray(tr.face_force),
                                      projected_modes(pm.n_faces), pm.dt, opts.beta, opts.gamma, pm.AK, pm.AD, pm.MK,
                                      pm.MD, pre.Bt, pre.W, pre.S, pre.WM, pre.SM, pre.P, pre.limits, pre.a1,
                                      pm.params, opts.w_reg)


def warm_up() -> dict:
    """Compile (or load from the on-disk cache, :mod:`contact.compiled_cache`) production's step loop and
    the sensitivity pass now, so that a later :func:`period_map` times the work alone.

    Returns
    -------
    dict
        ``compile_s`` (s, wall time of the compiles or cache loads) and ``from_cache`` (True if the
        sensitivity pass came from the disk cache).
    """
    t0 = time.perf_counter()
    production_warm_up()
    if not sensitivity_pass.signatures:
        f1, f2 = np.zeros((1, 2)), np.zeros((2, 2))
        sensitivity_pass(f1, f1.copy(), np.zeros((1, 2), np.int64), 1.0, 0.25, 0.5, f2, f2, f2, f2, np.zeros((6, 2)),
                         np.zeros((2, 6)), np.zeros((6, 6)), np.zeros((2, 6)), np.zeros((6, 6)), np.zeros((2, 2, 4)),
                         np.zeros(2), 0.0, False, np.zeros(N_PARAMS), 1e-6, True)
    return {"compile_s": time.perf_counter() - t0, "from_cache": bool(sum(sensitivity_pass.stats.cache_hits.values()))}


_SAMPLED = ("t", "q", "v", "a", "u", "w", "f_contact", "f_elastic", "face_force", "modes", "newton_iters", "passes")


def _subsample(tr: Trajectory, k: int) -> Trajectory:
    """Every ``k``-th sample of ``tr``, as ``simulate_production`` records with ``record_every = k``."""
    return dataclasses.replace(tr, **{name: getattr(tr, name)[::k].copy() for name in _SAMPLED})


def _single_sample(t: float, q, v) -> Trajectory:
    """A one-sample trajectory of the reduced system, for :func:`rotor.dynamics.condense.expand`."""
    z4 = np.zeros((1, 4))
    return Trajectory(t=np.array([float(t)]), q=q[None], v=v[None], a=np.zeros((1, q.size)), u=z4, w=z4,
                      f_contact=z4, f_elastic=z4, face_force=np.zeros((1, 2, 2)), modes=np.zeros((1, 2), np.int8),
                      newton_iters=np.zeros(1, np.int32), passes=np.zeros(1, np.int32))
