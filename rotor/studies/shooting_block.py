"""Shooting points in contiguous speed blocks, each speed started from its lower neighbour's orbit.

``study cascade|params --method shooting`` computes its speeds as one :class:`sweep.Task` per block of
:data:`BLOCK_SPEEDS` contiguous speeds (:func:`shooting_block_tasks`). Within a block the speeds are run
upwards as :func:`rotor.studies.orbit.cascade` runs them: the first speed of the block, and the speed after
one where shooting failed (or after zero speed), from :func:`rotor.dynamics.static_start.periodic_start` ("cold":
the linear periodic solution, or the equilibrium with its forced response under gravity or static loads the faces cannot
hold); every other
speed from the phase-0 state of its lower neighbour's orbit with that orbit's period as a hint
(:func:`rotor.studies.orbit.warm_options`). Each speed is stored under its own key (``rpm<speed>``) with
the arrays and info of :func:`rotor.studies.shooting_point.run_shooting_point` plus

* ``started_from``: ``"cold"`` or the neighbour's ``speed_rpm``;
* ``phase0_q_m``, ``phase0_v_m_s``: the orbit's full state at phase 0 (m, rad; m/s, rad/s; converged
  orbits only), from which a resumed block starts the next speed.

The partition is fixed by the speed list (not by the number of workers), and a missing speed of a partly
stored block is recomputed from its stored lower neighbour (JSON floats round-trip exactly), so a point's
result depends only on the partition and its neighbour, not on scheduling or interruption. The block
speeds are part of every point's parameters: a store computed with another partition is recomputed.
"""
from __future__ import annotations

import time

import numpy as np

from rotor.studies.orbit import orbit, warm_options
from rotor.studies.shooting_point import check_task_digest, orbit_point, run_shooting_point, task_digest
from rotor.studies.steady_state import SteadyStateOptions, point_system, step_per_rev

#: speeds per block: a cold start per block bounds the cost of a bad start, while 61 speeds still give
#: 8 blocks to share between workers
BLOCK_SPEEDS = 8


def _point_key(prefix: str, speed_rpm: float) -> str:
    return f"{prefix}{float(speed_rpm):.1f}"


def _warm_start(prev: dict | None):
    """``(start, period_hint)`` from the lower neighbour's info (None: start cold)."""
    if prev is None or prev.get("classified_by") != "multipliers" or "phase0_q_m" not in prev:
        return None, None
    start = (np.asarray(prev["phase0_q_m"], dtype=float), np.asarray(prev["phase0_v_m_s"], dtype=float))
    return start, int(prev["shooting_period_revs"])


def shooting_point_from(scene: str, speed_rpm: float, prev: dict | None, kw: dict, point: dict):
    """One speed of a block: ``(arrays, info)`` as :func:`run_shooting_point`, started from ``prev`` (the lower
    neighbour's info, or None: cold), with ``started_from`` and the phase-0 state added to the info."""
    t_start = time.perf_counter()
    if float(speed_rpm) == 0.0:
        arrays, info = run_shooting_point(scene, speed_rpm, **kw, **point)
        return arrays, {**info, "started_from": "cold"}
    start, hint = _warm_start(prev)
    system = point_system(scene, speed_rpm, **kw)[2]
    n = step_per_rev(system, SteadyStateOptions(**(point["options"] or {})))
    if start is None:
        res = orbit(scene, speed_rpm, steps_per_rev=n, **kw)
    else:
        res = orbit(scene, speed_rpm, steps_per_rev=n, start=start, options=warm_options(), period_hint=hint, **kw)
    arrays, info = orbit_point(res, scene, speed_rpm, kw, point, True, t_start)
    info["started_from"] = "cold" if start is None else float(prev["speed_rpm"])
    if res.converged:
        info.update(phase0_q_m=res.q_m.tolist(), phase0_v_m_s=res.v_m_s.tolist())
    return arrays, info


def run_shooting_block(scene: str, block_rpm: list, prefix: str = "rpm", stored: dict | None = None,
                       clearance_m: float | None = None, misalignment_m: float | None = None,
                       tilt_ignored: bool = False, mu: float | None = None, preload_n: float | None = None,
                       options: dict | None = None, max_order: float = 6.0, history_revs: int = 4,
                       elements_per_segment: int | None = None, method: str = "shooting",
                       law: str | None = None, scene_sha256: str | None = None) -> dict:
    """The speeds of ``block_rpm`` (rpm, ascending) not in ``stored`` (key -> info of the block's points
    already stored), each from its lower neighbour (module docstring): ``{key: (arrays, info)}`` for
    :func:`sweep.run_sweep`."""
    if method != "shooting":
        raise ValueError(f"method = {method!r}: run_shooting_block computes 'shooting' points")
    check_task_digest(scene_sha256, scene, elements_per_segment, law, f"shooting block from {block_rpm[0]:g} rpm")
    stored = stored or {}
    kw = {"clearance_m": clearance_m, "misalignment_m": misalignment_m, "tilt_ignored": tilt_ignored, "mu": mu,
          "preload_n": preload_n, "elements_per_segment": elements_per_segment, "law": law}
    point = {"options": options, "max_order": max_order, "history_revs": history_revs}
    out, prev = {}, None
    for s in block_rpm:
        key = _point_key(prefix, s)
        if key in stored:
            prev = stored[key]
            continue
        out[key] = shooting_point_from(scene, s, prev, kw, point)
        prev = out[key][1]
    return out


def shooting_block_tasks(scene: str, speeds_rpm, *, prefix: str = "rpm", block_speeds: int = BLOCK_SPEEDS,
                         **overrides) -> list:
    """One :class:`sweep.Task` of :func:`run_shooting_block` per ``block_speeds`` contiguous speeds (rpm, sorted
    ascending), each output keyed as :func:`rotor.studies.steady_state.sweep_tasks` (``<prefix><speed>``) with
    the parameters of :func:`rotor.studies.shooting_point.shooting_sweep_tasks` plus ``block_rpm``."""
    from sweep import Task

    params = {k: v for k, v in overrides.items() if v is not None}
    params["scene_sha256"] = task_digest(scene, params)
    speeds = sorted(float(s) for s in speeds_rpm)
    tasks = []
    for i in range(0, len(speeds), int(block_speeds)):
        block = speeds[i:i + int(block_speeds)]
        outputs = tuple((_point_key(prefix, s), {"scene": scene, "speed_rpm": s, **params, "method": "shooting",
                                                 "block_rpm": block}) for s in block)
        tasks.append(Task(f"{_point_key(prefix, block[0])}-{block[-1]:.1f}", run_shooting_block,
                          {"scene": scene, "block_rpm": block, "prefix": prefix, **params, "method": "shooting"},
                          outputs))
    return tasks
