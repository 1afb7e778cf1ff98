"""``ringcontact fem3d`` job: one point as JSON, rotated tilt axis, clear errors."""
from __future__ import annotations

import json
import math

import pytest

from reports.cli import fem3d as cli3d


def _point(capsys, *args):
    rc = cli3d.main(["point", *args, "--level", "Q0", "--no-cache", "--json"])
    out = capsys.readouterr()
    return rc, out


def test_point_json_and_tilt_about_y(capsys):
    rc, out = _point(capsys, "0.01", "--tilt-arcmin", "2")
    assert rc == 0
    z = json.loads(out.out)
    rc, out = _point(capsys, "0.01", "--tilt-arcmin", "2", "--tilt-axis", "y")
    assert rc == 0
    y = json.loads(out.out)
    # same magnitudes, vectors rotated by 90 deg about x (docs/reference/contact-laws.md §1: M_y = -x F_z, M_z = x F_y)
    assert y["force_N"] == pytest.approx(z["force_N"], rel=1e-12)
    assert z["force_y_N"] < 0 and abs(z["force_z_N"]) < 1e-9 * z["force_N"]
    assert y["force_z_N"] == pytest.approx(z["force_y_N"], rel=1e-12) and abs(y["force_y_N"]) < 1e-9 * y["force_N"]
    assert z["moment_z_Nm"] < 0 and y["moment_y_Nm"] == pytest.approx(z["moment_z_Nm"], rel=1e-12)
    assert math.isfinite(z["force_N"]) and z["ndofs"] > 0
    assert not any(k.endswith(("_n", "_nm", "_pa")) for k in z), "JSON keys carry the unit symbol: force_N, moment_Nm"


@pytest.mark.parametrize("args, word", [
    (["point", "0.01", "--scene", "nope", "--level", "Q0"], "scene"),
    (["point", "0.01", "--level", "L9"], "level"),
    (["point", "nan", "--level", "Q0", "--no-cache"], "penetration"),
])
def test_point_errors_are_clear(capsys, args, word):
    from reports.cli import main
    rc = main(["fem3d", *args])
    err = capsys.readouterr().err
    assert rc == 2 and word in err
