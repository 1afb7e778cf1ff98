"""Linear time response with the loose support locked (rotor.dynamics.linear_response, ``rotor response``)
against the closed-form steady state of a damped Jeffcott rotor (Jeffcott 1919; e.g. Genta 2005,
Dynamics of Rotating Systems, §4.2): ŷ = m e Ω² e^{iφ}/(k − mΩ² + icΩ), ẑ = −iŷ, with
1/k = L³/(48EI) + L/(4κGA) for the massless shaft pinned at both ends and the damper at the disk."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from reports.cli import rotor as cli
from rotor.linear.unbalance import forced_response
from rotor.model.assembly import assemble
from rotor.model.elements import cowper_shear_coefficient
from rotor.model.scene import loads_scene

E, D, L, NU, M, ME, PHI = 200e9, 0.02, 0.8, 0.3, 10.0, 100e-6, math.pi / 6

JEFFCOTT = (Path(__file__).resolve().parents[1] / "scenes" / "damped-jeffcott.toml").read_text()


def _read(path) -> dict:
    """The CSV's columns by header name."""
    head = path.read_text().splitlines()[0].split(",")
    table = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {h: table[:, j] for j, h in enumerate(head)}


def _k() -> float:
    A, I = math.pi / 4 * D * D, math.pi / 64 * D ** 4
    G = E / (2 * (1 + NU))
    return 1 / (L ** 3 / (48 * E * I) + L / (4 * cowper_shear_coefficient(D, 0, NU) * G * A))


def _closed(c: float, W: float, t):
    yhat = ME * W ** 2 * np.exp(1j * PHI) / (_k() - M * W ** 2 + 1j * c * W)
    e = np.exp(1j * W * np.asarray(t))
    return (yhat * e).real, (-1j * yhat * e).real, abs(yhat)


def _run(tmp_path, c: float, W: float, *extra):
    scene = tmp_path / "jeffcott.toml"
    scene.write_text(JEFFCOTT.replace("damping_n_s_per_m = 150", f"damping_n_s_per_m = {c!r}"))
    out = tmp_path / "out"
    assert cli.main(["response", str(scene), "--speed-rpm", repr(W * 30 / math.pi), "--out", str(out), "--json",
                     *extra]) == 0
    data = _read(out / "response.csv")
    return data, json.loads((out / "response-summary.json").read_text())


def test_harmonic_response_is_the_closed_form_steady_state(tmp_path, capsys):
    c, W = 150.0, 1.3 * math.sqrt(_k() / M)
    data, summary = _run(tmp_path, c, W, "--revolutions", "2")
    y, z, amp = _closed(c, W, data["t_s"])
    assert list(data) == ["t_s", "disk.y_m", "disk.z_m"]      # the scene's response station, by its name
    assert np.abs(data["disk.y_m"] - y).max() <= 1e-8 * amp
    assert np.abs(data["disk.z_m"] - z).max() <= 1e-8 * amp
    assert len(data["t_s"]) == 2 * 64 + 1 and data["t_s"][-1] == pytest.approx(2 * 2 * math.pi / W, rel=1e-12)
    # the summary's 1X semi-major comes from rotor.linear.unbalance and is the same amplitude
    st = summary["stations"]["disk"]
    assert st["forced_response_semi_major_um_1X"] == pytest.approx(amp * 1e6, rel=1e-9)
    assert st["last_rev_max_radius_um"] == pytest.approx(amp * 1e6, rel=1e-9)    # circular orbit
    assert json.loads(capsys.readouterr().out)["method"] == "harmonic"


def test_newmark_from_rest_settles_on_the_closed_form(tmp_path, capsys):
    """ζ = c/(2√(km)) ≈ 0.25: the start-up transient decays as e^{−ζω_n t} < 1e-5 in 12 revolutions
    at 1.5 ω_n; average acceleration with 256 steps/rev then matches the steady state within 1e-3."""
    c, W = 600.0, 1.5 * math.sqrt(_k() / M)
    data, summary = _run(tmp_path, c, W, "--revolutions", "12", "--method", "newmark")
    last = data["t_s"] >= data["t_s"][-1] - 2 * math.pi / W * (1 - 1e-9)
    y, z, amp = _closed(c, W, data["t_s"][last])
    assert np.abs(data["disk.y_m"][last] - y).max() <= 1e-3 * amp
    assert np.abs(data["disk.z_m"][last] - z).max() <= 1e-3 * amp
    assert data["disk.y_m"][0] == 0.0                                   # from rest, no static load
    assert summary["method"] == "newmark"
    capsys.readouterr()


def test_paper_rotor_support_locked_and_1x_is_the_forced_response(tmp_path, capsys):
    """Table 4 rotor at 4500 rpm: the loose bearing '5' and its support 's' move together, and the 1X
    Fourier coefficient of the CSV over one revolution equals rotor.linear.unbalance's amplitude."""
    out = tmp_path / "p"
    assert cli.main(["response", "paper-table4", "--speed-rpm", "4500", "--revolutions", "1",
                     "--record-per-rev", "64", "--stations", "disk1,5,s", "--out", str(out)]) == 0
    capsys.readouterr()
    data = _read(out / "response.csv")
    assert np.array_equal(data["5.y_m"], data["s.y_m"]) and np.array_equal(data["5.z_m"], data["s.z_m"])
    from rotor.model.scene import load_scene
    model = assemble(load_scene("paper-table4"))
    W = 4500 * math.pi / 30
    one = np.exp(-1j * W * data["t_s"][:-1])
    c1 = 2 * np.mean(data["disk1.y_m"][:-1] * one)                      # 1X coefficient of y(t)
    ref = forced_response(model, [W], order=1).amplitudes[0, model.dof_index("disk1.y")]
    assert c1 == pytest.approx(ref, rel=1e-8)


@pytest.mark.parametrize("args, text", [
    (["--speed-rpm", "0"], "--speed-rpm = 0 rpm: must be in (0, 200000] rpm"),
    (["--speed-rpm", "1000", "--revolutions", "-1"], "--revolutions = -1 rev: must be in (0, 100000] rev"),
    (["--speed-rpm", "1000", "--stations", "nowhere"], "no node or element named 'nowhere'"),
    (["--speed-rpm", "1000", "--record-per-rev", "48"], "record_per_rev = 48: must be >= 1 and divide"),
])
def test_bad_input_is_one_line(tmp_path, capsys, args, text):
    try:                    # refused by the parser (argparse exits) or by the job (returns)
        code = cli.main(["response", "verify-jeffcott", *args, "--out", str(tmp_path / "x")])
    except SystemExit as exc:
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and text in err and err.startswith("ringcontact rotor response: error:"), err
    assert not (tmp_path / "x").exists()
