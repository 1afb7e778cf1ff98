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
         "c0.08": {"clearance_m": 0.08e-3}, "d0.5": {"misalignment_m": 0.5e-3}, "d2": {"misalignment_m": 2e-3},
         "d0": {"misalignment_m": 1e-7}}                 # δ = 0.1 µm: the unbalance alone, for the mechanisms
LOC = ("disk1.y", "disk2.y", "s.y")
_CACHE: dict = {}

#: the mechanisms measured behind the failures (numbers in reports/published/study-findings.md). MIS3 and MIS1 quote the
#: run with the plain step (locate_events False); with events located their thresholds are re-checked at the same
#: speeds by test_misalignment_3x_stops_rising_where_the_contact_saturates and
#: test_misalignment_1x_moves_where_the_contact_is_not_yet_established, and the periodic speeds left in 9 000-12 000
#: rpm are in study-findings.md's "Mechanisms measured"
LAW = ("mechanism, where 2X/3X barely move with δ0: the conformal law's stiffness at the penetrations reached "
       "(median 3.4 µm, deepest 9.0 µm at the high-speed points on the paper's mesh) differs between the three "
       "clearances by 1.6 % and 3.9 % (0.5 % at 1 µm; tests/rotor/studies/test_section5.py); a change against "
       "the paper's sense is not explained by it")
MIS3 = ("mechanism: 3X stops rising with δ where the ring is on the bore most of the revolution at δ = 2 mm: "
        "contact share there 64-76 % at the five failing periodic speeds of 9 000-12 000 rpm (paper's mesh 9 000, 10 200, "
        "10 800; converged 9 000, 9 600 rpm) against 29-47 % at the two where 3X rises (paper's mesh 12 000, converged "
        "10 200); the contact-force 3X then peaks at δ = 1 mm (paper's mesh 9 000 rpm: 45 / 278 / 121 N, 1 / 2 / 1 "
        "impacts per revolution); there is no contact without misalignment (δ = 0.1 µm: max r/δ0 <= 0.09) "
        "(test_misalignment_3x_stops_rising_where_the_contact_saturates)")
MIS1 = ("mechanism: 1X moves with δ where the contact, absent without misalignment (δ = 0.1 µm: max r/δ0 <= 0.09), is "
        "weak or absent at δ = 0.5 mm and grows with δ: contact share at 0.5 mm 0-34 % at the three failing speeds "
        "(converged 10 200 rpm: no contact at 0.5 mm, support 1X 9.48 µm = the no-misalignment 9.49, then 17 % / 29 % "
        "contact and 11.55 / 14.12 µm with contact-force 1X 241 / 879 N; converged 9 600: 34 %, 1 impact per "
        "revolution, then 2; paper's mesh 12 000: 26 % with a period-6 orbit, 6.18 / 5.55 / 4.49 µm) against 48-77 % "
        "at the four where 1X holds. Not the third critical speed: converged 9 000 rpm, 2 % above 8 799, holds "
        "(test_misalignment_1x_moves_where_the_contact_is_not_yet_established)")
SLIP = ("mechanism: the end faces slip from 5 400 rpm (both meshes), with contact: the relative displacement the "
        "paper rules out below 9 000 rpm (first slip per reading in reports/published/section5-readings.md)")


def point(mesh: str, rpm: float, case: str):
    """``(arrays, info)`` of one point (:func:`rotor.studies.steady_state.run_point`); cached for the module."""
    key = (mesh, float(rpm), case)
    if key not in _CACHE:
        kw = {k: v for k, v in CASES[case].items()}
        _CACHE[key] = run_point("paper-table4", float(rpm), options=OPTIONS, elements_per_segment=MESHES[mesh], **kw)
    return _CACHE[key]


def amplitudes(mesh: str, rpm: float, case: str, quantity: str):
    """``(A (3 stations, 5 orders), info)`` of one point; cached for the module."""
    arrays, info = point(mesh, rpm, case)
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


