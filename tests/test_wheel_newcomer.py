"""Issue 38, must show 1: the newcomer's walk-through from the wheel in a fresh venv (slow: the build, the bearing's
2D and 3D FEM, and numba compiling into an empty cache).

The newcomer writes their own bearing, a ring-pair file (docs/ring-scenes.rst): a steel ring R 40-45 mm, 20 mm wide,
in an aluminium housing to R 65 mm, radial clearance 0.03 mm, penetrations 0.004-0.04 mm and tilt to 2' [ISSUE 38];
and their own rotor: Friswell et al. (2010) Example 5.9.1 with its right bearing loose in the aluminium housing and
gravity on (tests/rotor/scenes/friswell-591-loose-aluminium.toml with the ring's geometry keys left out, so the
scene takes them from the law, as docs/rotor-scenes say a law file may). From the wheel's ``ringcontact``
(tests/test_wheel.py builds and installs it):

1. ``bearing my-bearing.toml`` writes the law file (with tilt: the law with its tilt correction, and beside it the
   straight law, the one the rotor scene names);
2. a law its file flags is refused by ``simulate`` and the API without the option (exit 2, one line; InputError):
   the flagged law is the written one with the warning ``bearing`` puts into ``provenance.warnings`` when a held-out
   error passes the bound (reports/bearing/pipeline.py), checksum redone, since whether this ring's own law passes
   is the FEM's answer, not the test's;
3. ``simulate --out`` and ``ringcontact.simulate`` on the same run: the validity record's contact-time shares equal;
4. the run starts at the static equilibrium: over its first revolution the loose station moves by less than 1 % of
   its static sag (the bound of issue 38);
5. the law follows the rotor (must show 2): where the run left the law's range (measured: 3.0 um, below its
   fitted 4 um, and 5.3' past its checked 2'), ``bearing --range-from`` the run gives a law whose range holds the
   rerun (or, flagged, says where no family holds).

Measured 2026-11-29: the first law verified (0.004-0.04 mm, 2'); the run at 3.00-3.03 um and 5.3'; the widened
range 0.0024-0.04 mm, 0-6.6' FLAGGED (held-out 2.85 % at zero tilt, 2.28 % tilted, both at 0.0024 mm, the range's
lowest point, named in not_held), the rerun 100 % inside and 5.3' within; 279 s in all at a load of about 6.
"""
from __future__ import annotations

import json
import re

import pytest

from contact.dataset import document_sha256
from tests.test_wheel import ROOT, _installed, _run

RING = """schema = "ringcontact.ring-scene/1"
name = "my-bearing"
description = "steel ring R 40-45 mm x 20 mm in an aluminium housing to R 65 mm, clearance 0.03 mm"
[bearing_ring]
inner_radius_mm = 40.0
outer_radius_mm = 45.0
width_mm = 20.0
youngs_modulus_gpa = 210.0
poisson_ratio = 0.3
[housing]
radial_clearance_mm = 0.03
outer_radius_mm = 65.0
youngs_modulus_gpa = 70.0
poisson_ratio = 0.33
hold = "clamped-outer-axially-free"
[drive]
bearing = "rigid-inner-axially-free"
[range]
penetration_mm = [0.004, 0.04]
tilt_arcmin = [0, 2]
"""
FLAG = "holdout_max_rel_3d_zero_tilt = 14.20 % is 12.80 % beyond the FEM's stated error, more than the bound 2 %"
GEOMETRY_KEYS = ("clearance_mm", "ring_width_mm", "bearing_modulus_gpa", "bearing_poisson_ratio",
                 "support_modulus_gpa", "support_poisson_ratio")
RPM = 300
DRIVER = """\
import json, sys
import ringcontact as rc
out = {"file": rc.__file__}
try:
    rc.simulate("flagged.toml", %(rpm)s, revolutions=1)
    out["flagged"] = "ran"
except rc.InputError as e:
    out["flagged"] = str(e)
res = rc.simulate("scene.toml", %(rpm)s, revolutions=1%(allow)s)
i = list(res.channels).index("N6.y")
y = res.displacement_m[:, i]
out.update(law_validity=res.law_validity, sag_m=abs(float(y[0])), moved_m=float(abs(y - y[0]).max()))
print(json.dumps(out), file=sys.stderr)
"""


def _scene(law: str) -> str:
    text = (ROOT / "tests" / "rotor" / "scenes" / "friswell-591-loose-aluminium.toml").read_text(encoding="utf-8")
    text = text.replace('law = "conformal"', f'law = "{law}"')
    for key in GEOMETRY_KEYS:
        text = re.sub(rf"^{key} = .*\n", "", text, flags=re.M)
    return text + "\n[gravity]\nacceleration_y_m_per_s2 = -9.81\n"


