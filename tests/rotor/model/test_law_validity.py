"""The validity record of a run (rotor/model/law_validity.py): verdict from a law file, contact-time shares below,
inside and above the fitted range counted against a seeded random sample, their merge over several runs, and the
refusal of a flagged law."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from contact.calibrate.store import shipped_record
from contact.errors import InputError
from rotor.model.law_validity import (ANALYTIC, FLAGGED, VERIFIED, check_allowed, law_line, merged, record,
                                      stored_point_record, verdict)
from rotor.model.loose_support_scene import with_law
from rotor.model.scene import load_scene
from tests.seeds import commit_seed

ARCMIN = np.pi / 10800


def _loose(law="calibrated:clamped-foundation", **edit):
    ls = with_law(load_scene("paper-table4"), law).loose_support
    if edit and ls.calibrated is not None:
        ls = dataclasses.replace(ls, calibrated=dataclasses.replace(ls.calibrated, **edit))
    return ls


def test_verdicts_from_the_files_own_checks():
    law = shipped_record("clamped-foundation").law
    assert verdict(law) == (VERIFIED, [])
    assert verdict(None) == (ANALYTIC, [])
    bearing_flag = dataclasses.replace(law, provenance={"warnings": ["holdout 14.2 % beyond"]})
    calibrate_flag = dataclasses.replace(law, fit={**law.fit, "warning": "scene 'x': held-out 9 %"})
    assert verdict(bearing_flag) == (FLAGGED, ["holdout 14.2 % beyond"])
    assert verdict(calibrate_flag)[0] == FLAGGED and "held-out 9 %" in verdict(calibrate_flag)[1][0]


def test_a_flagged_law_is_refused_unless_allowed():
    flagged = _loose(provenance={"warnings": ["holdout_max_rel_2d = 14.2 % is 12 % beyond"]})
    with pytest.raises(InputError) as exc:
        check_allowed(flagged, False, "--allow-flagged-law")
    msg = str(exc.value)
    assert "FLAGGED" in msg and "--allow-flagged-law" in msg and "14.2 %" in msg and "\n" not in msg
    check_allowed(flagged, True, "--allow-flagged-law")          # allowed: no error
    check_allowed(_loose(), False, "--allow-flagged-law")         # verified: no error
    check_allowed(_loose("conformal"), False, "--allow-flagged-law")
    rec = record(flagged, [1e-5], [0.0])
    assert rec["verdict"] == FLAGGED and any("FLAGGED" in w for w in rec["warnings"])


def test_shares_below_inside_and_above_the_fitted_range_count_the_contact_samples():
    seed = commit_seed()
    print(f"seed {seed}")
    rng = np.random.default_rng(seed)
    ls = _loose()
    lo, hi = ls.calibrated.validity_penetration_m
    pen = rng.uniform(-0.5 * hi, 1.5 * hi, 2000)                  # a third of the samples out of contact
    pen[rng.integers(0, pen.size, 50)] = rng.uniform(0.0, lo, 50)    # some just below the fitted minimum
    tilt = rng.uniform(0.0, 3 * ARCMIN, pen.size)
    rec = record(ls, pen, tilt)
    hit = pen > 0
    assert rec["samples"] == pen.size and rec["contact_samples"] == int(hit.sum())
    assert rec["contact_time_share"] == pytest.approx(hit.mean())
    assert rec["contact_time_share_below"] == pytest.approx(np.mean(pen[hit] < lo))
    assert rec["contact_time_share_above"] == pytest.approx(np.mean(pen[hit] > hi))
    assert rec["contact_time_share_inside"] == pytest.approx(np.mean((pen[hit] >= lo) & (pen[hit] <= hi)))
    assert rec["visited_penetration_range_m"] == [pytest.approx(pen[hit].min()), pytest.approx(pen[hit].max())]
    assert rec["largest_tilt_rad"] == pytest.approx(tilt[hit].max())
    assert rec["penetration_range_m"] == [lo, hi] and rec["law_sha256"] == ls.law_sha256
    assert rec["beyond_tilt_range"] is None                        # a straight-ring law: its tilt never checked
    said = " ".join(rec["warnings"])
    assert "below the law's fitted range" in said and "above the law's fitted range" in said
    # checked to 2 arcmin: the tilts to 3 arcmin pass it
    tilted = record(_loose(validity_tilt_max_rad=2 * ARCMIN), pen, tilt)
    assert tilted["beyond_tilt_range"] is True and any("arcmin" in w for w in tilted["warnings"])
    # merged halves give the whole
    half = pen.size // 2
    both = merged([record(ls, pen[:half], tilt[:half]), record(ls, pen[half:], tilt[half:])])
    for key in ("contact_time_share", "contact_time_share_below", "contact_time_share_inside",
                "contact_time_share_above", "largest_tilt_rad", "visited_penetration_range_m"):
        assert both[key] == pytest.approx(rec[key]), key


def test_no_contact_and_analytic_laws():
    rec = record(_loose(), np.full(10, -1e-6), np.zeros(10))
    assert rec["contact_time_share"] == 0 and rec["contact_time_share_below"] is None and rec["warnings"] == []
    ana = record(_loose("conformal"), [1e-5, -1e-6], [0.0, 0.0])
    assert ana["verdict"] == ANALYTIC and ana["penetration_range_m"] is None and ana["contact_time_share"] == 0.5
    assert ana["contact_time_share_below"] is None and ana["warnings"] == []
    assert record(None, [1e-5], [0.0]) == {} and merged([{}, None]) == {}
    assert stored_point_record(_loose(), {"r1": np.array([])}, 5e-5) == {}


def test_law_line_names_geometry_law_and_overrides():
    line = law_line(_loose(), {"clearance_m": None, "mu": 0.1})
    assert "clearance 0.05 mm" in line and "mu 0.1" in line and "clamped-foundation" in line
    assert "verified" in line and "0.001-0.05 mm" in line and "\n" not in line
