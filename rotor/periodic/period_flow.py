"""The production scheme's flow over a whole number of steps, with its monodromy matrix: what shooting,
Floquet analysis and continuation integrate (:mod:`rotor.periodic.shooting`).

Two back-ends give the same map ``x(t0) ↦ x(t0 + n Δt)`` of the reduced state ``x = [p, v]`` (the
coordinates ``q = T p`` of :mod:`rotor.dynamics.production`: massless DOFs condensed, the 3a/3b lock
removed) and its Jacobian:

* ``"exact"`` — :mod:`rotor.dynamics.period_map`, the monodromy carried through the Newmark steps from
  the step Jacobians (the support's analytic Jacobian), the default (``"auto"``);
* ``"fd"`` — :func:`monodromy_fd`, central finite differences of
  :func:`rotor.dynamics.production.simulate_production` over the same steps (``4 n_r`` runs), kept for
  cross-checks. Its error is O(h²) away from events; a contact onset, stick onset or
  release inside the perturbed runs makes it a secant rather than a derivative there.

Both step the same compiled loop, so the state (and the residual of a periodic orbit) agrees to the
Newton tolerance of the step; only the Jacobian differs.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotor.dynamics import constraints as cons
from rotor.dynamics.condense import expand
from rotor.dynamics.period_map import full_state, period_map, period_map_setup, reduced_state
from rotor.dynamics.production import simulate_production
from rotor.dynamics.system import NewmarkOptions, RotorSystem, Trajectory

#: relative finite-difference step of :func:`monodromy_fd` (of the state's block scale)
FD_REL_STEP = 1e-6


@dataclass(frozen=True)
class Flow:
    """One system and step ``dt_s`` prepared for repeated maps.

    Attributes
    ----------
    system : the full system (all DOFs); reduced : the one integrated (massless DOFs condensed)
    condensed : rotor.dynamics.condense.Condensed or None
    T : (n_k, n_r) orthonormal basis of the lock's null space (``q_k = T p``)
    dt_s : float (s); backend : "exact" or "fd" (how :func:`advance` differentiates the map);
    handle : the :class:`rotor.dynamics.period_map.PeriodMap` both back-ends step with
    """

    system: RotorSystem
    reduced: RotorSystem
    condensed: object
    T: np.ndarray
    dt_s: float
    backend: str
    handle: object

    @property
    def n_state(self) -> int:
        return 2 * self.T.shape[1]


@dataclass(frozen=True)
class MapResult:
    """``state`` (2 n_r,) after the steps, ``monodromy`` (2 n_r, 2 n_r) or None, end-face ``modes``, and
    ``events``: end-face mode changes met (the initial stick test's included). The exact back-end's monodromy
    is the derivative of the map while every switch stays in its step; a perturbation that moves a switch by
    a step makes the map jump, which no derivative (nor the multipliers) sees (:mod:`rotor.dynamics.period_map`).
    ``unsmooth_columns``: with events located, the monodromy's event-step columns that did not settle under
    shorter differencing (:attr:`rotor.dynamics.period_map.PeriodMapResult.unsmooth_columns`; where not 0 the
    monodromy is not the map's derivative)."""

    state: np.ndarray
    monodromy: np.ndarray | None
    modes: tuple
    events: int = 0
    unsmooth_columns: int = 0


def make_flow(system: RotorSystem, dt_s: float, backend: str = "auto", locate_events: bool | None = None,
              friction_scheme: str | None = None) -> Flow:
    """Prepare ``system`` for maps of step ``dt_s`` (s); ``backend`` "auto" (= "exact": the monodromy of
    :mod:`rotor.dynamics.period_map`) or "fd" (central differences, :func:`monodromy_fd`, for cross-checks;
    its step is not checked against the contact limit). ``locate_events``: friction events located inside the
    step (:attr:`rotor.dynamics.system.NewmarkOptions.locate_events`: the map continuous through them); None:
    the default of :class:`~rotor.dynamics.system.NewmarkOptions`. ``friction_scheme``: "active-set" or
    "projection" (:attr:`rotor.dynamics.system.NewmarkOptions.friction_scheme`); None: the default."""
    if backend == "auto":
        backend = "exact"
    if backend not in ("exact", "fd"):
        raise ValueError(f"backend = {backend!r}: must be 'auto', 'fd' or 'exact' (rotor.dynamics.period_map)")
    given = {} if locate_events is None else {"locate_events": bool(locate_events)}
    if friction_scheme is not None:
        given["friction_scheme"] = friction_scheme
        if friction_scheme == "projection":     # a map with no jump: nothing to locate (the step-grid map is it)
            given["locate_events"] = False
    opts = NewmarkOptions(**given) if given else None
    pm = period_map_setup(system, dt_s, opts, check_step=backend == "exact")
    return Flow(system, pm.reduced, pm.condensed, pm.T, float(dt_s), backend, pm)


def to_reduced(flow: Flow, q, v) -> np.ndarray:
    """Reduced state ``[p, v_p]`` of the full ``(q, v)`` (m, rad; m/s, rad/s); rows of samples allowed."""
    return reduced_state(flow.handle, q, v)


def _kept(flow: Flow, state) -> tuple[np.ndarray, np.ndarray]:
    nr = flow.T.shape[1]
    state = np.asarray(state, float)
    return flow.T @ state[:nr], flow.T @ state[nr:]


def to_full(flow: Flow, state, t_s: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Full ``(q, v)`` of a reduced state at time ``t_s`` (the condensed DOFs depend on the load at t)."""
    return full_state(flow.handle, state, t_s)


def _run(flow: Flow, state, t0: float, n_steps: int, modes0, record_every: int | None = None) -> Trajectory:
    qk, vk = _kept(flow, state)
    return simulate_production(flow.reduced, flow.dt_s, int(n_steps), qk, vk, t0=float(t0), modes0=tuple(modes0),
                               options=flow.handle.options, record_every=int(record_every or n_steps), check_step=False,
                               prepared=flow.handle.prepared)


def advance(flow: Flow, state, t0: float, n_steps: int, modes0=(cons.STICK, cons.STICK), *,
            jacobian: bool = True) -> MapResult:
    """The map over ``n_steps`` steps from ``state`` at ``t0`` (s), with its Jacobian if asked."""
    if flow.backend == "exact":
        r = period_map(flow.handle, np.asarray(state, float), float(t0), int(n_steps), modes0=tuple(modes0),
                            jacobian=jacobian)
        return MapResult(np.asarray(r.state, float), None if not jacobian else np.asarray(r.monodromy, float),
                         tuple(int(m) for m in r.modes), int(r.events), int(r.unsmooth_columns))
    tr = _run(flow, state, t0, n_steps, modes0, 1)
    end = np.concatenate([flow.T.T @ tr.q[-1], flow.T.T @ tr.v[-1]])
    mono = monodromy_fd(flow, state, t0, n_steps, modes0) if jacobian else None
    nf = flow.reduced.support.faces()[2] if flow.reduced.support is not None else 0
    events = int(sum(int(modes0[k]) != int(tr.modes[0, k]) for k in range(nf)))
    events += int(np.count_nonzero(np.diff(tr.modes[:, :nf].astype(np.int64), axis=0)))
    return MapResult(end, mono, tuple(int(m) for m in tr.modes[-1]), events)


def block_scales(flow: Flow, state) -> np.ndarray:
    """Per-component scale (2 n_r,): the largest displacement and the largest velocity component of
    ``state`` (each at least 1e-12 of its unit), for finite differences and norms."""
    nr = flow.T.shape[1]
    state = np.asarray(state, float)
    sp = max(float(np.abs(state[:nr]).max(initial=0.0)), 1e-12)
    sv = max(float(np.abs(state[nr:]).max(initial=0.0)), 1e-12)
    return np.concatenate([np.full(nr, sp), np.full(nr, sv)])


def monodromy_fd(flow: Flow, state, t0: float, n_steps: int, modes0=(cons.STICK, cons.STICK), *,
                 rel_step: float = FD_REL_STEP) -> np.ndarray:
    """``∂x(t0 + nΔt)/∂x(t0)`` by central differences of :func:`rotor.dynamics.production.simulate_production`.

    Step ``h_j = rel_step · s_j`` with ``s_j`` the block scale of component j (:func:`block_scales`); every
    perturbed run starts with the same end-face modes ``modes0``. Cost: ``2 · 2 n_r`` runs of ``n_steps``.
    """
    x0 = np.asarray(state, float)
    h = rel_step * block_scales(flow, x0)
    n = len(x0)
    J = np.empty((n, n))
    for j in range(n):
        cols = []
        for sgn in (1.0, -1.0):
            x = x0.copy()
            x[j] += sgn * h[j]
            tr = _run(flow, x, t0, n_steps, modes0)
            cols.append(np.concatenate([flow.T.T @ tr.q[-1], flow.T.T @ tr.v[-1]]))
        J[:, j] = (cols[0] - cols[1]) / (2.0 * h[j])
    return J


def record(flow: Flow, state, t0: float, n_steps: int, modes0=(cons.STICK, cons.STICK), record_every: int = 1):
    """The full-DOF trajectory (:class:`~rotor.dynamics.system.Trajectory`) over ``n_steps`` from ``state``."""
    tr = _run(flow, state, t0, n_steps, modes0, record_every)
    return expand(flow.condensed, tr) if flow.condensed is not None else tr
