"""study-findings.md's measured §5.3.2 mechanism (reports/studies/mesh.py: misalignment_lines) on synthetic
params points whose contact shares and amplitudes are set by hand, so that each number of the line is known:
the contact share at δ = 2 mm where 3X does not rise and where it does, at δ = 0.5 mm where 1X moves and where it
holds (rotor.studies.section5: the verdicts of misalignment_1x and misalignment_3x, contact_pattern)."""
from types import SimpleNamespace

import numpy as np

from reports.studies.mesh import misalignment_lines

D0, SPR, REVS = 50e-6, 64, 4
PREFIX = {"d0.5": "d0.5mm-rpm", "base": "base-rpm", "d2": "d2mm-rpm"}


def _point(case, rpm, share, one_x, three_x, converged=True):
    k = np.arange(SPR * REVS) % SPR
    r1 = np.where(k < round(share * SPR), D0 * 1.001, D0 * 0.5)
    harm = np.zeros((5, 3), complex)
    harm[0], harm[2] = one_x, three_x
    arrays = {"channels": np.array(["disk1.y", "disk2.y", "s.y"]), "harm_q": harm, "r1": r1,
              "r2": np.zeros_like(r1), "f_contact": np.zeros((len(r1), 4))}
    info = {"converged": converged, "clearance_m": D0, "samples_per_rev": SPR, "period_revs": 1}
    return SimpleNamespace(key=f"{PREFIX[case]}{rpm:.1f}", params={"speed_rpm": rpm}, info=info, arrays=arrays)


def _speed(rpm, shares, one_x, three_x, converged=True):
    return [_point(c, rpm, s, a, b, converged) for c, s, a, b in zip(PREFIX, shares, one_x, three_x)]


def test_the_line_separates_the_speeds_by_contact_share():
    flat, rising = (10e-6, 10e-6, 10e-6), (10e-6, 12e-6, 15e-6)
    falling, up = (0.2e-6, 0.2e-6, 0.1e-6), (0.1e-6, 0.2e-6, 0.3e-6)
    pts = (_speed(9000.0, (0.6, 0.6, 0.7), flat, falling)           # 1X holds, 3X falls by half from 0.5 to 2 mm
           + _speed(12000.0, (0.2, 0.25, 0.3), rising, up)          # 1X moves 50 %, 3X rises
           + _speed(10200.0, (0.0, 0.0, 0.0), rising, up, converged=False)      # not periodic: left out
           + _speed(15000.0, (0.9, 0.9, 0.9), flat, falling))       # outside band H1: left out
    [line] = misalignment_lines(pts, "test mesh")
    assert "9000 rpm (1X unchanged: agrees; 3X rises: disagrees)" in line
    assert "12000 rpm (1X unchanged: disagrees; 3X rises: agrees)" in line
    assert "10200 rpm" not in line and "15000 rpm" not in line
    assert "impacts/rev 1 / 1 / 1; contact 59 / 59 / 70 %" in line           # round(0.6 * 64) = 38 of 64 samples
    assert "at δ = 2 mm where 3X does not rise (verdict other than agrees): 70–70 %; where it rises: 30–30 %" in line
    assert "at δ = 0.5 mm where 1X moves by more than 10 %: 20–20 %; where it holds: 59–59 %" in line


def test_no_periodic_speed_no_line():
    assert misalignment_lines(_speed(9000.0, (0.5, 0.5, 0.5), (1, 1, 1), (1, 2, 3), converged=False), "m") == []


def test_the_reports_name_the_integrator_options_the_points_recorded():
    """Every study note names the NewmarkOptions its points were computed with (recorded in each point's info by
    rotor/studies/steady_state.py), so that a change of default (locate_events) shows in the published text."""
    import dataclasses

    from reports.studies.common import integrator_text
    from rotor.dynamics.system import NewmarkOptions

    on = dataclasses.asdict(dataclasses.replace(NewmarkOptions(), locate_events=True))
    off = dataclasses.asdict(dataclasses.replace(NewmarkOptions(), locate_events=False))
    assert "locate_events True: friction events (slip reversals, stick onsets, releases) and contact onsets and losses located inside" in integrator_text([{"integrator": on}] * 2)
    assert "contact onsets and losses not located inside" in integrator_text([{"integrator": off}])
    assert "different options" in integrator_text([{"integrator": on}, {"integrator": off}])
    assert "predate the record" in integrator_text([{}], "points computed at commit abc") and "abc" in \
        integrator_text([{}], "points computed at commit abc")
