"""The paper's Section 5 findings (Dai et al. 2025) checked per speed band, on two meshes.

Table 4 rotor, the paper's conformal law as published, the scene's reading of Eq. 34
(rotor/scenes/paper-table4.toml; chosen in reports/published/section5-readings.md), the tilt-ignored case
without any moment between bearing and support (§5.2). Each finding is a predicate on one speed
(rotor/studies/section5.py, the same code that writes reports/published/study-findings.md), checked at
two speeds of each band (edges in ``rotor.studies.section5.BANDS``) on the paper's mesh (one element
per shaft segment, ``paper``) and on the converged mesh (two per segment, ``converged``;
reports/published/rotor-mesh.md). The points are computed as ``ringcontact study cascade`` /
``params`` compute them (:func:`rotor.studies.steady_state.run_point` from rest, 256 steps per
revolution, transient cap 1 500 revolutions), so each test reproduces the published numbers of its speeds.

Where a finding holds in a band the test asserts it at two of the band's periodic speeds. Where it does
not, the test still states the paper's claim at the speeds where it fails and is marked
``xfail(strict=True)`` with the measured numbers and the mechanism where one was measured: it documents
the disagreement and flags (XPASS → failure) the day a model change makes the claim hold.
"""
import numpy as np
import pytest

from rotor.studies.section5 import finding, in_band
from rotor.studies.steady_state import run_point

OPTIONS = {"steps_per_rev": 256, "max_revs": 1500}      # as `ringcontact study` (reports/cli/study.py: _options)
MESHES = {"paper": None, "converged": 2}
CASES = {"base": {}, "notilt": {"tilt_ignored": True}, "c0.03": {"clearance_m": 0.03e-3},
         "c0.08": {"clearance_m": 0.08e-3}, "d0.5": {"misalignment_m": 0.5e-3}, "d2": {"misalignment_m": 2e-3}}
LOC = ("disk1.y", "disk2.y", "s.y")
_CACHE: dict = {}

#: the mechanisms measured behind the failures (numbers in reports/published/study-findings.md)
LAW = ("mechanism: the conformal law's stiffness at the sub-micrometre penetrations reached does not depend on "
       "δ0 (0.05 % apart at 0.1 µm, 0.5 % at 1 µm; tests/rotor/studies/test_section5.py)")
SLIP = "mechanism: the end faces slip (measured per reading in reports/published/section5-readings.md)"


def amplitudes(mesh: str, rpm: float, case: str, quantity: str):
    """``(A (3 stations, 5 orders), info)`` of one point; cached for the module."""
    key = (mesh, rpm, case)
    if key not in _CACHE:
        kw = {k: v for k, v in CASES[case].items()}
        _CACHE[key] = run_point("paper-table4", rpm, options=OPTIONS, elements_per_segment=MESHES[mesh], **kw)
    arrays, info = _CACHE[key]
    cols = [list(arrays["channels"]).index(c) for c in LOC]
    return np.abs(arrays[f"harm_{quantity}"])[:, cols].T, info


def judge(name: str, mesh: str, rpm: float):
    f = finding(name)
    amps = {c: amplitudes(mesh, rpm, c, f.quantity) for c in f.cases}
    for c, (_, info) in amps.items():
        assert info["converged"], f"{mesh} {rpm} rpm {c}: not periodic (the band's speeds are periodic ones)"
    return f.predicate(amps)


def _check(name, mesh, band, speeds, why=None):
    marks = [pytest.mark.slow]
    if why:
        marks.append(pytest.mark.xfail(strict=True, reason=why))
    return pytest.param(name, mesh, band, speeds, marks=marks, id=f"{name}-{mesh}-{band}-{'fails' if why else 'holds'}")


CHECKS = [
]


@pytest.mark.parametrize("name, mesh, band, speeds", CHECKS)
def test_finding_in_band(name, mesh, band, speeds):
    """The finding ``name`` (rotor.studies.section5.FINDINGS: the paper's words) at each of ``speeds``."""
    for rpm in speeds:
        assert in_band(rpm, band)
        ok, text = judge(name, mesh, float(rpm))
        assert ok, f"{name}, {mesh}, {rpm} rpm: {text}"


def test_simulate_steady_at_point_a_shows_2X_highest_at_the_support(tmp_path):
    """The command an engineer types (`simulate --speed-rpm 4500 --steady` on paper-table4), Dai 2025 §5.1,
    Fig. 13: the support's 2X/1X y velocity >= 0.05 and above disk 1's, the steady state periodic, both
    faces stuck (the support moves with the rotor)."""
    import json

    from reports.cli import main

    assert main(["simulate", "--speed-rpm", "4500", "--steady", "--out", str(tmp_path)]) == 0
    s = json.loads((tmp_path / "simulate-summary.json").read_text())
    v = s["velocity_amplitudes_mm_s_1X_to_5X"]
    ratio = {k: v[k][1] / v[k][0] for k in ("disk1.y", "disk2.y", "s.y")}
    assert s["steady_converged"] and s["stick_fraction_right"] == s["stick_fraction_left"] == 1.0
    assert ratio["s.y"] >= 0.05 and ratio["s.y"] > ratio["disk1.y"], ratio   # measured 0.101 vs 0.005


@pytest.mark.slow
def test_a_point_past_the_law_domain_is_recorded_not_failed():
    """Fig. 19's δ = 2 mm at 15 000 rpm on the paper's mesh: the load drives the ring past the conformal law's
    neat-fit limit (D(b) <= 0, Dai et al. 2025 Eq. 5). The point is a measured outcome: no record, NaN
    harmonics, not periodic, the law's message kept (rotor.studies.steady_state.beyond_law_record)."""
    arrays, info = run_point("paper-table4", 15000.0, misalignment_m=2e-3, options=OPTIONS)
    assert "neat-fit" in info["outside_law_domain"] and not info["converged"]
    assert np.isnan(arrays["harm_q"]).all() and arrays["harm_q"].shape == (5, len(arrays["channels"]))
