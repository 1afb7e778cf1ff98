"""Provenance stamps (sweep.provenance): code revision, package versions, machine."""
import re
import subprocess

import pytest

from sweep import code_revision, environment, package_versions, revision_label
from sweep.provenance import ROOT, utc_stamp


def test_code_revision_names_the_checked_out_commit():
    head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    rev = code_revision()
    if not head:
        pytest.skip("not a git checkout")
    assert rev["git_commit"] == head and isinstance(rev["git_dirty"], bool)


def test_scoped_revision_sees_only_its_paths(tmp_path):
    subprocess.run(["git", "init", "-q"], cwd=tmp_path, check=True)
    for d in ("a", "b"):
        (tmp_path / d).mkdir()
        (tmp_path / d / "f.txt").write_text("1\n")
    subprocess.run(["git", "add", "a", "b"], cwd=tmp_path, check=True)
    subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "x"], cwd=tmp_path,
                   check=True)
    (tmp_path / "b" / "f.txt").write_text("2\n")
    (tmp_path / "a" / "new.txt").write_text("untracked\n")
    assert code_revision(tmp_path)["git_dirty"] is True
    assert code_revision(tmp_path, scope=["a"])["git_dirty"] is False
    assert code_revision(tmp_path, scope=["a"], untracked=True)["git_dirty"] is True
    rev = code_revision(tmp_path, scope=["b"])
    assert revision_label(rev) == rev["git_commit"] + "+dirty" and len(rev["git_commit"]) == 40
    assert revision_label({"git_commit": "unknown", "git_dirty": None}) == "unknown"


def test_package_versions_record_names_and_required_modules():
    v = package_versions({"numpy": "numpy", "scikit-fem": "skfem"})
    assert list(v) == ["python", "numpy", "scikit-fem"] and re.match(r"\d+\.\d+", v["scikit-fem"])
    with pytest.raises(ImportError):
        package_versions(["no_such_module_xyz"])
    assert package_versions(["no_such_module_xyz"], required=False)["no_such_module_xyz"] is None
    env = environment()
    assert set(env) == {"python", "numpy", "machine", "cpu_count", "scipy", "numba"}
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", utc_stamp())
