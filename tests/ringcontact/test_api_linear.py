"""ringcontact linear analyses: the Jeffcott rotor's closed forms and the same numbers as ``ringcontact rotor``;
what every result object does (save, CSV, xarray, DataFrame, plot)."""
from __future__ import annotations

import json
import math
import sys

import numpy as np
import pytest

import ringcontact as rc
from reports.cli import main as cli

# verify-jeffcott (rotor/scenes/verify-jeffcott.toml): 0.8 m, d = 20 mm steel shaft of no mass, a 10 kg
# central disk with 100 g·mm of unbalance, two 2e6 N/m bearings
L, D, M, KB, E, NU, ME = 0.8, 0.02, 10.0, 2.0e6, 200e9, 0.3, 1e-4


def _jeffcott_stiffness() -> float:
    """Jeffcott (1919): 1/k = L³/(48EI) + L/(4κGA) + 1/(2k_b), κ of a solid section 6(1+ν)/(7+6ν) (Cowper 1966)."""
    A, I = math.pi / 4 * D * D, math.pi / 64 * D ** 4
    kappa, G = 6 * (1 + NU) / (7 + 6 * NU), E / (2 * (1 + NU))
    return 1.0 / (L ** 3 / (48 * E * I) + L / (4 * kappa * G * A) + 1 / (2 * KB))


def _cli_json(capsys, *argv) -> dict:
    capsys.readouterr()
    assert cli(list(argv)) == 0
    return json.loads(capsys.readouterr().out)


def test_modes_are_the_jeffcott_critical_speed_and_the_cli_numbers(capsys):
    m = rc.modes("verify-jeffcott", 0.0)
    assert m.frequency_rad_s == pytest.approx([math.sqrt(_jeffcott_stiffness() / M)] * 2, rel=1e-9)
    assert set(m.whirl) == {"forward", "backward"}
    d = _cli_json(capsys, "rotor", "modes", "verify-jeffcott", "--json")
    assert [r["frequency_hz"] for r in d["modes"]] == list(m.frequency_hz)      # the job's numbers, unchanged
    assert m.frequency_rad_s == pytest.approx(2 * math.pi * m.frequency_hz, rel=1e-15)


def test_campbell_of_a_disk_without_polar_inertia_is_flat_and_matches_the_cli(capsys):
    """No gyroscopic coupling (Ip = 0): the whirl frequencies do not move with speed."""
    c = rc.campbell("verify-jeffcott", [0.0, 1500.0, 3000.0], n_modes=2)
    assert c.frequency_rad_s == pytest.approx(np.full((3, 2), math.sqrt(_jeffcott_stiffness() / M)), rel=1e-9)
    d = _cli_json(capsys, "rotor", "campbell", "verify-jeffcott", "--max-rpm", "3000", "--points", "3", "--modes", "2",
                  "--json")
    assert d["speed_rpm"] == pytest.approx(list(c.speeds_rpm), rel=1e-12)
    assert np.array(d["frequency_hz"]) == pytest.approx(c.frequency_hz, rel=1e-12)


def test_unbalance_response_is_the_undamped_jeffcott_amplitude_with_its_phase(capsys):
    """|x| = m e ω² / |k − m ω²| (Jeffcott 1919, undamped), in phase below and opposite above the critical speed."""
    rpm = np.array([600.0, 1000.0, 2000.0])
    u = rc.unbalance_response("verify-jeffcott", rpm)
    w = rpm * math.pi / 30
    k = _jeffcott_stiffness()
    assert u.semi_major_m[:, 0] == pytest.approx(ME * w ** 2 / np.abs(k - M * w ** 2), rel=1e-9)
    assert u.semi_minor_m[:, 0] == pytest.approx(u.semi_major_m[:, 0], rel=1e-9)          # a circle: isotropic
    assert np.abs(u.phase_y_deg[:, 0]) == pytest.approx([0.0, 0.0, 180.0], abs=1e-6)       # critical at 1137 rpm
    d = _cli_json(capsys, "rotor", "unbalance", "verify-jeffcott", "--max-rpm", "3000", "--points", "3", "--json")
    again = rc.unbalance_response("verify-jeffcott", d["speed_rpm"])
    assert np.array(d["semi_major_um"]["d"]) == pytest.approx(again.semi_major_m[:, 0] * 1e6, rel=1e-12)


def test_a_result_saves_tabulates_and_draws(tmp_path):
    m = rc.modes("verify-jeffcott")
    back = rc.load_result(m.save(tmp_path / "modes.json"))
    assert back["result"] == "ModesResult" and back["frequency_rad_s"] == list(m.frequency_rad_s)
    npz = rc.load_result(m.save(tmp_path / "modes.npz"))
    assert np.array_equal(npz["frequency_rad_s"], m.frequency_rad_s) and np.array_equal(npz["shapes"], m.shapes)
    assert json.loads(str(np.load(tmp_path / "modes.npz")["summary_json"]))["whirl"] == list(m.whirl)
    header, *rows = m.to_csv(tmp_path / "modes.csv").read_text().splitlines()
    assert header.split(",")[:3] == ["mode", "frequency_rad_s", "frequency_hz"] and len(rows) == 2
    ds = m.to_xarray()
    assert np.array_equal(ds["frequency_rad_s"].values, m.frequency_rad_s)
    assert list(m.to_dataframe()["frequency_hz"]) == list(m.frequency_hz)
    with pytest.raises(rc.InputError, match=r"suffix must be \.json or \.npz"):
        m.save(tmp_path / "modes.txt")
    ax = rc.unbalance_response("verify-jeffcott", [500.0, 900.0]).plot()
    (line,) = ax.get_lines()
    assert len(line.get_xdata()) == 2 and ax.get_xlabel() == "rotor speed (rpm)"
    import matplotlib.pyplot as plt
    plt.close("all")


def test_without_pandas_or_xarray_the_message_says_what_to_do(monkeypatch):
    m = rc.modes("verify-jeffcott")
    monkeypatch.setitem(sys.modules, "pandas", None)
    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(rc.InputError, match=r"pandas is not installed.*\.to_csv\(path\)"):
        m.to_dataframe()
    with pytest.raises(rc.InputError, match=r"xarray is not installed; install the xarray extra"):
        m.to_xarray()


def test_bad_speeds_are_refused_in_one_line():
    with pytest.raises(rc.InputError, match=r"speed_rpm = -1 rpm, i.e. --speed-rpm = -1 rpm: must be in \[0, "):
        rc.modes("verify-jeffcott", -1)
    with pytest.raises(rc.InputError, match=r"rpm = nan rpm, i.e. --speed-rpm = nan rpm: must be finite"):
        rc.campbell("verify-jeffcott", [0.0, float("nan")])
