"""``orbit`` and ``branch`` call an unstable rotor unstable (issue 40): the Table 4 rotor with its bearing1
cross-coupled (``k_yz = -k_zy`` = 1e7 N/m, the case of tests/rotor/linear/test_stability.py) is said unstable in one
warning line before the work, naming the mode, and its divergence is blamed on the rotor, not the contact law; a
stable rotor (a Jeffcott-ring scene of rotor/periodic/jeffcott_scene.py) says nothing and its JSON's ``stability`` is
stable. Expected mode: :func:`rotor.linear.stability.linearisation_unstable` on the same model (the damped
eigenproblem, checked against the modes in tests/rotor/linear/test_stability.py)."""
from __future__ import annotations

import json

import pytest
from unstable_scenes import table4_cross_coupled

from reports import cli
from rotor.linear.stability import linearisation_unstable
from rotor.model.assembly import assemble
from rotor.model.scene import load_scene
from rotor.periodic.jeffcott_scene import JeffcottRing, scene_toml


@pytest.mark.parametrize("job,extra", [("orbit", ["--speed-rpm", "3000"]),
                                       ("branch", ["--rpm-start", "3000", "--rpm-end", "3100", "--max-points", "3"])])
def test_orbit_and_branch_say_unstable_and_blame_the_rotor(job, extra, tmp_path, capsys):
    scene = table4_cross_coupled(tmp_path, 1e7)
    found = linearisation_unstable(assemble(load_scene(scene)), 3000 * 3.141592653589793 / 30)
    assert found is not None and found.damping_ratio < 0
    rc = cli.main([job, str(scene), *extra, "--json", "--accept-long"])
    out, err = capsys.readouterr()
    lines = err.strip().splitlines()
    assert "warning: unstable rotor" in lines[0] and f"mode {found.mode}" in lines[0], err
    assert "not the contact law" in lines[0]
    if rc == 0:                          # an orbit found all the same: its JSON says the rotor is unstable
        assert json.loads(out)["stability"]["stable"] is False
    else:                                # the divergence's one line blames the rotor
        assert "the rotor is unstable" in lines[-1] and "whatever the contact law" in lines[-1], err
        assert "use a larger clearance" not in lines[-1]


def test_a_stable_rotor_says_nothing_and_its_json_says_stable(tmp_path, capsys):
    scene = tmp_path / "ring.toml"
    scene.write_text(scene_toml(JeffcottRing()), encoding="utf-8")
    assert cli.main(["orbit", str(scene), "--speed-rpm", "600", "--json"]) == 0
    out, err = capsys.readouterr()
    assert "unstable" not in err and json.loads(out)["stability"] == {"stable": True, "unstable_mode": None}


@pytest.mark.parametrize("job,extra", [("orbit", ["--speed-rpm", "600"]),
                                       ("branch", ["--rpm-start", "600", "--rpm-end", "620", "--max-points", "5"])])
def test_orbit_and_branch_on_a_full_disk_say_so_in_one_line(job, extra, tmp_path, monkeypatch, capsys):
    """A full disk (fsync failing as one does: no file name) at the ``--out`` file: one line naming it, exit 1,
    nothing left in the folder (issue 40; the dispatcher's handler, tests/reports/test_disk_full.py)."""
    import errno
    import os

    scene = tmp_path / "ring.toml"
    scene.write_text(scene_toml(JeffcottRing()), encoding="utf-8")
    out = tmp_path / "o"
    out.mkdir()

    def full(*args):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fsync", full)
    rc = cli.main([job, str(scene), *extra, "--out", str(out / "r.json"), "--json"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 1 and "internal error" not in err[-1] and f"could not write {out}/r.json" in err[-1], err
    assert list(out.iterdir()) == []


def test_a_study_of_an_unstable_rotor_says_so_before_its_points(tmp_path, capsys):
    scene = table4_cross_coupled(tmp_path, 1e7)
    found = linearisation_unstable(assemble(load_scene(scene)), 3000 * 3.141592653589793 / 30)
    cli.main(["study", "cascade", "--scene", str(scene), "--rpm-min", "3000", "--rpm-max", "3000", "--points", "1",
              "--out", str(tmp_path / "c")])
    err = capsys.readouterr().err
    warn = [ln for ln in err.splitlines() if "warning: unstable rotor" in ln]
    assert len(warn) == 1 and f"mode {found.mode}" in warn[0] and "not by the contact law" in warn[0], err


def test_fem_vtu_on_a_full_disk_says_so_in_one_line(tmp_path, monkeypatch, capsys):
    """The FEM jobs write through the same atomic writes and dispatcher (issue 40): a full disk at fem-vtu's
    output is one line naming it, nothing left (one coarse point, 4 mm elements)."""
    import errno
    import os

    out = tmp_path / "o"
    out.mkdir()

    def full(*args):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fsync", full)
    rc = cli.main(["fem-vtu", "0.01", str(out / "p.vtu"), "--h-mm", "4"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 1 and "internal error" not in err[-1] and f"could not write {out}/p.vtu" in err[-1], err
    assert list(out.iterdir()) == []


@pytest.mark.parametrize("argv", [["study", "cascade", "--rpm-min", "3000", "--rpm-max", "3000", "--points", "1",
                                   "--out", "{o}/c"],
                                  ["study", "point", "--speed-rpm", "3000", "--out", "{o}/p"],
                                  ["report", "--out", "{o}", "--only", "accuracy"]], ids=lambda a: " ".join(a[:2]))
def test_studies_and_reports_on_a_full_disk_say_so_in_one_line(argv, tmp_path, monkeypatch, capsys):
    """Study and report jobs on a full disk: one line naming the file, exit 1, no data file left (a study's folder
    keeps only its writer's lock, which the next writer takes over: sweep/guard.py)."""
    import errno
    import os

    out = tmp_path / "o"
    out.mkdir()

    def full(*args):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fsync", full)
    rc = cli.main([a.replace("{o}", str(out)) for a in argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 1 and "internal error" not in err[-1] and f"could not write {out}/" in err[-1], err
    assert [p for p in out.rglob("*") if p.is_file() and p.name != ".lock"] == []
