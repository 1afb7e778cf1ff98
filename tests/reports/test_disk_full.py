"""A full disk is one line naming the path, exit status 1, never an internal error (issue 40).

ENOSPC is simulated by making the job's write raise ``OSError(28)``: ``bearing`` (its pipeline's first write)
and ``simulate`` (the run's files, written as one unit with the summary last).
"""
from __future__ import annotations

import errno
import os

import pytest

from reports import cli


def _enospc(path="x"):
    def fail(*args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))
    return fail


def test_bearing_on_a_full_disk_says_so_in_one_line(tmp_path, monkeypatch, capsys):
    import reports.bearing.pipeline as pipeline
    target = tmp_path / "o" / "steel-in-aluminium-law.json"
    monkeypatch.setattr(pipeline, "run", _enospc(target))
    rc = cli.main(["bearing", "steel-in-aluminium", "--out", str(tmp_path / "o")])
    lines = capsys.readouterr().err.strip().splitlines()
    # the work's estimate (above a minute with the tilt correction's grids) is announced before it starts
    assert all(line.startswith("ringcontact bearing: estimated ") for line in lines[:-1]) and len(lines) <= 2, lines
    err = lines[-1]
    assert rc == 1 and "internal error" not in err, err
    assert str(target) in err and os.strerror(errno.ENOSPC) in err and "no summary" in err, err


def test_simulate_on_a_full_disk_writes_no_summary(tmp_path, monkeypatch, capsys):
    import contact.files as files
    monkeypatch.setattr(files, "atomic_write_bytes", _enospc(tmp_path / "o" / "simulate.npz"))
    monkeypatch.setattr(files, "atomic_write_text", _enospc(tmp_path / "o" / "simulate-summary.json"))
    rc = cli.main(["simulate", "--speed-rpm", "3000", "--revolutions", "1", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 1 and len(err) == 1 and "internal error" not in err[0], err
    assert os.strerror(errno.ENOSPC) in err[0] and not (tmp_path / "o" / "simulate-summary.json").exists()


def _fsync_enospc(*args):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))     # as a full disk raises it: no file name


@pytest.mark.parametrize("argv", [
    ["calibrate", "--out", "{o}"],
    ["rotor", "response", "verify-jeffcott", "--speed-rpm", "1000", "--revolutions", "2", "--out", "{o}"],
    ["rotor", "campbell", "verify-jeffcott", "--points", "3", "--plot", "{o}/c"],
    ["rotor", "unbalance", "verify-jeffcott", "--points", "3", "--plot", "{o}/u"],
    ["rotor", "modes", "verify-jeffcott", "--plot", "{o}/m"],
], ids=lambda a: " ".join(a[:2]))
def test_a_full_disk_is_one_line_naming_the_path(tmp_path, monkeypatch, capsys, argv):
    """A write that fails as a full disk fails (in fsync, no file name): one line naming the file in the output
    folder, exit 1, no temporary and no half-written file left."""
    out = tmp_path / "o"
    out.mkdir()
    monkeypatch.setattr(os, "fsync", _fsync_enospc)
    rc = cli.main([a.replace("{o}", str(out)) for a in argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 1 and len(err) == 1 and "internal error" not in err[0], err
    assert f"could not write {out}/" in err[0] and os.strerror(errno.ENOSPC) in err[0], err
    assert list(out.rglob("*")) == [], sorted(out.rglob("*"))
