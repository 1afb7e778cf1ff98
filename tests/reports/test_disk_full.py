"""A full disk is one line naming the path, exit status 1, never an internal error (issue 40).

ENOSPC is simulated by making the job's write raise ``OSError(28)``: ``bearing`` (its pipeline's first write)
and ``simulate`` (the run's files, written as one unit with the summary last).
"""
from __future__ import annotations

import errno
import os

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
    err = capsys.readouterr().err.strip()
    assert rc == 1 and err.count("\n") == 0 and "internal error" not in err, err
    assert str(target) in err and os.strerror(errno.ENOSPC) in err and "no summary" in err, err


def test_simulate_on_a_full_disk_writes_no_summary(tmp_path, monkeypatch, capsys):
    import contact.files as files
    monkeypatch.setattr(files, "atomic_write_bytes", _enospc(tmp_path / "o" / "simulate.npz"))
    monkeypatch.setattr(files, "atomic_write_text", _enospc(tmp_path / "o" / "simulate-summary.json"))
    rc = cli.main(["simulate", "--speed-rpm", "3000", "--revolutions", "1", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 1 and len(err) == 1 and "internal error" not in err[0], err
    assert os.strerror(errno.ENOSPC) in err[0] and not (tmp_path / "o" / "simulate-summary.json").exists()
