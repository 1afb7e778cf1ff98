"""One sweep point by shooting: the periodic orbit, its Floquet stability, and the arrays of a transient point.

:func:`run_shooting_point` is the ``--method shooting`` counterpart of
:func:`rotor.studies.steady_state.run_point`: the periodic orbit of the operating point is found by Newton
shooting on the production scheme's period map (:func:`rotor.studies.orbit.orbit`), one period of it is
recorded at every time step and repeated to the same whole number of revolutions as the transient record
(``spectrum_revs`` rounded up to whole periods; a periodic orbit repeats exactly, to the Newton residual),
and the same arrays and info fields are built from it (:func:`rotor.studies.steady_state.point_record`), so
every figure and export of a study reads either method. Added to the info: the Floquet multipliers, the
stability and the kind of the critical multiplier (:mod:`rotor.periodic.floquet`), and a classification.

Classification (``info["classification"]``, and ``info["classified_by"]`` says how it was reached):

* shooting converged (``classified_by = "multipliers"``): ``periodic`` (stable orbit), or, for an unstable
  orbit, the way its largest multiplier lies outside the unit circle: ``quasi_periodic`` (a complex pair:
  Neimark–Sacker, the motion settles on a torus), ``period_doubling`` (a real multiplier below −1) or
  ``unstable_fold`` (a real multiplier above +1). The arrays are those of the orbit, stable or not.
* shooting did not converge (``classified_by = "transient fallback"``): the point is computed by the
  transient (:func:`rotor.studies.steady_state.run_point`, arrays and info as with ``--method transient``)
  and classified by it: ``periodic`` (the Poincaré section converged with some period) or ``non_periodic``
  (it did not within ``max_revs``). The last Newton iterate's multipliers are kept for the record, marked
  as not those of an orbit.

A point at zero speed has no dynamics: it is the transient's static point, ``classified_by = "static"``.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from rotor.dynamics import constraints as cons
from rotor.studies.orbit import orbit
from rotor.periodic.period_flow import make_flow, record
from rotor.studies.steady_state import (Convergence, SteadyResult, SteadyStateOptions, point_record, point_system,
                                        run_point, step_per_rev)

METHODS = ("transient", "shooting")


def classify(floquet) -> str:
    """``periodic`` for a stable orbit, else by its critical (largest non-neutral) multiplier: a complex pair,
    ``quasi_periodic``; real below −1, ``period_doubling``; real above +1, ``unstable_fold``."""
    if floquet.stable:
        return "periodic"
    return {"neimark_sacker": "quasi_periodic", "period_doubling": "period_doubling"}.get(floquet.kind,
                                                                                           "unstable_fold")


def floquet_info(res) -> dict:
    """The Floquet fields of a shooting point's info (multipliers as ``[re, im]``, largest first)."""
    f = res.floquet
    return {"multipliers": [[float(m.real), float(m.imag)] for m in f.multipliers[:12]],
            "stable": bool(f.stable), "spectral_radius": float(f.spectral_radius), "critical_kind": f.kind,
            "leading_multiplier": f.leading,
            "neutral_multipliers": int(f.n_neutral), "newton_iterations": int(res.newton_iterations),
            "shooting_residual": float(res.residual), "shooting_converged": bool(res.converged),
            "shooting_period_revs": int(res.period_revs), "shooting_wall_s": float(res.wall_s)}


def orbit_record(system, model, res, opts: SteadyStateOptions) -> SteadyResult:
    """The steady record of a converged orbit: one period at every step from its phase-0 state, repeated to
    ``spectrum_revs`` rounded up to whole periods (channels: ``model.response_stations()``)."""
    sh = res.shooting
    n = res.steps_per_rev
    flow = make_flow(system, 2.0 * math.pi / (system.omega_rad_s * n), res.backend)
    tr = record(flow, sh.state, sh.t0_s, res.period_revs * n, sh.modes, 1)
    reps = int(math.ceil(opts.spectrum_revs / res.period_revs))
    channels = tuple(f"{s}.{c}" for s in model.response_stations() for c in ("y", "z"))
    idx = [model.dof_index(c) for c in channels]
    sl = slice(0, -1)               # one period: the last sample starts the next one

    def tile(x):
        return np.concatenate([x[sl]] * reps, axis=0)

    u = tile(tr.u)
    width = system.support.width_m if system.support is not None else 0.0
    r1, r2 = cons.edge_offsets(u, width) if system.support is not None else (np.zeros(len(u)),) * 2
    d0 = system.support.law.clearance_m if system.support is not None else math.inf
    t = sh.t0_s + np.arange(len(u)) * flow.dt_s
    return SteadyResult(float(system.omega_rad_s), channels, t, tile(tr.q)[:, idx], tile(tr.v)[:, idx], u, r1, r2,
                        tile(tr.modes).astype(np.int8), tile(tr.f_contact), reps * res.period_revs, n, n,
                        int(res.transient_revs), Convergence(True, res.period_revs, res.residual, 0.0, 0.0), d0,
                        int(tr.unconverged_steps), res.wall_s, False, tile(tr.q), tr.q[-1].copy(), tr.v[-1].copy(),
                        system.support.faces()[2] if system.support is not None else 0)