@pytest.mark.slow
def test_the_newcomers_walkthrough_from_the_wheel(tmp_path):
    venv, py, env, site_packages, work = _installed(tmp_path)
    exe = venv / "bin" / "ringcontact"
    (work / "my-bearing.toml").write_text(RING, encoding="utf-8")
    _run([exe, "bearing", "my-bearing.toml", "--out", "brg", "--workers", "2"], cwd=work, env=env)
    # with tilt the law file carries the tilt correction; the rotor names the straight law written beside it
    corrected = json.loads((work / "brg" / "my-bearing-law.json").read_text(encoding="utf-8"))
    assert corrected["provenance"]["tilt_correction"]["chosen"] and corrected["provenance"]["rotor_note"]
    law = json.loads((work / "brg" / "my-bearing-law-straight.json").read_text(encoding="utf-8"))
    assert law["provenance"]["ring_scene"]["name"] == "my-bearing" and law["provenance"]["rotor_kernel"]
    (work / "my-law.json").write_text(json.dumps(law), encoding="utf-8")
    flagged = dict(law, provenance={**law["provenance"], "warnings": [FLAG]})
    flagged.pop("sha256")
    flagged["sha256"] = document_sha256(flagged)
    (work / "flagged-law.json").write_text(json.dumps(flagged), encoding="utf-8")
    (work / "scene.toml").write_text(_scene("my-law.json"), encoding="utf-8")
    (work / "flagged.toml").write_text(_scene("flagged-law.json"), encoding="utf-8")
    verdict = "flagged" if law["provenance"]["warnings"] else "verified"
    allow = ["--allow-flagged-law"] if verdict == "flagged" else []

    # 2. refused without the option: the command line (one line, exit 2) and the API
    import subprocess
    proc = subprocess.run([str(exe), "simulate", "--scene", "flagged.toml", "--speed-rpm", str(RPM), "--revolutions",
                           "1", "--out", "refused"], cwd=work, env=env, capture_output=True, text=True, timeout=600)
    err = proc.stderr.strip().splitlines()
    assert proc.returncode == 2 and len(err) == 1 and "FLAGGED" in err[0] and "--allow-flagged-law" in err[0], err
    assert "Traceback" not in proc.stderr and not (work / "refused").exists()

    # 3. the same run through the command line and the API: the same record
    _run([exe, "simulate", "--scene", "scene.toml", "--speed-rpm", str(RPM), "--revolutions", "1", "--out", "run",
          *allow], cwd=work, env=env)
    cli_rec = json.loads((work / "run" / "simulate-summary.json").read_text(encoding="utf-8"))["law_validity"]
    (work / "driver.py").write_text(DRIVER % {"rpm": RPM, "allow": ", allow_flagged_law=True" if allow else ""},
                                    encoding="utf-8")
    d = json.loads(_run([py, "driver.py"], cwd=work, env=env).stderr.strip().splitlines()[-1])
    assert d["file"].startswith(str(site_packages))
    assert "FLAGGED" in d["flagged"] and "allow_flagged_law=True" in d["flagged"], d["flagged"]
    api_rec = d["law_validity"]
    print(json.dumps({k: v for k, v in cli_rec.items() if k != "warnings"}, indent=1), d["sag_m"], d["moved_m"])
    assert cli_rec["verdict"] == api_rec["verdict"] == verdict and cli_rec["contact_time_share"] > 0
    for key in ("contact_time_share", "contact_time_share_below", "contact_time_share_inside",
                "contact_time_share_above", "visited_penetration_range_m", "largest_tilt_rad", "law_sha256"):
        assert cli_rec[key] == api_rec[key], key

    # 4. started at equilibrium: the first revolution moves the loose station by under 1 % of its sag
    assert d["sag_m"] > 10 * 30e-6                      # many clearances: the start matters
    assert d["moved_m"] < 0.01 * d["sag_m"], (d["moved_m"], d["sag_m"])

    # 5. the law follows the rotor: the run's visited range into `bearing --range-from`, the rerun inside the new law
    if cli_rec["contact_time_share_inside"] == 1.0 and not cli_rec["beyond_tilt_range"]:
        return                                          # already inside: nothing to follow
    _run([exe, "bearing", "my-bearing.toml", "--out", "brg", "--workers", "2", "--range-from", "run"], cwd=work, env=env)
    wider = json.loads((work / "brg" / "summary.json").read_text(encoding="utf-8"))
    print(json.dumps({k: wider[k] for k in ("validity_penetration_mm", "validity_tilt_max_arcmin", "warnings",
                                            "not_held")}))
    (work / "my-law.json").write_bytes((work / "brg" / "my-bearing-law-straight.json").read_bytes())
    allow = ["--allow-flagged-law"] if wider["warnings"] else []
    _run([exe, "simulate", "--scene", "scene.toml", "--speed-rpm", str(RPM), "--revolutions", "1", "--out", "rerun",
          *allow], cwd=work, env=env)
    again = json.loads((work / "rerun" / "simulate-summary.json").read_text(encoding="utf-8"))["law_validity"]
    print(json.dumps({k: v for k, v in again.items() if k != "warnings"}))
    assert again["contact_time_share_inside"] == 1.0 and again["beyond_tilt_range"] is False, again["warnings"]
    if wider["warnings"]:               # flagged on the wider range: the summary says where no family holds
        assert wider["not_held"] or any("no law family" in w for w in wider["warnings"])
