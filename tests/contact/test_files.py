"""Temporaries of the atomic writers: named with their writer's pid, removed when their writer is gone.

Measured before: kill -9 of ``report`` left ``.laws-vs-paper.csv.*.tmp`` and of ``fem-vtu`` an 808 kB
``.out.vtu.*.tmp`` that no later run removed (the names carried no writer to check).
"""
from __future__ import annotations

import os
import stat
import subprocess
import time

import pytest

from contact import files
from contact.files import atomic_write_bytes, atomic_write_via, discard_own_temporaries, remove_stale_temporaries


def _dead_pid() -> int:
    p = subprocess.Popen(["true"])
    p.wait()
    return p.pid


def test_only_temporaries_of_gone_writers_are_removed(tmp_path):
    dead = tmp_path / f".a.csv.{_dead_pid()}.x1y2z3w4.tmp"
    live = tmp_path / f".a.csv.{os.getpid()}.x1y2z3w4.tmp"
    old = tmp_path / ".a.csv.q9w8e7r6.tmp"              # no pid (an older version's name): by its age
    young = tmp_path / ".b.csv.q9w8e7r6.tmp"
    foreign = [tmp_path / ".tmp", tmp_path / ".x.tmp", tmp_path / "a.csv.tmp", tmp_path / ".a.csv.1.tmpx"]
    for p in [dead, live, old, young, *foreign]:
        p.write_bytes(b"x")
    os.utime(old, (time.time() - files.STALE_AFTER_S - 60,) * 2)
    assert sorted(p.name for p in remove_stale_temporaries(tmp_path)) == sorted([dead.name, old.name])
    assert live.exists() and young.exists() and all(p.exists() for p in foreign)
    assert sorted(p.name for p in remove_stale_temporaries(tmp_path, max_age_s=0)) == sorted([live.name, young.name])


def test_the_first_write_into_a_folder_clears_it_and_names_its_temporary_with_the_pid(tmp_path, monkeypatch):
    monkeypatch.setattr(files, "_SWEPT", set())
    left = tmp_path / f".old.json.{_dead_pid()}.abcdefgh.tmp"
    left.write_bytes(b"half")
    seen = []
    real = os.replace
    monkeypatch.setattr(files.os, "replace", lambda a, b: (seen.append(os.path.basename(a)), real(a, b))[1])
    atomic_write_bytes(tmp_path / "new.json", b"{}")
    assert not left.exists() and (tmp_path / "new.json").read_bytes() == b"{}"
    assert seen[0].startswith(f".new.json.{os.getpid()}.") and seen[0].endswith(".tmp")


def test_a_library_writing_to_a_name_writes_atomically(tmp_path):
    out = tmp_path / "sub" / "m.vtu"
    atomic_write_via(out, lambda name: open(name, "w").write("<VTKFile/>"))
    assert out.read_text() == "<VTKFile/>" and stat.S_IMODE(out.stat().st_mode) == 0o666 & ~_umask()
    with pytest.raises(ZeroDivisionError):
        atomic_write_via(tmp_path / "sub" / "n.vtu", lambda name: 1 / 0)
    assert sorted(p.name for p in out.parent.iterdir()) == ["m.vtu"]


def test_an_interruption_removes_the_temporaries_this_process_holds(tmp_path):
    held = []

    def interrupted(name):
        held.append(name)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        atomic_write_via(tmp_path / "a.bin", interrupted)
    assert not os.path.exists(held[0])                    # the writer's own clean-up
    fd, name = files.tempfile.mkstemp(prefix=".b.bin.", suffix=".tmp", dir=tmp_path)
    os.close(fd)
    files._LIVE.add(name)                                 # as if the signal struck between create and clean-up
    assert discard_own_temporaries() == [name] and not os.path.exists(name)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
