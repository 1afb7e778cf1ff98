"""The path a branch will follow, predicted before it starts: its scaled arclength and where it grazes.

For the work estimate of ``ringcontact branch`` (:func:`reports.cli._budget.orbit`). The scaled arclength is the
parameter's 10 speed scales plus the state's change where the linear periodic solution with the loose support
locked moves (:func:`rotor.dynamics.initial.linear_initial_state`), in the orbit's own scales, as
:func:`rotor.periodic.corrector.rescale` keeps them. The grazings are where the linear periodic solution with the
support free (no contact force: the rotor's orbit until it touches) reaches the clearance: the largest radial
displacement of the bearing relative to its support over the period, against the contact law's clearance. For a
Jeffcott rotor in a ring that is the closed-form grazing condition (the free orbit is a circle whose radius is the
linear whirl amplitude; rotor/periodic/jeffcott_scene.py); on other rotors the nonlinear orbit may touch a little
earlier or later. A stretch that touches between two grazings (or between a grazing and an end of the range) is
where :func:`rotor.periodic.grazing.continue_through_grazing` follows a contact branch, a new segment after each
grazing; a range that touches throughout (gravity or misalignment holding the ring against its support) has no
grazing and is counted as one smooth segment.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: phases of the period at which the linear orbits are sampled
PHASES = 16


@dataclass(frozen=True)
class BranchPath:
    """The predicted path of a branch.

    Attributes
    ----------
    segments : tuple of (float, bool)
        Each segment's scaled arclength [-], and whether it is a contact stretch between grazings.
    grazing_rpm : tuple of float
        Predicted grazing speeds, in the order the branch meets them [rpm].
    deepest_rpm : float or None
        The sampled speed of a contact stretch where the free orbit reaches farthest past the clearance [rpm]
        (where a probe sees the contact branch's step cost); None without a contact stretch.
    """

    segments: tuple
    grazing_rpm: tuple
    deepest_rpm: float | None

    @property
    def total(self) -> float:
        """The whole scaled arclength [-]."""
        return float(sum(p for p, _ in self.segments))


def _sample(system, phases: int = PHASES):
    """``(state, ranges, reach)`` of the linear orbits at one speed: the locked orbit's state at phase 0, its
    peak-to-peak ranges (displacements, velocities; m, m/s), and the free orbit's largest radial excursion over
    the clearance [-] (NaN without a loose support)."""
    from rotor.dynamics.initial import linear_initial_state

    period = 2.0 * np.pi / system.omega_rad_s
    qv = [np.concatenate(linear_initial_state(system, period * j / 8)) for j in range(8)]
    n = system.n
    ptp = np.ptp(np.array(qv), axis=0)
    ranges = np.concatenate([np.full(n, max(ptp[:n].max(), 1e-12)), np.full(n, max(ptp[n:].max(), 1e-12))])
    reach = float("nan")
    sup = system.support
    if sup is not None and sup.law.clearance_m > 0.0:
        R = sup.relative_map(n)[:2]
        radius = max(np.linalg.norm(R @ (linear_initial_state(system, period * j / phases, lock_support=False)[0]
                                         - system.offset)) for j in range(phases))
        reach = radius / sup.law.clearance_m
    return qv[0], ranges, reach


def branch_path(system_at_rpm, rpm_start: float, rpm_end: float, samples: int = 17) -> BranchPath:
    """The predicted path (module docstring) from ``samples`` speeds evenly over ``rpm_start`` → ``rpm_end``;
    ``system_at_rpm(rpm)`` builds the rotor system at a speed. A grazing lies between two samples on either side
    of the clearance, placed by linear interpolation of the reach; the interval's arclength is split there."""
    rpms = np.linspace(rpm_start, rpm_end, samples)
    states, ranges, reach = zip(*(_sample(system_at_rpm(float(r))) for r in rpms))
    floor = ranges[0]
    touches = [bool(x > 1.0) for x in reach]          # NaN (no support): never
    segments, grazings, current = [], [], 0.0
    for i in range(samples - 1):
        piece = float(np.hypot(10.0 / (samples - 1),
                               np.linalg.norm((states[i + 1] - states[i]) / np.maximum(ranges[i + 1], floor))))
        if touches[i] == touches[i + 1]:
            current += piece
            continue
        f = (1.0 - reach[i]) / (reach[i + 1] - reach[i])
        grazings.append(float(rpms[i] + f * (rpms[i + 1] - rpms[i])))
        segments.append([current + f * piece, touches[i]])
        current = (1.0 - f) * piece
    segments.append([current, touches[-1]])
    if not grazings:                                  # touching throughout, or never: one smooth segment
        segments = [[segments[0][0], False]]
    stretch = [i for i in range(samples) if touches[i]] if grazings else []
    deepest = float(rpms[max(stretch, key=lambda i: reach[i])]) if stretch else None
    return BranchPath(tuple((float(p), bool(c)) for p, c in segments), tuple(grazings), deepest)