#: (finding, mesh, band, speeds[, why it fails]) as measured by the published run (study-findings.md, friction and
#: contact events located inside the step, the default since the fourth session of 2026-11-27: the comments are the
#: band verdicts; a band with fewer than two periodic speeds has no verdict and no test). Rules: a band that holds is
#: asserted at its first and last periodic speed; one that holds in part at its first and last passing speed (two or
#: more) and, strict xfail, at its first and last failing one.
CHECKS = [
    # near_support, paper, H1: yes
    _check("near_support", "paper", "H1", (9000, 12000)),
    # near_support, paper, H2: yes
    _check("near_support", "paper", "H2", (12300, 12600)),
    # near_support, paper, H3: n/a (0 periodic; 10 of 10 non-periodic meet it)
    # tilt, paper, H1: yes
    _check("tilt", "paper", "H1", (9300, 12000)),
    # tilt, paper, H2: n/a (1 periodic; 0 of 9 non-periodic meet it)
    # tilt, paper, H3: n/a (0 periodic; 2 of 10 non-periodic meet it)
    # stuck_low, paper, L1: yes
    _check("stuck_low", "paper", "L1", (300, 4500)),
    # stuck_low, paper, L2: partly (2 of 14)
    _check("stuck_low", "paper", "L2", (4800, 5100)),
    _check("stuck_low", "paper", "L2", (5400, 8700), "partly (2 of 14) of the band's periodic speeds; 5400 rpm stuck 0 %, contact 100 %; 8700 rpm stuck 0 %, contact 62 %; " + SLIP),
    # clearance_low, paper, L1: yes
    _check("clearance_low", "paper", "L1", (600, 4200)),
    # clearance_low, paper, L2: partly (1 of 3)
    _check("clearance_low", "paper", "L2", (6600, 7800), "partly (1 of 3) of the band's periodic speeds; 6600 rpm largest change 1X 1.7 %, 2X 9.8 %; 7800 rpm largest change 1X 3.1 %, 2X 6.8 %; " + SLIP),
    # clearance_2x, paper, H1: partly (1 of 3)
    _check("clearance_2x", "paper", "H1", (9000, 10200), "partly (1 of 3) of the band's periodic speeds; 9000 rpm 2X disk 2 1.78/1.79/1.8; support 2.09/2.11/2.11 µm; 10200 rpm 2X disk 2 1.87/1.89/1.93; support 2.07/2.1/2.15 µm; " + LAW),
    # clearance_2x, paper, H2: n/a (1 periodic; 0 of 4 non-periodic meet it)
    # clearance_2x, paper, H3: n/a (0 periodic; 1 of 5 non-periodic meet it)
    # clearance_3x, paper, H1: partly (1 of 3)
    _check("clearance_3x", "paper", "H1", (9000, 10200), "partly (1 of 3) of the band's periodic speeds; 9000 rpm 3X disk 2 0.21/0.212/0.191; support 0.17/0.169/0.156 µm; 10200 rpm 3X disk 2 0.0353/0.0406/0.0442; support 0.017/0.0245/0.0419 µm; " + LAW),
    # clearance_3x, paper, H2: n/a (1 periodic; 0 of 4 non-periodic meet it)
    # clearance_3x, paper, H3: n/a (0 periodic; 0 of 5 non-periodic meet it)
    # misalignment_2x, paper, L1: yes
    _check("misalignment_2x", "paper", "L1", (600, 4200)),
    # misalignment_2x, paper, L2: yes
    _check("misalignment_2x", "paper", "L2", (4800, 8400)),
    # misalignment_2x, paper, H1: n/a (1 periodic; 5 of 5 non-periodic meet it)
    # misalignment_2x, paper, H2: n/a (0 periodic; 4 of 5 non-periodic meet it)
    # misalignment_2x, paper, H3: n/a (0 periodic; 4 of 5 non-periodic meet it)
    # misalignment_3x, paper, H1: n/a (1 periodic; 2 of 5 non-periodic meet it)
    # misalignment_3x, paper, H2: n/a (0 periodic; 0 of 5 non-periodic meet it)
    # misalignment_3x, paper, H3: n/a (0 periodic; 0 of 5 non-periodic meet it)
    # misalignment_1x, paper, L1: yes
    _check("misalignment_1x", "paper", "L1", (600, 4200)),
    # misalignment_1x, paper, L2: yes
    _check("misalignment_1x", "paper", "L2", (4800, 8400)),
    # misalignment_1x, paper, H1: n/a (1 periodic; 3 of 5 non-periodic meet it)
    # misalignment_1x, paper, H2: n/a (0 periodic; 0 of 5 non-periodic meet it)
    # misalignment_1x, paper, H3: n/a (0 periodic; 0 of 5 non-periodic meet it)
    # near_support, converged, H1: yes
    _check("near_support", "converged", "H1", (9000, 11400)),
    # near_support, converged, H2: n/a (0 periodic; 10 of 10 non-periodic meet it)
    # near_support, converged, H3: n/a (0 periodic; 9 of 10 non-periodic meet it)
    # tilt, converged, H1: n/a (0 periodic; 10 of 11 non-periodic meet it)
    # tilt, converged, H2: n/a (0 periodic; 0 of 10 non-periodic meet it)
    # tilt, converged, H3: n/a (0 periodic; 1 of 10 non-periodic meet it)
    # stuck_low, converged, L1: yes
    _check("stuck_low", "converged", "L1", (1200, 4500)),
    # stuck_low, converged, L2: partly (2 of 13)
    _check("stuck_low", "converged", "L2", (4800, 5100)),
    _check("stuck_low", "converged", "L2", (5700, 8700), "partly (2 of 13) of the band's periodic speeds; 5700 rpm stuck 0 %, contact 100 %; 8700 rpm stuck 0 %, contact 64 %; " + SLIP),
    # clearance_low, converged, L1: yes
    _check("clearance_low", "converged", "L1", (1200, 4200)),
    # clearance_low, converged, L2: partly (1 of 3)
    _check("clearance_low", "converged", "L2", (6600, 7800), "partly (1 of 3) of the band's periodic speeds; 6600 rpm largest change 1X 0.6 %, 2X 6.4 %; 7800 rpm largest change 1X 0.7 %, 2X 5.5 %; " + SLIP),
    # clearance_2x, converged, H1: partly (1 of 5)
    _check("clearance_2x", "converged", "H1", (9000, 11400), "partly (1 of 5) of the band's periodic speeds; 9000 rpm 2X disk 2 1.66/1.68/1.74; support 1.91/1.93/1.96 µm; 11400 rpm 2X disk 2 3.13/3.15/3.2; support 3.21/3.23/3.3 µm; " + LAW),
    # clearance_2x, converged, H2: n/a (0 periodic; 1 of 5 non-periodic meet it)
    # clearance_2x, converged, H3: n/a (0 periodic; 0 of 5 non-periodic meet it)
    # clearance_3x, converged, H1: partly (2 of 5)
    _check("clearance_3x", "converged", "H1", (10200, 11400)),
    _check("clearance_3x", "converged", "H1", (9000, 10800), "partly (2 of 5) of the band's periodic speeds; 9000 rpm 3X disk 2 0.0422/0.0456/0.0617; support 0.0614/0.0657/0.0935 µm; 10800 rpm 3X disk 2 0.0785/0.0871/0.0886; support 0.112/0.124/0.127 µm; " + LAW),
    # clearance_3x, converged, H2: n/a (0 periodic; 0 of 5 non-periodic meet it)
    # clearance_3x, converged, H3: n/a (0 periodic; 0 of 5 non-periodic meet it)
    # misalignment_2x, converged, L1: yes
    _check("misalignment_2x", "converged", "L1", (1200, 4200)),
    # misalignment_2x, converged, L2: n/a (1 periodic; 6 of 6 non-periodic meet it)
    # misalignment_2x, converged, H1: yes
    _check("misalignment_2x", "converged", "H1", (9000, 10200)),
    # misalignment_2x, converged, H2: n/a (0 periodic; 3 of 5 non-periodic meet it)
    # misalignment_2x, converged, H3: n/a (0 periodic; 5 of 5 non-periodic meet it)
    # misalignment_3x, converged, H1: partly (1 of 2)
    _check("misalignment_3x", "converged", "H1", (9000,), "partly (1 of 2) of the band's periodic speeds; 9000 rpm 3X disk 2 0.0554/0.0456/0.0164; support 0.0666/0.0657/0.0217 µm; " + MIS3),
    # misalignment_3x, converged, H2: n/a (0 periodic; 1 of 5 non-periodic meet it)
    # misalignment_3x, converged, H3: n/a (0 periodic; 2 of 5 non-periodic meet it)
    # misalignment_1x, converged, L1: yes
    _check("misalignment_1x", "converged", "L1", (1200, 4200)),
    # misalignment_1x, converged, L2: n/a (1 periodic; 5 of 6 non-periodic meet it)
    # misalignment_1x, converged, H1: partly (1 of 2)
    _check("misalignment_1x", "converged", "H1", (10200,), "partly (1 of 2) of the band's periodic speeds; 10200 rpm 1X change 7.6 / 11.5 / 49.0 %; " + MIS1),
    # misalignment_1x, converged, H2: n/a (0 periodic; 0 of 5 non-periodic meet it)
    # misalignment_1x, converged, H3: n/a (0 periodic; 0 of 5 non-periodic meet it)
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


# ---------------------------------------------------------------------------------------------
# the mechanisms behind the failing §5.3.2 checks, measured at the band H1 speeds where all three δ are periodic
# ---------------------------------------------------------------------------------------------

#: (mesh, rpm) of band H1 where the three δ are periodic (study-findings.md), by whether the finding holds there
ONE_X = {"fails": (("paper", 12000), ("converged", 9600), ("converged", 10200)),
         "holds": (("paper", 9000), ("paper", 10200), ("paper", 10800), ("converged", 9000))}
THREE_X = {"fails": (("paper", 9000), ("paper", 10200), ("paper", 10800), ("converged", 9000), ("converged", 9600)),
           "holds": (("paper", 12000), ("converged", 10200))}


def _pattern(mesh, rpm):
    from rotor.studies.section5 import misalignment_mechanism
    return misalignment_mechanism({c: point(mesh, rpm, c) for c in ("d0.5", "base", "d2")})


@pytest.mark.slow
def test_misalignment_1x_moves_where_the_contact_is_not_yet_established():
    """§5.3.2's "1X essentially unchanged" fails (xfail MIS1) where the ring touches the support little or not at
    δ = 0.5 mm (contact share below ``ENGAGED_SHARE``) and holds where it is already in contact: the contact, which
    the unbalance alone never makes (δ = 0.1 µm: the ring stays inside the clearance), then grows with δ and moves
    the support's 1X with it. At converged 10 200 rpm the δ = 0.5 mm point has no contact and its support 1X is the
    unbalance-only one (within 1 %)."""
    from rotor.studies.section5 import ENGAGED_SHARE, misalignment_1x

    for verdict, where in ONE_X.items():
        for mesh, rpm in where:
            assert misalignment_1x({c: amplitudes(mesh, rpm, c, "q") for c in ("d0.5", "base", "d2")})[0] == \
                (verdict == "holds"), (mesh, rpm)
            pat, text = _pattern(mesh, rpm)
            assert (pat["d0.5"]["contact_share"] >= ENGAGED_SHARE) == (verdict == "holds"), f"{mesh} {rpm}: {text}"
            assert point(mesh, rpm, "d0")[1]["max_r_over_clearance"] < 1.0, (mesh, rpm)   # no contact without δ
    a05, i05 = amplitudes("converged", 10200, "d0.5", "q")
    a0, _ = amplitudes("converged", 10200, "d0", "q")
    assert i05["contact_fraction"] == 0.0 and a05[2, 0] == pytest.approx(a0[2, 0], rel=0.01)


@pytest.mark.slow
def test_misalignment_3x_stops_rising_where_the_contact_saturates():
    """§5.3.2's "3X rises with δ" fails (xfail MIS3) where the ring is on the bore more than ``SATURATED_SHARE``
    of the revolution at δ = 2 mm, and holds where the contact at 2 mm is still partial."""
    from rotor.studies.section5 import SATURATED_SHARE, misalignment_3x

    for verdict, where in THREE_X.items():
        for mesh, rpm in where:
            assert misalignment_3x({c: amplitudes(mesh, rpm, c, "q") for c in ("d0.5", "base", "d2")})[0] == \
                (verdict == "holds"), (mesh, rpm)
            pat, text = _pattern(mesh, rpm)
            assert (pat["d2"]["contact_share"] <= SATURATED_SHARE) == (verdict == "holds"), f"{mesh} {rpm}: {text}"
