"""The paper's Section 6 (test rig) statements judged on the rig's steady states: agrees / disagrees / no effect.

Dai et al. (2025) §6.2 on the Table 5 rig at the speed steps 3 600 and 5 500 rpm:

* Figs. 25–26: "the trajectories of the test rotor are non-circular at different positions" (:func:`noncircular`);
* Figs. 25–26: "Noticeable harmonic frequencies 2 f, 3 f, 4 f, 5 f ... more pronounced in the response of positions
  near the loose support (disk 2 and 3# bearing)" (:func:`harmonics_near_support`);
* Figs. 25c, 26c: "the amplitudes of the harmonic frequencies are relatively higher at 3600 rpm compared to those at
  5500 rpm" at the 3# bearing (:func:`higher_at_first_step`);
* Fig. 27: at 3 600 rpm 2 f–5 f "increase significantly as the bearing clearance decreases" (0.05 → 0.01 mm;
  :func:`clearance_raises`);
* Fig. 28: at 3 600 rpm 2 f–5 f "show a noticeable increase as the misalignment increases" (1 → 3 mm;
  :func:`misalignment_raises`).

Each judge returns ``(verdict, effect, threshold, text)`` as :meth:`rotor.studies.section5.Finding.judge` does:
the effect is a relative margin or change in the paper's sense (positive agrees), the threshold the model's
numerical noise of it (:func:`rotor.studies.section5.amplitude_noise`: the time step's amplitude error, or a
non-periodic point's spectral floor), the verdict *agrees* beyond it, *disagrees* below minus it, *no effect*
within it. Inputs per point: ``{"A": (3, 5) y-velocity amplitudes of 1X–5X (m/s) at disk 1, disk 2, the
support; "floor": (3, 5) spectral floor (zero when periodic); "orbit": (3,) largest/smallest orbit radius;
"orbit_noise": (3,) relative noise of those radii}``.
"""
from __future__ import annotations

import numpy as np

from rotor.studies.section5 import AGREES, DISAGREES, NO_EFFECT, amplitude_noise

#: "non-circular" orbit: largest/smallest radius at least this (as reports/studies/readings.py NONCIRCULAR_RATIO)
NONCIRCULAR = 1.2
#: "noticeable" harmonics: (2X+…+5X)/1X at least this (as the Section 5 readings' VISIBLE)
NOTICEABLE = 0.05
HARMONICS = (2, 3, 4, 5)
#: the rig's speed steps (rpm), Figs. 25–26 (text: 5 500 rpm; Fig. 26's caption says 5 400)
STEPS_RPM = (3600.0, 5500.0)


def _verdict(e: float, t: float) -> str:
    return AGREES if e > t else DISAGREES if e < -t else NO_EFFECT


def _worst(terms) -> tuple[str, float, float]:
    order = (DISAGREES, NO_EFFECT, AGREES)
    e, t = min(terms, key=lambda et: (order.index(_verdict(*et)), et[0] - et[1]))
    return _verdict(e, t), float(e), float(t)


def _noise(p, loc: int, orders) -> float:
    return amplitude_noise({"noise_rel": p["floor"]}, loc, orders, p["A"])


def _sum(p, loc: int) -> float:
    return float(p["A"][loc, 1:5].sum())


def noncircular(p) -> tuple:
    """Figs. 25–26: largest/smallest orbit radius ≥ :data:`NONCIRCULAR` at disk 1, disk 2 and the support."""
    o, n = np.asarray(p["orbit"], float), np.asarray(p["orbit_noise"], float)
    v = _worst([(o[k] / NONCIRCULAR - 1, 2 * n[k] * o[k] / NONCIRCULAR) for k in range(3)])
    return (*v, "max/min radius " + " / ".join(f"{x:.3g}" for x in o))


def harmonics_near_support(p) -> tuple:
    """Figs. 25–26: (2X+…+5X)/1X ≥ :data:`NOTICEABLE` at disk 2 and the support, and larger there than at disk 1."""
    r = [_sum(p, k) / max(p["A"][k, 0], 1e-300) for k in range(3)]
    n = [_noise(p, k, HARMONICS) + _noise(p, k, (1,)) for k in range(3)]
    terms = [(r[k] / NOTICEABLE - 1, n[k] * r[k] / NOTICEABLE) for k in (1, 2)]
    terms += [(r[k] / max(r[0], 1e-300) - 1, (n[k] + n[0]) * r[k] / max(r[0], 1e-300)) for k in (1, 2)]
    return (*_worst(terms), "(2X+…+5X)/1X " + " / ".join(f"{x:.3g}" for x in r))


