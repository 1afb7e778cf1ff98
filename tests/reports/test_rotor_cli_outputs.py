"""``ringcontact rotor``'s outputs (issue 26): frequencies and speeds in rad/s on request, the unbalance response
with its phase, and critical speeds of the forward 1X crossings unless more are asked for.

The phase is checked on the bundled verify-jeffcott rotor, which has no damping. Closed form of the undamped
Jeffcott rotor: ŷ = m e Ω² / (k − M Ω²), real, so the response is in step with the unbalance (phase 0) below
the critical speed √(k/M) and opposite to it (180°) above; its isotropic supports make the orbit a forward
circle, y + i z = ŷ e^{iΩt}, so z has the amplitude of y and lags it by 90°.
"""
from __future__ import annotations

import json
import math

import pytest

from reports import cli


def _json(argv, capsys) -> dict:
    assert cli.main(argv) == 0
    return json.loads(capsys.readouterr().out)


def _table(argv, capsys) -> list[str]:
    assert cli.main(argv) == 0
    return capsys.readouterr().out.splitlines()


def test_modes_table_in_rad_s(capsys):
    d = _json(["rotor", "modes", "paper-table4", "--json"], capsys)
    rows = _table(["rotor", "modes", "paper-table4", "--units", "rad/s"], capsys)
    assert "freq (rad/s)" in rows[2]
    shown = [float(r.split()[1]) for r in rows[3:]]
    assert shown == pytest.approx([2 * math.pi * m["frequency_hz"] for m in d["modes"]], abs=5e-4)
    assert [m["frequency_rad_s"] for m in d["modes"]] == pytest.approx([2 * math.pi * m["frequency_hz"]
                                                                         for m in d["modes"]], rel=1e-15)


def test_critical_speeds_forward_1x_unless_asked(capsys):
    few = _json(["rotor", "critical-speeds", "paper-table4", "--json"], capsys)
    every = _json(["rotor", "critical-speeds", "paper-table4", "--orders", "1", "2", "--backward", "--json"], capsys)
    assert few["orders"] == [1] and few["whirl"] == ["forward"]
    assert few["critical_speeds"] and {(c["order"], c["whirl"]) for c in few["critical_speeds"]} == {(1, "forward")}
    assert {(c["order"], c["whirl"]) for c in every["critical_speeds"]} == {(1, "forward"), (1, "backward"),
                                                                            (2, "forward"), (2, "backward")}
    assert [c for c in every["critical_speeds"] if c["order"] == 1 and c["whirl"] == "forward"] == few["critical_speeds"]
    rows = _table(["rotor", "critical-speeds", "paper-table4", "--units", "rad/s"], capsys)
    assert [float(r.split()[1]) for r in rows[3:]] == pytest.approx(
        [c["speed_rad_s"] for c in few["critical_speeds"]], abs=0.05)


def test_unbalance_phase_of_an_undamped_rotor(capsys):
    crit = _json(["rotor", "critical-speeds", "verify-jeffcott", "--json"], capsys)["critical_speeds"][0]["speed_rpm"]
    d = _json(["rotor", "unbalance", "verify-jeffcott", "--points", "8", "--json"], capsys)
    rpm = d["speed_rpm"]
    assert min(rpm) < crit < max(rpm)
    y, z = d["y_phase_deg"]["d"], d["z_phase_deg"]["d"]
    for s, py, pz in zip(rpm, y, z):
        assert py == pytest.approx(0.0 if s < crit else 180.0, abs=1e-9)
        assert (py - pz) % 360.0 == pytest.approx(90.0, abs=1e-9)           # z lags y by a quarter turn
    assert d["y_amplitude_um"]["d"] == pytest.approx(d["z_amplitude_um"]["d"], rel=1e-12)
    assert d["y_amplitude_um"]["d"] == pytest.approx(d["semi_major_um"]["d"], rel=1e-12)   # a circle
