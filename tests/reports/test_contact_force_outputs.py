"""The headline answer in the outputs: the contact force on the bearing and each end face's stick, in
``simulate`` (CSV, NPZ, summary), ``orbit``/``branch`` JSON and the study cascade CSV
(:mod:`rotor.dynamics.support_record`).

The contacting run is the Table 4 rotor at 10 500 rpm with a 0.005 mm clearance, started from rest (``--from-rest``:
the ring reaches the bore within the first revolution; the scene's 0.05 mm clearance takes hundreds of revolutions
from rest, and from the static equilibrium, simulate's default, the ring touches 8 % of the first 3 revolutions). The
force is checked against an independent call of the contact law, :func:`contact.loose_support.loose_support_force`,
with the scene's [loose_support] values at the recorded relative state rebuilt from the recorded DOFs.
"""
from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from reports import cli

SPEED = 10500.0
CLEARANCE_MM = 0.005
NEW_KEYS = ("peak_contact_force_N", "peak_contact_force_t_s", "mean_contact_force_N", "peak_contact_moment_Nm",
            "contact_share", "separation_share", "stick_share_right_face", "stick_share_left_face", "peak_face_force_N")
UNITS = ("_N", "_Nm", "_s", "_share", "_face")   # N, N m, s; shares are fractions of the samples (–)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("simulate")
    rc = cli.main(["simulate", "--speed-rpm", str(SPEED), "--revolutions", "3", "--clearance-mm", str(CLEARANCE_MM),
                   "--from-rest", "--out", str(out)])
    assert rc == 0
    with open(out / "simulate.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    cols = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    summary = json.loads((out / "simulate-summary.json").read_text())
    return cols, dict(np.load(out / "simulate.npz")), summary


def test_summary_peak_and_shares_are_those_of_the_csv_columns(run):
    cols, _, s = run
    f = cols["contact_force_N"]
    assert s["contact_share"] > 0.1 and s["peak_contact_force_N"] > 0            # this run hits its support
    assert s["peak_contact_force_N"] == pytest.approx(f.max(), rel=1e-8)        # CSV written to 9 digits
    assert s["peak_contact_force_t_s"] == pytest.approx(cols["t_s"][np.argmax(f)], rel=1e-8)
    assert s["mean_contact_force_N"] == pytest.approx(f[f > 0].mean(), rel=1e-8)
    assert s["peak_contact_moment_Nm"] == pytest.approx(cols["contact_moment_Nm"].max(), rel=1e-8)
    assert s["contact_share"] == pytest.approx(np.mean(f > 0)) and s["separation_share"] == pytest.approx(np.mean(f == 0))
    assert s["stick_share_right_face"] == pytest.approx(cols["face_right_stuck"].mean())
    assert s["stick_share_left_face"] == pytest.approx(cols["face_left_stuck"].mean())
    assert 0 < s["stick_share_right_face"] < 1                                   # the right face slips and sticks
    # the older keys stay, with the same stick numbers; contact_fraction counts edges past the clearance
    assert s["stick_fraction_right"] == s["stick_share_right_face"] and s["stick_fraction_left"] == s["stick_share_left_face"]
    assert s["contact_fraction"] >= s["contact_share"] - 1e-12
    assert all(k in s and k.endswith(UNITS) for k in NEW_KEYS)
    assert "ON the bearing" in s["contact_force_convention"]


def test_csv_force_columns_equal_the_npz_arrays(run):
    cols, npz, _ = run
    for k in ("contact_force_y_N", "contact_force_z_N", "contact_force_N", "contact_moment_y_Nm",
              "contact_moment_z_Nm", "face_right_force_y_N", "face_left_force_z_N", "face_right_stuck"):
        np.testing.assert_allclose(cols[k], npz[k], rtol=1e-8, atol=1e-9 * np.abs(npz[k]).max())
    np.testing.assert_allclose(cols["contact_force_N"], np.hypot(npz["contact_force_y_N"], npz["contact_force_z_N"]),
                               rtol=1e-8)
    named = np.column_stack([npz[k] for k in ("contact_force_y_N", "contact_force_z_N", "contact_moment_y_Nm",
                                              "contact_moment_z_Nm")])
    assert np.array_equal(named, npz["f_contact"])                      # the unlabelled array, now named
    assert np.array_equal(npz["face_left_force_y_N"], npz["face_force"][:, 1, 0])


def test_recorded_force_is_the_contact_law_at_the_recorded_state(run):
    """The recorded force against an independent call of the law: the relative state rebuilt from the recorded
    DOFs (bearing node 5 minus support node s, Table 4 scene) and the scene's [loose_support] values with the
    run's clearance, friction off (the faces are the integrator's constraints)."""
    from contact.loose_support import LooseSupportParams, loose_support_force
    from rotor.model.scene import load_scene

    _, npz, _ = run
    names = list(npz["dof_names"])
    b = [names.index(f"5.{c}") for c in ("y", "z", "θy", "θz")]
    sup = [names.index(f"s.{c}") for c in ("y", "z", "θy", "θz")]
    u = npz["q"][:, b] - npz["q"][:, sup]
    w = npz["v"][:, b] - npz["v"][:, sup]
    np.testing.assert_allclose(u, npz["u"], rtol=0, atol=1e-12 * np.abs(u).max())
    ls = load_scene("paper-table4").loose_support
    params = LooseSupportParams(clearance_m=CLEARANCE_MM * 1e-3, width_m=ls.ring_width_m,
                                bearing_E_Pa=ls.bearing_modulus_pa, bearing_nu=ls.bearing_poisson,
                                support_E_Pa=ls.support_modulus_pa, support_nu=ls.support_poisson,
                                c_c_s_per_m=ls.collision_factor_s_m, law=ls.law)
    hit = np.flatnonzero(npz["contact_force_N"] > 0)
    pick = np.unique(np.r_[hit[:: max(1, hit.size // 8)], np.argmax(npz["contact_force_N"])])
    r = loose_support_force(params, *u[pick].T, *w[pick].T)
    got = np.column_stack([r.Fy_N, r.Fz_N, r.My_Nm, r.Mz_Nm])
    scale = np.abs(npz["f_contact"][pick]).max()
    np.testing.assert_allclose(got, npz["f_contact"][pick], rtol=1e-9, atol=1e-9 * scale)
    # on the bearing, pushing it back into the clearance: against its offset where the centre is past it
    out = pick[np.hypot(u[pick, 0], u[pick, 1]) > params.clearance_m]
    assert out.size and np.all(npz["f_contact"][out, 0] * u[out, 0] + npz["f_contact"][out, 1] * u[out, 1] < 0)


def _orbit(speed_rpm, capsys, tmp_path) -> dict:
    out = tmp_path / f"orbit-{speed_rpm:g}.json"
    assert cli.main(["orbit", "paper-table4", "--speed-rpm", f"{speed_rpm:g}", "--json", "--out", str(out)]) == 0
    d = json.loads(capsys.readouterr().out)
    assert json.loads(out.read_text()) == d
    return d


def test_orbit_json_tells_a_stuck_ring_from_one_that_hits(capsys, tmp_path):
    """3 000 rpm: the paper's linear regime (both faces stuck, no contact: 4 neutral multipliers, the faces'
    free offsets); 10 500 rpm: the ring presses on its bore and the right face slips (measured 3 % stuck)."""
    stuck, hits = _orbit(3000, capsys, tmp_path), _orbit(SPEED, capsys, tmp_path)
    assert stuck["neutral_multipliers"] == 4 and stuck["face_mode_changes"] == 0
    assert stuck["contact_share"] == 0 and stuck["separation_share"] == 1 and stuck["peak_contact_force_N"] == 0
    assert stuck["mean_contact_force_N"] is None and stuck["peak_contact_force_t_s"] is None
    assert stuck["stick_share_right_face"] == 1 and stuck["stick_share_left_face"] == 1
    assert hits["contact_share"] > 0.5 and hits["peak_contact_force_N"] > 0 and hits["stick_share_right_face"] < 1
    assert 0 <= hits["peak_contact_force_t_s"] < hits["period_s"]
    assert hits["mean_contact_force_N"] <= hits["peak_contact_force_N"]
    assert (hits["max_edge_penetration_mm"] > 0) == (hits["contact_share"] > 0)
    for d in (stuck, hits):
        assert all(k in d and k.endswith(UNITS) for k in NEW_KEYS)
    # the stuck ring's orbit is one of a family held by friction (its neutral multipliers), said as such
    assert stuck["unique"] is False and stuck["family"] == "not unique: a family held by friction"
    assert hits["unique"] is (hits["neutral_multipliers"] == 0) and (hits["family"] is None) == hits["unique"]


def test_branch_points_carry_the_contact_fields(capsys):
    rc = cli.main(["branch", "paper-table4", "--rpm-start", "3000", "--rpm-end", "3100", "--max-points", "2", "--json"])
    assert rc == 1                                                     # stopped at --max-points, before --rpm-end
    d = json.loads(capsys.readouterr().out)
    assert len(d["points"]) == 2
    for p in d["points"]:
        assert p["contact_share"] == 0 and p["stick_share_right_face"] == 1 and p["peak_contact_force_N"] == 0
        assert p["unique"] is False                                    # both faces stuck: a family held by friction


def test_cascade_csv_has_peak_force_and_shares_per_speed(tmp_path):
    from reports.cli.study import main as study

    out = tmp_path / "run"
    assert study(["cascade", "--rpm-min", "3000", "--rpm-max", str(SPEED), "--points", "2", "--method", "shooting",
                  "--workers", "1", "--no-progress", "--out", str(out)]) == 0
    with open(out / "figures" / "study-cascade.csv", newline="") as f:
        rows = {float(r["speed_rpm"]): r for r in csv.DictReader(f)}
    low, high = rows[3000.0], rows[SPEED]
    assert float(low["contact_share"]) == 0 and float(low["peak_contact_force_N"]) == 0
    assert float(low["stick_share_right_face"]) == 1 and float(low["stick_share_left_face"]) == 1
    assert float(high["contact_share"]) > 0 and float(high["peak_contact_force_N"]) > 0
    # the peak of the stored point's force history (a period-1 orbit repeated: the same samples)
    point = np.load(out / "points" / f"rpm{SPEED:.1f}.npz")
    fc = point["f_contact"]
    assert float(high["peak_contact_force_N"]) == pytest.approx(np.hypot(fc[:, 0], fc[:, 1]).max(), rel=1e-5)


def test_runup_records_the_force_and_its_note_names_the_peak(tmp_path):
    """A short ramp at the small clearance (0.15 s: the note's 0.1 s STFT window fits): the stored force history,
    the info's summary over it, the note."""
    from reports.studies.runup import runup_note
    from rotor.studies.runup import RunupSpec, run_runup

    spec = RunupSpec(rpm_start=10000, rpm_end=10500, duration_s=0.15, clearance_m=CLEARANCE_MM * 1e-3)
    info = run_runup(spec, tmp_path / "runup")
    point = np.load(tmp_path / "runup" / "points" / "runup.npz")
    force = np.hypot(point["f_contact"][:, 0], point["f_contact"][:, 1])
    assert info["contact_share"] == pytest.approx(np.mean(force > 0)) and info["contact_share"] > 0
    assert info["peak_contact_force_N"] == force.max()
    assert info["peak_contact_force_t_s"] == point["t"][np.argmax(force)]
    assert point["face_force"].shape == (force.size, 2, 2)
    assert f"Peak radial contact force on the bearing {force.max():.4g} N" in runup_note(tmp_path / "runup")
