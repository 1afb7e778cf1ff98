"""The cross-module numba cache guard drops stale entries when a dependency changes."""
from pathlib import Path

from rotor.dynamics._numba_cache import drop_stale_cache


def test_stale_cache_entries_dropped_when_dependency_changes(tmp_path, monkeypatch):
    pkg = tmp_path / "fakepkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    dep = pkg / "dep.py"
    dep.write_text("X = 1\n")
    owner = pkg / "owner.py"
    owner.write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    cache = pkg / "__pycache__"
    cache.mkdir()
    entry = cache / "owner.kernel-10.py311.nbi"
    entry.write_text("old machine code")
    assert drop_stale_cache(str(owner), ["fakepkg.dep"]) is True   # first sight: no stamp yet
    assert not entry.exists()
    entry.write_text("fresh machine code")
    assert drop_stale_cache(str(owner), ["fakepkg.dep"]) is False  # unchanged dependency
    assert entry.exists()
    dep.write_text("X = 2\n")
    assert drop_stale_cache(str(owner), ["fakepkg.dep"]) is True   # changed dependency
    assert not entry.exists()
    assert Path(cache / "owner.deps.sha256").read_text()
