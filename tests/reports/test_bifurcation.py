"""The bifurcation diagram's drawing rules (reports/bifurcation.py): stable solid, unstable dashed, kinds marked."""
from __future__ import annotations

from reports.bifurcation import bifurcation_figure, branch_curve, stability_runs


def test_runs_of_equal_stability_share_their_end_points():
    assert stability_runs([True, True, False, False, True]) == [(0, 2, True), (2, 4, False), (4, 4, True)]
    assert stability_runs([False]) == [(0, 0, False)]


def _branch():
    pts = [{"speed_rpm": 1000.0 + 100 * i, "stable": i < 3, "spectral_radius": 0.9 + 0.05 * i,
            "critical_kind": "period_doubling", "velocity_amplitudes_mm_s_1X_to_5X": {"d.y": [1.0 + i, 0, 0, 0, 0]}}
           for i in range(5)]
    return {"scene": "synthetic", "period_revs": 1, "points": pts,
            "bifurcations": [{"kind": "period_doubling", "speed_rpm": 1250.0, "after_point": 3}]}


def test_curve_reads_the_requested_channel_and_order():
    rpm, amp, rad, stable = branch_curve(_branch(), "d.y", 1)
    assert list(rpm) == [1000, 1100, 1200, 1300, 1400] and list(amp) == [1, 2, 3, 4, 5]
    assert list(stable) == [True, True, True, False, False]


def test_figure_is_written_with_the_kind_in_it(tmp_path):
    files = bifurcation_figure(_branch(), "d.y", tmp_path / "bif")
    assert [f.suffix for f in files] == [".png", ".svg"]
    svg = (tmp_path / "bif.svg").read_text()
    assert "period doubling" in svg and "1250 rpm" in svg and "unstable" in svg


def test_segments_are_drawn_together(tmp_path):
    b1, b2 = _branch(), _branch()
    b2["points"] = [dict(p, speed_rpm=p["speed_rpm"] + 5000) for p in b2["points"]]
    b2["bifurcations"] = [{"kind": "neimark_sacker", "speed_rpm": 6250.0, "after_point": 3}]
    bifurcation_figure([b1, b2, {"points": [], "bifurcations": []}], "d.y", tmp_path / "two")
    svg = (tmp_path / "two.svg").read_text()
    assert "period doubling" in svg and "Neimark" in svg and "6250 rpm" in svg


def test_publish_writes_the_report_with_each_segment(tmp_path):
    import json

    from reports.bifurcation import publish

    b = dict(_branch(), rpm_start=1000.0, rpm_end=2000.0, stop="step below ds_min")
    empty = {"points": [], "bifurcations": [], "rpm_start": 300.0, "rpm_end": 900.0, "stop": "no orbit at the start"}
    files = publish([b, empty], tmp_path, channel="d.y", commands=["ringcontact branch x"], reading="Reading.")
    assert {f.name for f in files} >= {"study-bifurcation.md", "study-bifurcation.json", "study-bifurcation.png"}
    md = (tmp_path / "study-bifurcation.md").read_text()
    assert "| 1000 | 1400 | 2000 | 5 | 3/5 | 1.1000 | period doubling 1250 | step below ds_min |" in md
    assert "| 300 | – | 900 | 0 |" in md and md.rstrip().endswith("Reading.")
    data = json.loads((tmp_path / "study-bifurcation.json").read_text())
    assert data[0]["points"][4]["velocity_amplitudes_mm_s_1X_to_5X_d.y"] == [5.0, 0, 0, 0, 0]


def test_segments_table_counts_restarts_when_the_segments_carry_them():
    """The restart column appears only with ``restarts`` in the segments, one count per kind."""
    from reports.bifurcation import segments_table

    seg = {"rpm_start": 600.0, "rpm_end": 18000.0, "stop": "max_points", "bifurcations": [],
           "points": [{"speed_rpm": 600.0, "stable": True, "spectral_radius": 0.7},
                      {"speed_rpm": 650.0, "stable": True, "spectral_radius": 0.8}]}
    plain = segments_table([seg])
    assert "restarts" not in plain and plain.splitlines()[2].count("|") == 9
    table = segments_table([{**seg, "restarts": {"secant": 1, "transient": 4, "cold": 0, "step-grid": 2}}])
    assert "restarts past switches" in table.splitlines()[0] and "| 1/4/0/2 |" in table.splitlines()[2]
    assert table.splitlines()[2].count("|") == 10


def test_one_run_report_lists_each_restart_with_its_reason_and_discontinuous_bifurcations(tmp_path):
    """A single branch (no hand-started segments): the report says so and lists every restart (speeds skipped,
    how shot, why) and each bifurcation with its detail."""
    from reports.bifurcation import publish

    b = dict(_branch(), rpm_start=1000.0, rpm_end=1400.0, stop="end reached")
    b["points"][2] = dict(b["points"][2], restarted="secant", skipped_rpm=[1100.0, 1200.0],
                          restart_reason="3 corrector failures, last: no convergence")
    b["bifurcations"] = [{"kind": "discontinuous", "speed_rpm": 1250.0, "after_point": 3,
                          "detail": "period doubling: largest |multiplier| 0.98 -> 1.2, switches per period 4 -> 6"}]
    publish([b], tmp_path, channel="d.y", commands=["ringcontact branch x"])
    md = (tmp_path / "study-bifurcation.md").read_text()
    assert "in one run from its first speed" in md and "segments started" not in md
    assert "| 1100.0 – 1200.0 | secant | 3 corrector failures, last: no convergence |" in md
    assert "| discontinuous | 1250.0 | period doubling: largest |multiplier| 0.98 -> 1.2" in md
    assert "discontinuous (at a switch)" in (tmp_path / "study-bifurcation.svg").read_text()


def test_publish_draws_each_channel_in_its_own_panel_the_first_on_top(tmp_path):
    """The published diagram: the loose support's channel on top, disk 1 below it (reports/bifurcation.py
    PUBLISHED_CHANNELS); the JSON keeps both channels' amplitudes, the report names both."""
    import json

    from reports.bifurcation import PUBLISHED_CHANNELS, publish

    b = dict(_branch(), rpm_start=1000.0, rpm_end=1400.0, stop="end reached")
    b["points"] = [dict(p, velocity_amplitudes_mm_s_1X_to_5X={"s.y": [10.0 * (i + 1), 0, 0, 0, 0],
                                                              "disk1.y": [1.0 + i, 0, 0, 0, 0], "x.y": [0] * 5})
                   for i, p in enumerate(b["points"])]
    assert PUBLISHED_CHANNELS[0] == "s.y"
    publish([b], tmp_path, commands=["ringcontact branch x"])
    data = json.loads((tmp_path / "study-bifurcation.json").read_text())
    p4 = data[0]["points"][4]
    assert p4["velocity_amplitudes_mm_s_1X_to_5X_s.y"] == [50.0, 0, 0, 0, 0]
    assert p4["velocity_amplitudes_mm_s_1X_to_5X_disk1.y"] == [5.0, 0, 0, 0, 0]
    assert not any("x.y" in k for k in p4)
    md = (tmp_path / "study-bifurcation.md").read_text()
    assert "1X velocity amplitude at the loose support (s.y" in md and "and at disk 1 (disk1.y)" in md
    svg = (tmp_path / "study-bifurcation.svg").read_text()
    assert svg.index("at the loose support") < svg.index("at disk 1")
