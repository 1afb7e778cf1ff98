"""A ``simulate`` run's files are one unit: interrupted anywhere, no summary is left beside another run's CSV.

The unit test interrupts :func:`contact.files.write_run_files` at every write and every rename in
turn (the moments a crash, a full disk or Ctrl-C can strike) over a folder holding an earlier run,
and checks after each that the folder holds either no summary or a summary whose checksums match
the files present. The command-line test makes the second of two real runs fail while writing
its CSV and checks the same through ``check_run_files``, plus the one-line error and exit 1.
"""
from __future__ import annotations

import json
import os

import pytest

from contact import files as cf
from contact.errors import DatasetError
from contact.files import check_run_files, sha256_bytes, write_run_files


def _state(out) -> str:
    """'complete' (summary and matching files), 'none' (no summary); anything else fails the test."""
    if not (out / "simulate-summary.json").exists():
        return "none"
    summary = check_run_files(out, "simulate")                    # raises on a mismatched pair
    for name, want in summary["files"].items():
        assert sha256_bytes((out / name).read_bytes()) == want["sha256"]
    return "complete"


RUN_A = {"simulate.csv": b"t_s,y_m\n0,1\n", "simulate.npz": b"npz of run A"}
RUN_B = {"simulate.csv": b"t_s,y_m\n0,2\n1,3\n", "simulate.npz": b"npz of run B"}


@pytest.mark.parametrize("where", ["_temporary", "replace"])
def test_an_interruption_at_any_write_or_rename_leaves_no_mismatched_pair(tmp_path, monkeypatch, where):
    # the calls write_run_files makes for RUN_B: 2 temporaries + the summary's (3), or 2 renames + the summary's (3)
    for k in range(3):
        out = tmp_path / f"{where}-{k}"
        write_run_files(out, "simulate", {**RUN_A, "simulate.old-extra": b"a companion run B does not write"},
                        {"run": "A"})
        (out / "simulate.py").write_bytes(b"a user's file of the same prefix, described by no summary")
        calls = {"n": 0}
        real = cf._temporary if where == "_temporary" else os.replace

        def interrupted(*args, _real=real, _k=k):
            calls["n"] += 1
            if calls["n"] == _k + 1:
                raise OSError(28, "No space left on device")
            return _real(*args)
        monkeypatch.setattr(cf, "_temporary", interrupted) if where == "_temporary" else \
            monkeypatch.setattr(cf.os, "replace", interrupted)
        with pytest.raises(OSError):
            write_run_files(out, "simulate", RUN_B, {"run": "B"})
        monkeypatch.undo()
        assert calls["n"] == k + 1
        assert _state(out) == "none", f"interrupted at {where} #{k + 1}: a summary survived"
        # run A's files are gone with its summary (no stale companion a reader could pair), no temporary left
        left = {p.name: p.read_bytes() for p in out.iterdir() if p.name != "simulate.py"}
        assert all(RUN_B.get(name) == data for name, data in left.items()), sorted(left)
        assert not (out / "simulate.old-extra").exists()
        assert (out / "simulate.py").exists()                  # not a companion: left alone
        assert not list(out.glob(".*.tmp"))
        # the next uninterrupted run is complete and describes exactly its own files
        write_run_files(out, "simulate", RUN_B, {"run": "B"})
        assert _state(out) == "complete"
        assert json.loads((out / "simulate-summary.json").read_text())["run"] == "B"


def test_a_summary_never_vouches_for_a_changed_file(tmp_path):
    write_run_files(tmp_path, "simulate", RUN_A, {"run": "A"})
    assert check_run_files(tmp_path, "simulate")["files"]["simulate.csv"]["bytes"] == len(RUN_A["simulate.csv"])
    (tmp_path / "simulate.csv").write_bytes(RUN_B["simulate.csv"])       # another run's CSV put beside it
    with pytest.raises(DatasetError, match="simulate.csv is not the file this summary describes"):
        check_run_files(tmp_path, "simulate")
    (tmp_path / "simulate.csv").unlink()
    with pytest.raises(DatasetError, match="simulate.csv is missing"):
        check_run_files(tmp_path, "simulate")
    with pytest.raises(ValueError):
        write_run_files(tmp_path, "simulate", {"other.csv": b""}, {})


def test_simulate_interrupted_while_writing_its_csv(tmp_path, monkeypatch, capsys):
    from reports.cli import main

    out = tmp_path / "run"
    assert main(["simulate", "--speed-rpm", "10500", "--revolutions", "1", "--out", str(out)]) == 0
    first = check_run_files(out, "simulate")
    assert first["speed_rpm"] == 10500 and set(first["files"]) == {"simulate.csv", "simulate.npz"}
    assert json.loads(capsys.readouterr().out)["speed_rpm"] == 10500

    real = cf._temporary

    def full_disk(path, data):
        if path.name == "simulate.csv":
            raise OSError(28, "No space left on device")
        return real(path, data)
    monkeypatch.setattr(cf, "_temporary", full_disk)
    rc = main(["simulate", "--speed-rpm", "9000", "--revolutions", "1", "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 1
    assert err.count("\n") == 1 and err.startswith("ringcontact simulate: error: --out = ")
    assert "No space left on device" in err and "Traceback" not in err
    assert _state(out) == "none"                         # the 10 500 rpm summary did not survive beside new files
    assert not list(out.glob(".*.tmp"))
    monkeypatch.undo()
    assert main(["simulate", "--speed-rpm", "9000", "--revolutions", "1", "--out", str(out)]) == 0
    assert check_run_files(out, "simulate")["speed_rpm"] == 9000
