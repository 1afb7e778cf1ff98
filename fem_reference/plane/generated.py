"""Ring pairs nobody tuned: a seeded generator and the check of the error-driven bars on them (issue 37).

:func:`draw_pair` draws one 2D pair: ring inner radius 30-100 mm, its thickness 6-20 % of that radius,
housing thickness 0.6-2.5 times the ring's, clearance 0.01-0.06 mm, ring modulus 190-215 GPa and the
housing's 0.3-3 times it (log-uniform), Poisson ratios 0.27-0.31 and 0.25-0.34, width 10-40 mm, every 2D
hold and drive and both plane assumptions, and two penetrations spanning the range, log-uniform in
0.2-0.7 and 0.7-2 clearances.

:func:`check_pair` solves each penetration on the error-driven levels (:func:`fem_reference.plane.adapt.
adaptive_point`) and on the independent reference (:func:`fem_reference.plane.uniform_reference.
uniform_reference`: linear triangles on nested uniform refinements, the thinner ring's thickness / 2
first), and says whether the difference is within the stated bar.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fem_reference.plane.adapt import AdaptiveResult, adaptive_point
from fem_reference.plane.geometry import Material, RingPair
from fem_reference.plane.uniform_reference import UniformReference, uniform_reference
from fem_reference.scenes import BEARING_DRIVES, SUPPORT_HOLDS, Scene

HOLDS_2D = tuple(h for h in SUPPORT_HOLDS if "axially" not in h)
DRIVES_2D = tuple(d for d in BEARING_DRIVES if "axially" not in d)
MAX_REFERENCE_DOFS = 800_000        # no further reference level past this many DOFs (its memory: check_pair)
MAX_REFERENCE_LEVELS = 6             # the reference's levels at most
REFERENCE_H0_PER_THICKNESS = 2.0     # the reference's first mesh: the thinner ring's thickness / 2


def draw_pair(rng: np.random.Generator, index: int) -> tuple[Scene, tuple[float, float]]:
    """One generated 2D pair (SI) and its two penetrations [m] (module docstring)."""
    ri = rng.uniform(30e-3, 100e-3)
    t_b = ri * rng.uniform(0.06, 0.2)
    c = rng.uniform(0.01e-3, 0.06e-3)
    t_s = t_b * rng.uniform(0.6, 2.5)
    e_b = rng.uniform(190e9, 215e9)
    e_s = e_b * math.exp(rng.uniform(math.log(0.3), math.log(3.0)))
    rings = RingPair(ri, ri + t_b, c, ri + t_b + c + t_s, rng.uniform(10e-3, 40e-3),
                     Material(e_b, rng.uniform(0.27, 0.31)), Material(e_s, rng.uniform(0.25, 0.34)))
    hold = str(rng.choice(HOLDS_2D))
    drive = str(rng.choice(DRIVES_2D))
    plane = str(rng.choice(["strain", "stress"]))
    low = c * math.exp(rng.uniform(math.log(0.2), math.log(0.7)))
    high = c * math.exp(rng.uniform(math.log(0.7), math.log(2.0)))
    return Scene(f"generated-{index}", rings, plane, drive, hold, "generated (fem_reference.plane.generated)"), (low, high)


def thinner_thickness_m(scene: Scene) -> float:
    """The thinner of the two rings' radial thicknesses [m]."""
    r = scene.rings
    return min(r.outer_radius_m - r.inner_radius_m, r.support_outer_radius_m - r.bore_radius_m)


@dataclass(frozen=True)
class PointCheck:
    """One penetration's error-driven force and bar against the independent reference.

    Attributes
    ----------
    penetration_m : float
        [m].
    adaptive : AdaptiveResult
        The error-driven levels and their bar (``adaptive.bar``).
    reference : UniformReference
        The P1 reference on nested uniform refinements.
    difference_rel : float
        ``F_adaptive / F_reference − 1`` [-].
    verdict : str
        ``"within"``, ``"outside"`` or ``"refused"`` (no bar given).
    """

    penetration_m: float
    adaptive: AdaptiveResult
    reference: UniformReference
    difference_rel: float
    verdict: str


def check_pair(scene: Scene, penetrations_m, *, reference_levels: int = 4,
               max_reference_levels: int = MAX_REFERENCE_LEVELS,
               reference_h0_per_thickness: float = REFERENCE_H0_PER_THICKNESS, adaptive_levels: int = 3,
               extra_levels: int = 2) -> tuple[PointCheck, ...]:
    """Each penetration [m] of ``scene``: error-driven force and bar against the reference (module docstring).

    ``reference_levels``: the reference's levels (the first at the thinner ring's thickness /
    ``reference_h0_per_thickness``, each refinement halving it); more (up to ``max_reference_levels``) while a
    reference's own uncertainty exceeds half the bar it checks and the next level stays within
    ``MAX_REFERENCE_DOFS``: a level's memory, not its time, is the limit (seed 627535865's pair 18: its fifth
    level, 468k DOFs, took 59 s for both penetrations and 4.8 GB; its sixth, 1.87M DOFs, passed 11.6 GB while
    being built, and two benchmark workers share the machine). ``adaptive_levels`` and ``extra_levels``: as
    :func:`adaptive_point`'s ``n_levels`` and ``extra_levels``.
    """
    h0 = thinner_thickness_m(scene) / reference_h0_per_thickness
    adaptive = [adaptive_point(scene, dr, n_levels=adaptive_levels, extra_levels=extra_levels) for dr in penetrations_m]
    refs = uniform_reference(
        scene, penetrations_m, h0, reference_levels, max_levels=max_reference_levels, max_dofs=MAX_REFERENCE_DOFS,
        more=lambda refs: any(a.bar.given and r.uncertainty_rel > a.bar.error_rel / 2 for a, r in zip(adaptive, refs)))
    out = []
    for dr, ref, a in zip(penetrations_m, refs, adaptive):
        diff = a.bar.force_n / ref.force_n - 1.0
        verdict = "refused" if not a.bar.given else ("within" if abs(diff) <= a.bar.error_rel else "outside")
        out.append(PointCheck(float(dr), a, ref, float(diff), verdict))
    return tuple(out)
