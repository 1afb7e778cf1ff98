"""``ringcontact fem3d`` job: one point as JSON, rotated tilt axis, clear errors."""
from __future__ import annotations

import json
import math

import pytest

from reports.cli import fem3d as cli3d


def _point(capsys, *args):
    rc = cli3d.main(["point", *args, "--level", "L0", "--no-cache", "--json"])
    out = capsys.readouterr()
    return rc, out


def test_point_json_and_tilt_about_y(capsys):
    rc, out = _point(capsys, "0.01", "--tilt-arcmin", "2")
    assert rc == 0
    z = json.loads(out.out)
    rc, out = _point(capsys, "0.01", "--tilt-arcmin", "2", "--tilt-axis", "y")
    assert rc == 0
    y = json.loads(out.out)
    # same magnitudes, vectors rotated by 90 deg about x (contact-laws.md §1: M_y = -x F_z, M_z = x F_y)
    assert y["force_n"] == pytest.approx(z["force_n"], rel=1e-12)
    assert z["force_y_n"] < 0 and abs(z["force_z_n"]) < 1e-9 * z["force_n"]
    assert y["force_z_n"] == pytest.approx(z["force_y_n"], rel=1e-12) and abs(y["force_y_n"]) < 1e-9 * y["force_n"]
    assert z["moment_z_nm"] < 0 and y["moment_y_nm"] == pytest.approx(z["moment_z_nm"], rel=1e-12)
    assert math.isfinite(z["force_n"]) and z["ndofs"] > 0


@pytest.mark.parametrize("args, word", [
    (["point", "0.01", "--scene", "nope", "--level", "L0"], "scene"),
    (["point", "0.01", "--level", "L9"], "level"),
    (["point", "nan", "--level", "L0", "--no-cache"], "penetration"),
])
def test_point_errors_are_clear(capsys, args, word):
    rc = cli3d.main(args)
    err = capsys.readouterr().err
    assert rc == 2 and word in err