def _change(a, b, locs=(1, 2)) -> list:
    """Relative change of the 2X–5X sum from point ``b`` to point ``a`` at ``locs``, with the two points' noise."""
    return [(_sum(a, k) / max(_sum(b, k), 1e-300) - 1, _noise(a, k, HARMONICS) + _noise(b, k, HARMONICS))
            for k in locs]


def _text(a, b, what: str) -> str:
    return (f"2X–5X {what}: disk 2 {_sum(a, 1) * 1e3:.3g} vs {_sum(b, 1) * 1e3:.3g} mm/s, support "
            f"{_sum(a, 2) * 1e3:.3g} vs {_sum(b, 2) * 1e3:.3g} mm/s")


def higher_at_first_step(p3600, p5500) -> tuple:
    """Figs. 25c, 26c: the support's 2X–5X higher at 3 600 than at 5 500 rpm."""
    return (*_worst(_change(p3600, p5500, (2,))), _text(p3600, p5500, "3 600 vs 5 500 rpm"))


def clearance_raises(p001, p005) -> tuple:
    """Fig. 27: at 3 600 rpm 2X–5X at disk 2 and the support higher with δ0 0.01 mm than with 0.05 mm."""
    return (*_worst(_change(p001, p005)), _text(p001, p005, "δ0 0.01 vs 0.05 mm"))


def misalignment_raises(p3, p1) -> tuple:
    """Fig. 28: at 3 600 rpm 2X–5X at disk 2 and the support higher with δ 3 mm than with 1 mm."""
    return (*_worst(_change(p3, p1)), _text(p3, p1, "δ 3 vs 1 mm"))


#: (key, the paper's words, figure) of each statement, in the report's order
STATEMENTS = (
    ("noncircular", "trajectories non-circular at disk 1, disk 2 and the 3# bearing (max/min radius ≥ 1.2)",
     "Figs. 25–26"),
    ("harmonics", "noticeable 2X–5X ((2X+…+5X)/1X ≥ 0.05), more pronounced at disk 2 and the 3# bearing than at "
     "disk 1", "Figs. 25–26"),
    ("first_step", "harmonics at the 3# bearing higher at 3 600 than at 5 500 rpm", "Figs. 25c, 26c"),
    ("clearance", "2X–5X increase significantly as δ0 decreases (0.05 → 0.01 mm), disk 2 and 3# bearing (the paper: "
     "at 3 600 rpm)", "Fig. 27"),
    ("misalignment", "2X–5X increase as δ increases (1 → 3 mm), disk 2 and 3# bearing (the paper: at 3 600 rpm)",
     "Fig. 28"),
)


def judge_rig(points: dict) -> list[tuple]:
    """``[(key, rpm, verdict, effect, threshold, text)]``: every statement at every speed it speaks of.
    ``points`` maps ``(rpm, δ0 mm, δ mm)`` to a point's inputs (module docstring); the base case is Table 5's
    δ0 0.05 mm, δ 2 mm."""
    out = []
    for rpm in STEPS_RPM:
        base = points.get((rpm, 0.05, 2.0))
        if base is not None:
            out.append(("noncircular", rpm, *noncircular(base)))
            out.append(("harmonics", rpm, *harmonics_near_support(base)))
    if (3600.0, 0.05, 2.0) in points and (5500.0, 0.05, 2.0) in points:
        out.append(("first_step", 3600.0, *higher_at_first_step(points[(3600.0, 0.05, 2.0)],
                                                                  points[(5500.0, 0.05, 2.0)])))
    for rpm in STEPS_RPM:
        if (rpm, 0.01, 2.0) in points and (rpm, 0.05, 2.0) in points:
            out.append(("clearance", rpm, *clearance_raises(points[(rpm, 0.01, 2.0)], points[(rpm, 0.05, 2.0)])))
        if (rpm, 0.05, 3.0) in points and (rpm, 0.05, 1.0) in points:
            out.append(("misalignment", rpm, *misalignment_raises(points[(rpm, 0.05, 3.0)],
                                                                  points[(rpm, 0.05, 1.0)])))
    return out
