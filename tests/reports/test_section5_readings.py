"""Point B under the readings of Eq. 34, judged by the paper's text of Figs. 13–15 (reports.studies.readings).

Sources: Dai et al. (2025) §5.1: at point B (10 500 rpm) r1, r2 "fluctuate periodically within a certain
range near clearance δ0, indicating that there is periodic contact and separation"; orbits
"non-circular"; 2X and "noticeable" 3X–5X, more pronounced near the loose support. Issue 25's audit
measured, on the paper's mesh, 100 % contact and r1 never below δ0 for `inertial-at-joint` and 55 % /
45 % contact / separation for the opposed pair with m_sp L² ×22.
"""
import numpy as np
import pytest

from reports.studies.readings import STATEMENTS, STATEMENTS_A, judge, judge_a
from rotor.studies.readings import CONTROL, READING_NAMES, reading, reading_scene, scene_reading


def _measures(**over):
    m = {"contact_share": 0.5, "stick_share": 0.0, "r1_min_over_d0": 0.9, "r1_max_over_d0": 1.02,
         "r2_min_over_d0": 0.95, "r2_max_over_d0": 1.01, "orbit_ratio": np.array([1.3, 1.7, 1.9]),
         "disk2_radius_um": (5.8, 9.8), "v2_over_v1": np.array([0.1, 0.5, 0.6]),
         "v35_over_v1": np.array([0.01, 0.06, 0.08]), "largest_order": np.array([1, 1, 1])}
    m.update(over)
    return m


def test_point_b_rows_tell_constant_contact_from_contact_and_separation():
    assert all(ok for _, ok in judge(_measures()))
    rows = judge(_measures(contact_share=1.0, r1_min_over_d0=1.0, r2_max_over_d0=0.984))
    assert [ok for _, ok in rows][:2] == [False, False]          # 100 % contact, r2 never reaches δ0
    assert len(judge(_measures())) == len(STATEMENTS)


def test_point_a_rows():
    a = judge_a(_measures(orbit_ratio=np.array([1.0, 1.04, 1.1]), stick_share=1.0,
                          v2_over_v1=np.array([0.005, 0.04, 0.101])))
    assert all(ok for _, ok in a) and len(a) == len(STATEMENTS_A)
    assert not judge_a(_measures(largest_order=np.array([1, 2, 2])))[2][1]     # 2X above 1X: not "dominated by f"


def test_readings_put_their_placement_and_sleeve_on_the_scene():
    from rotor.model.scene import load_scene
    sc = load_scene("paper-table4")
    for name in READING_NAMES:
        r, s = reading(name), reading_scene(sc, name)
        assert scene_reading(s) == name and s.misalignment.excitation == r.excitation
    ctrl = reading_scene(sc, CONTROL.name)          # the control: no Eq. 34 excitation, never a scene's reading
    assert scene_reading(ctrl) is None and ctrl.couplings[0].shaft_mass_kg == 0.0
    assert reading("opposed-at-joint-long-sleeve").moment_factor == pytest.approx(25.2 * 0.21 ** 2 / (9 * 0.075 ** 2))


@pytest.mark.slow
def test_point_b_contact_and_separation_only_with_the_default_reading():
    """~25 s: the default (opposed pair, 420 mm sleeve) separates part of the time and r1, r2 cross δ0; the
    former default (inertial-at-joint, 150 mm sleeve) stays in contact the whole record on the paper's mesh."""
    from reports.studies.readings import point_measures
    from rotor.studies.readings import run_reading_point

    class P:
        def __init__(self, name):
            self.arrays, self.info = run_reading_point("paper-table4", name, 10500.0,
                                                       options={"steps_per_rev": 256, "max_revs": 1500})
            self.params = {"reading_name": name, "speed_rpm": 10500.0}
    new, old = (judge(point_measures(P(n))) for n in ("opposed-at-joint-long-sleeve", "inertial-at-joint"))
    assert new[0][1] and new[1][1], new[:2]                   # measured 56 % contact, r1/δ0 0.973-1.015
    assert not old[0][1] and not old[1][1], old[:2]           # measured 100 % contact, r2/δ0 0.984 throughout


def test_a_point_beyond_the_law_domain_meets_no_row():
    """A reading whose load drives the ring past the conformal law's neat-fit limit has no record: every
    row is unmet, and the report says why (rotor.studies.readings.run_reading_point)."""
    from reports.studies.readings import BEYOND, readings_table

    class P:
        params = {"reading_name": "inertial-at-joint-long-sleeve", "speed_rpm": 10500.0}
        info = {"outside_law_domain": "loose support: penetration beyond the conformal law's neat-fit limit"}
    (m, rows, judged), = readings_table([P()]).values()
    assert m is None and rows == [(BEYOND, False)] * len(STATEMENTS)
    assert sorted(judged) == [f"B{i + 1}" for i in range(len(STATEMENTS))]
    assert all(v == "fails" and np.isnan(e) for v, e, _ in judged.values())