def run_shooting_point(scene: str, speed_rpm: float, clearance_m: float | None = None,
                       misalignment_m: float | None = None, tilt_ignored: bool = False, mu: float | None = None,
                       preload_n: float | None = None, options: dict | None = None, max_order: float = 6.0,
                       history_revs: int = 4, elements_per_segment: int | None = None, method: str = "shooting",
                       fallback: bool = True, law: str | None = None, scene_sha256: str | None = None):
    """Steady state of one operating point by shooting, as ``(arrays, info)`` for :func:`sweep.run_sweep`
    (the arrays of :func:`rotor.studies.steady_state.run_point`; the info adds the Floquet fields and the
    classification of the module docstring). ``method`` is stored in the task's parameters so that a study
    directory computed by the transient is not reused for shooting; it must be "shooting". ``fallback``
    False: no transient where shooting fails (the point keeps the last Newton iterate's Floquet fields,
    ``classification = "no_orbit_found"``, and no arrays beyond ``channels``: for timing the shooting alone)."""
    if method != "shooting":
        raise ValueError(f"method = {method!r}: run_shooting_point computes 'shooting' points")
    check_task_digest(scene_sha256, scene, elements_per_segment, law, f"shooting point at {speed_rpm:g} rpm")
    t_start = time.perf_counter()
    kw = {"clearance_m": clearance_m, "misalignment_m": misalignment_m, "tilt_ignored": tilt_ignored, "mu": mu,
          "preload_n": preload_n, "elements_per_segment": elements_per_segment, "law": law}
    point = {"options": options, "max_order": max_order, "history_revs": history_revs}
    if float(speed_rpm) == 0.0:
        arrays, info = run_point(scene, speed_rpm, **kw, **point)
        return arrays, {**info, "method": "shooting", "classification": "static", "classified_by": "static"}
    opts = SteadyStateOptions(**(options or {}))
    system = point_system(scene, speed_rpm, **kw)[2]
    res = orbit(scene, speed_rpm, steps_per_rev=step_per_rev(system, opts), **kw)
    return orbit_point(res, scene, speed_rpm, kw, point, fallback, t_start)


def orbit_point(res, scene: str, speed_rpm: float, kw: dict, point: dict, fallback: bool, t_start: float):
    """``(arrays, info)`` of a shooting point from its :class:`rotor.studies.orbit.OrbitResult` ``res``
    (:func:`run_shooting_point`; ``kw``: the scene overrides, ``point``: ``options``, ``max_order``,
    ``history_revs``; ``t_start``: :func:`time.perf_counter` when the point began)."""
    opts = SteadyStateOptions(**(point["options"] or {}))
    sc, model, system = point_system(scene, speed_rpm, **kw)
    fl = floquet_info(res)
    if not res.converged and not fallback:
        return {"channels": np.array([])}, {"speed_rpm": float(speed_rpm), "converged": False, **fl,
                                            "multipliers_note": "last Newton iterate, not an orbit",
                                            "method": "shooting", "classified_by": "none",
                                            "classification": "no_orbit_found", "wall_s": time.perf_counter() - t_start}
    if not res.converged:
        arrays, info = run_point(scene, speed_rpm, **kw, **point)
        fl["multipliers_note"] = "last Newton iterate, not an orbit"
        return arrays, {**info, **fl, "method": "shooting", "classified_by": "transient fallback",
                        "classification": "periodic" if info["converged"] else "non_periodic",
                        "wall_s": time.perf_counter() - t_start}
    ss = orbit_record(system, model, res, opts)
    arrays, info = point_record(replace(ss, wall_s=time.perf_counter() - t_start), sc, model, system, opts,
                                speed_rpm=speed_rpm, misalignment_m=kw["misalignment_m"],
                                tilt_ignored=kw["tilt_ignored"], max_order=point["max_order"],
                                history_revs=point["history_revs"], elements_per_segment=kw["elements_per_segment"])
    info.update({**fl, "method": "shooting", "classified_by": "multipliers", "classification": classify(res.floquet)})
    return arrays, info


def shooting_sweep_tasks(scene: str, speeds_rpm, *, prefix: str = "rpm", **overrides) -> list:
    """One :class:`sweep.Task` of :func:`run_shooting_point` per speed (rpm), keys as
    :func:`rotor.studies.steady_state.sweep_tasks`, params with the resolved scene's digest."""
    from sweep import Task

    params = {k: v for k, v in overrides.items() if v is not None}
    params["scene_sha256"] = task_digest(scene, params)
    return [Task(f"{prefix}{float(s):.1f}", run_shooting_point,
                 {"scene": scene, "speed_rpm": float(s), **params, "method": "shooting"}) for s in speeds_rpm]


def task_digest(scene: str, overrides: dict) -> str:
    """The resolved scene's digest of a study task (rotor/studies/scene_digest.py): the scene with its mesh and
    law overrides, as the point builds it."""
    from rotor.studies.scene_digest import scene_digest
    from rotor.studies.steady_state import _scene_model

    e = overrides.get("elements_per_segment")
    return scene_digest(_scene_model(scene, e, overrides.get("law"))[0], e)


def check_task_digest(expected: str | None, scene: str, elements_per_segment, law, what: str) -> None:
    """Refuse a shooting point whose scene changed since its task was made (as run_point does)."""
    if expected is None:
        return
    from rotor.studies.scene_digest import check_digest
    from rotor.studies.steady_state import _scene_model

    check_digest(expected, _scene_model(scene, elements_per_segment, law)[0], elements_per_segment, what=what)
