"""Dampers have plausible ranges like every other scene key (issue 40: ``damping_yz = 1e300`` was accepted and
lost): each refused in one line naming the file, the entry, the key and the value with its unit."""
from __future__ import annotations

import pytest

from reports import cli
from rotor.model.scene import scene_path

KEYS = [("damping_n_s_per_m", v) for v in ("1e300", "1e11", "-5")] + \
       [(k, v) for k in ("damping_yy_n_s_per_m", "damping_zz_n_s_per_m") for v in ("1e12", "-1")] + \
       [(k, v) for k in ("damping_yz_n_s_per_m", "damping_zy_n_s_per_m") for v in ("1e300", "-1e300", "2e10")] + \
       [("angular_stiffness_n_m_per_rad", "1e15"), ("angular_damping_n_m_s_per_rad", "1e12")]


@pytest.mark.parametrize("key,value", KEYS)
def test_a_damper_out_of_range_is_refused(key, value, tmp_path, capsys):
    text = scene_path("verify-jeffcott").read_text(encoding="utf-8").replace(
        "stiffness_n_per_m = 2.0e6\n", f"stiffness_n_per_m = 2.0e6\n{key} = {value}\n", 1)
    (tmp_path / "s.toml").write_text(text, encoding="utf-8")
    rc = cli.main(["rotor", "modes", str(tmp_path / "s.toml")])
    out = capsys.readouterr()
    line = out.err.strip()
    assert rc == 2 and "\n" not in line and out.out == "", out.err
    assert f"s.toml: bearings[0].{key} = {float(value):g}" in line and "must be" in line, line
