"""`ringcontact study` on damaged result directories (issue 15): exit 2 and one line naming the file
or the points, never a traceback and never a short publication with exit 0. Each failed before:
a damaged timing.json raised JSONDecodeError on every re-run, and `study publish` on a cascade
with two corrupted points published the rest with exit 0."""
import shutil

import pytest

from reports.cli.study import main

ARGS = ["--rpm-min", "0", "--rpm-max", "3000", "--points", "3", "--steps-per-rev", "64", "--max-revs", "100",
        "--workers", "1", "--no-progress"]


@pytest.fixture(scope="module")
def cascade(tmp_path_factory):
    out = tmp_path_factory.mktemp("cascade") / "run"
    assert main(["cascade", *ARGS, "--out", str(out)]) == 0
    return out


@pytest.fixture
def run(cascade, tmp_path):
    out = tmp_path / "run"
    shutil.copytree(cascade, out)
    (out / ".lock").unlink(missing_ok=True)
    return out


def test_damaged_timing_json_is_set_aside_and_the_run_goes_on(run, capsys):
    (run / "timing.json").write_text('[{"workers": 1, "wall')
    assert main(["cascade", *ARGS, "--out", str(run)]) == 0
    cap = capsys.readouterr()
    assert "0 computed, 3 reused" in cap.out and "timing.json: damaged" in cap.err
    assert len(list(run.glob("timing.json.damaged-*"))) == 1


def test_publish_refuses_a_cascade_with_corrupted_points(run, tmp_path, capsys):
    for key in ("rpm0.0", "rpm1500.0"):
        npz = run / "points" / f"{key}.npz"
        b = bytearray(npz.read_bytes())
        b[len(b) // 2] ^= 0xFF
        npz.write_bytes(bytes(b))
    pub = tmp_path / "published"
    assert main(["publish", "--cascade", str(run), "--to", str(pub)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "2 of 3 points missing or damaged" in err
    assert "rpm0.0 (corrupt" in err and "rpm1500.0 (corrupt" in err
    assert not (pub / "study-cascade.md").exists()


def test_publish_refuses_a_cascade_with_a_deleted_point(run, tmp_path, capsys):
    (run / "points" / "rpm3000.0.json").unlink()
    (run / "points" / "rpm3000.0.npz").unlink()
    assert main(["publish", "--cascade", str(run), "--to", str(tmp_path / "pub")]) == 2
    assert "rpm3000.0 (missing)" in capsys.readouterr().err
    assert main(["cascade", *ARGS, "--out", str(run)]) == 0
    cap = capsys.readouterr()
    assert "1 computed, 2 reused, 1 recomputed" in cap.out and "rpm3000.0: deleted" in cap.err


def test_damaged_sweep_json_is_refused_by_name(run, capsys):
    (run / "sweep.json").write_text("{oops")
    assert main(["cascade", *ARGS, "--out", str(run)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "sweep.json: damaged" in err
    assert (run / "sweep.json").read_text() == "{oops"
