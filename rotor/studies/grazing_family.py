"""Branches through grazing checked on rotors nobody tuned: the Jeffcott-ring scenes of
:mod:`rotor.periodic.jeffcott_scene` against their closed form, through the same :func:`rotor.studies.orbit.branch`
that ``ringcontact branch`` runs.

:func:`sweep_range` picks a rotor's speed range from its closed form (from below the first grazing to past the
jump-down fold, short of the isolated high-speed contact branch); :func:`check_branch` runs one sweep and
measures it: the bifurcations against the closed-form grazings and folds, the orbits between the fold and the
grazing fold (the middle branch) and their stability, every orbit's distance from the scheme-consistent
closed form, the restarts.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rotor.periodic.branch_types import speed_problem, start_modes
from rotor.periodic.grazing import largest_penetration
from rotor.periodic.jeffcott_scene import (JeffcottRing, closed_form_folds, closed_form_grazing, closed_form_radius,
                                           closed_form_speeds, scene_toml)
from rotor.studies.orbit import branch
from rotor.studies.steady_state import point_system

TO_RPM = 30.0 / math.pi


@dataclass(frozen=True)
class SweepCheck:
    """One sweep of :func:`check_branch` (speeds in rpm).

    Attributes
    ----------
    direction : "up" or "down"; stop : the branch's stop reason; restarts : restarted points.
    expected : closed-form ``(kind, speed_rpm)`` in the range (kinds "grazing", "grazing_fold", "fold").
    found : the branch's ``(kind, speed_rpm)``.
    fold_errors : relative speed error of the reported bifurcation nearest each expected one of its kind (inf
        where none was reported).
    middle_points, middle_unstable : orbits reported between the fold and the grazing fold, and how many of
        them have a multiplier outside the unit circle.
    worst_distance : the largest distance of an orbit from the closed form (relative: the smaller of the
        speed distance at its radius and the radius distance at its speed).
    steps_per_rev : the scheme's steps per revolution (the closed form's warp); cpu_s : process time (s).
    """

    direction: str
    stop: str
    restarts: int
    expected: tuple
    found: tuple
    fold_errors: tuple
    middle_points: int
    middle_unstable: int
    worst_distance: float
    steps_per_rev: int
    cpu_s: float


def main_fold(rotor: JeffcottRing, steps_per_rev: int | None = None) -> tuple[float, float] | None:
    """The jump-down fold ``(speed_rad_s, radius_m)`` of the main response curve: the slower of the two smooth
    folds (the faster one turns the isolated contact branch at high speed); None with fewer than two."""
    folds = sorted(closed_form_folds(rotor, steps_per_rev))
    return folds[0] if len(folds) >= 2 else None


def sweep_range(rotor: JeffcottRing) -> tuple[float, float]:
    """``(low, high)`` speeds (rpm) of a sweep: from 0.8 times the first grazing speed to 1.1 times the main
    fold's, or halfway to the isolated branch's fold if that is nearer (continuous-time closed form)."""
    folds = sorted(closed_form_folds(rotor))
    graze = closed_form_grazing(rotor)
    high = min(1.1 * folds[0][0], 0.5 * (folds[0][0] + folds[1][0]))
    return 0.8 * graze[0][0] * TO_RPM, high * TO_RPM


def expected_events(rotor: JeffcottRing, steps_per_rev: int, low_rpm: float, high_rpm: float) -> tuple:
    """Closed-form ``(kind, speed_rpm)`` of the scheme at ``steps_per_rev`` within the range, ascending."""
    out = [(kind, w * TO_RPM) for w, kind in closed_form_grazing(rotor, steps_per_rev)]
    fold = main_fold(rotor, steps_per_rev)
    if fold is not None:
        out.append(("fold", fold[0] * TO_RPM))
    return tuple(sorted((e for e in out if low_rpm < e[1] < high_rpm), key=lambda e: e[1]))


def orbit_distance(rotor: JeffcottRing, speed_rad_s: float, radius_m: float, steps_per_rev: int) -> float:
    """Relative distance of the orbit ``(Ω, r)`` from the closed-form curve of the scheme: the smaller of
    ``|Ω − Ω_cf(r)|/Ω`` (nearest closed-form speed at the radius) and ``|r − r_cf(Ω)|/r`` (nearest radius)."""
    speeds = closed_form_speeds(rotor, radius_m, steps_per_rev)
    d_speed = float(np.min(np.abs(speeds - speed_rad_s))) / speed_rad_s if len(speeds) else math.inf
    try:
        d_radius = abs(closed_form_radius(rotor, speed_rad_s, radius_m, steps_per_rev) - radius_m) / radius_m
    except ValueError:
        d_radius = math.inf
    return min(d_speed, d_radius)


def _radii(scene: str, result, n: int) -> list[float]:
    """Relative orbit radius (m) of each branch point: δ0 plus its largest penetration (a circular whirl)."""
    def system_at(w):
        return point_system(scene, w * TO_RPM)[2]

    pb = speed_problem(system_at, n, period_revs=result.start.period_revs)
    d0 = system_at(result.branch.points[0].parameter).support.law.clearance_m
    return [d0 * (1.0 + largest_penetration(pb.flow(p.parameter), p.state, n, start_modes(pb, p))[0])
            for p in result.branch.points]


def _middle(result, direction: str) -> list:
    """The branch points between the fold and the grazing fold (the middle branch), in either order."""
    idx = {b["kind"]: b["after_point"] for b in result.bifurcations}
    if "fold" not in idx or "grazing_fold" not in idx:
        return []
    f, g = idx["fold"], idx["grazing_fold"]       # a fold lies before its point, a grazing fold is its point
    return list(result.branch.points[f:g] if direction == "up" else result.branch.points[g + 1:f])


def check_branch(rotor: JeffcottRing, low_rpm: float, high_rpm: float, direction: str, workdir) -> SweepCheck:
    """Run :func:`rotor.studies.orbit.branch` on the rotor's scene (written to ``workdir``) up or down the range
    and measure it against the closed form (:class:`SweepCheck`)."""
    scene = Path(workdir) / "jeffcott-ring.toml"
    scene.write_text(scene_toml(rotor), encoding="utf-8")
    a, b = (low_rpm, high_rpm) if direction == "up" else (high_rpm, low_rpm)
    t0 = time.process_time()
    res = branch(str(scene), a, b, amplitudes=False)
    cpu = time.process_time() - t0
    n = int(res.start.steps_per_rev)
    expected = expected_events(rotor, n, low_rpm, high_rpm)
    found = tuple((bf["kind"], float(bf["speed_rpm"])) for bf in res.bifurcations)
    errors = []
    for kind, speed in expected:
        near = [abs(s - speed) / speed for k, s in found if k == kind]
        errors.append(min(near) if near else math.inf)
    radii = _radii(str(scene), res, n) if res.branch.points else []
    worst = max((orbit_distance(rotor, p.parameter, r, n) for p, r in zip(res.branch.points, radii)), default=math.inf)
    middle = _middle(res, direction)
    restarts = sum(1 for p in res.branch.points if p.restarted)
    return SweepCheck(direction, res.stop, restarts, expected, found, tuple(errors), len(middle),
                      sum(1 for p in middle if not p.floquet.stable), float(worst), n, cpu)
