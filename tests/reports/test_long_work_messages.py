"""Long work speaks on a terminal, and a failure says what was tried and what to change (issue 26).

Progress (sweep/progress.py): the events of a shooting orbit (transient rounds, the residual of every Newton
iteration, each attempt) and of a branch (points, speed, time left) reach stderr with ``--progress`` or on a
terminal, never stdout: ``--json`` stays parseable. Failure: an orbit that does not converge prints one
paragraph naming its attempts and residuals (the numbers of the JSON's ``attempts``) and what to try instead
of the amplitude table of a non-converged iterate; ``branch`` says why there was no orbit at the start. The
failing orbit is a real one: paper-table4 at 15 000 rpm with the end faces free (``--mu 0``), whose orbit
needs 8 Newton iterations, shot with at most one iteration per attempt.
"""
from __future__ import annotations

import functools
import io
import json
import re

import pytest

from reports import cli
from sweep.progress import Elapsed, Events, report, reporting

FREE = ["paper-table4", "--speed-rpm", "15000", "--mu", "0"]
# a frictionless orbit whose Newton converges from the first transient (5 iterations, 0.7 s; measured): at 15 000 rpm
# the located map's transients find no orbit and the step-grid search is needed (rotor.studies.orbit, ~50 s)
QUICK = ["paper-table4", "--speed-rpm", "3000", "--mu", "0"]


class _FakeTTY(io.StringIO):
    def isatty(self):
        return True


def test_report_reaches_only_the_installed_listener():
    got = []
    report("newton", iteration=1, residual=0.5)               # no listener: nothing happens
    with reporting(lambda kind, f: got.append((kind, f))):
        report("newton", iteration=2, residual=0.25)
    report("newton", iteration=3, residual=0.125)
    assert got == [("newton", {"iteration": 2, "residual": 0.25})]


def test_events_show_residuals_and_keep_attempts_when_silent(monkeypatch):
    monkeypatch.delenv("CI", raising=False)
    tty, piped = _FakeTTY(), io.StringIO()
    shown, silent = Events("orbit", stream=tty), Events("orbit", stream=piped)
    attempt = {"period_revs": 1, "transient_revs": 24, "iterations": 1, "residual": 0.41, "converged": False}
    for ev in (shown, silent):
        ev("transient", {"revs": 24, "max_revs": 2000})
        ev("newton", {"iteration": 3, "residual": 4.32e-3})
        ev("attempt", attempt)
        ev.close()
    text = tty.getvalue()
    assert "transient 24/2000 rev" in text and "Newton iteration 3, residual 4.32e-03" in text
    assert "residual 4.10e-01, not converged" in text and text.endswith("\n")
    assert piped.getvalue() == "" and silent.attempts == shown.attempts == [attempt]


def test_branch_point_shows_speed_share_and_time_left():
    tty = _FakeTTY()
    ev = Events("branch", parameter_unit=("rpm", 2.0), stream=tty, enabled=True)
    ev.t0 -= 30.0                                                        # 30 s spent on a quarter of the range
    ev("branch_point", {"points": 5, "max_points": 400, "parameter": 150.0, "start": 100.0, "end": 300.0})
    # 25 % done in 30 s: 90 s left at that rate; the parameter shown times the unit factor 2
    assert "point 5 (at most 400) at 300.0 rpm, 25 % of the range, ~1m30s left" in tty.getvalue()
    ev("branch_point", {"points": 200, "max_points": 400, "parameter": 150.0, "start": 100.0, "end": 300.0})
    assert "point 200 (at most 400) at 300.0 rpm, 25 % of the range, ~0m30s left" in tty.getvalue()  # half the points


def test_elapsed_is_quiet_for_a_quick_step_and_counts_a_slow_one():
    import time
    quick = _FakeTTY()
    with Elapsed("simulate", "compiling", stream=quick, enabled=True):
        pass
    assert quick.getvalue() == ""
    slow = _FakeTTY()
    with Elapsed("simulate", "compiling", quiet_s=0.0, stream=slow, enabled=True):
        time.sleep(0.7)
    assert "simulate: 1 s (compiling)" in slow.getvalue() or "simulate: 0 s (compiling)" in slow.getvalue()
    assert "done in" in slow.getvalue() and slow.getvalue().endswith("\n")


def test_orbit_progress_on_stderr_never_in_json_stdout(capsys):
    assert cli.main(["orbit", *QUICK, "--json", "--progress"]) == 0
    out, err = capsys.readouterr()
    d = json.loads(out)                                              # stdout: the JSON alone
    assert "\r" not in out and "Newton iteration" in err and "residual" in err
    assert d["converged"] and d["attempts"][-1]["converged"] and d["attempts"][-1]["residual"] == d["residual"]
    assert cli.main(["orbit", *QUICK, "--json"]) == 0                # not a terminal, no --progress: silent
    assert capsys.readouterr().err == ""


@pytest.fixture
def one_iteration(monkeypatch):
    """Shooting with one Newton iteration per attempt, transient rounds of 24, 36 and 54 up to 60 revolutions."""
    import rotor.studies.orbit as ro
    from rotor.studies.orbit import ShootingOptions
    monkeypatch.setattr(ro, "orbit", functools.partial(ro.orbit, options=ShootingOptions(
        max_iter=1, transient_revs=24, max_transient_revs=60)))


def test_orbit_failure_says_what_was_tried_and_what_to_change(one_iteration, capsys):
    assert cli.main(["orbit", *FREE]) == 1
    out, err = capsys.readouterr()
    assert "1X mm/s" not in out                                      # no amplitudes of a non-converged iterate
    assert cli.main(["orbit", *FREE, "--json"]) == 1
    d = json.loads(capsys.readouterr().out)
    assert not d["converged"] and d["attempts"] and not any(a["converged"] for a in d["attempts"])
    residuals = ", ".join(f"{a['residual']:.2g}" for a in d["attempts"])
    assert f"{len(d['attempts'])} Newton attempts" in out and f"residuals {residuals}" in out
    assert "--period-revs" in out and f"--steps-per-rev {2 * d['steps_per_rev']}" in out
    assert "ringcontact simulate --scene paper-table4 --mu 0 --speed-rpm 15000 --steady" in out
    assert "--from-orbit FILE" in out          # an unstable orbit no transient settles on
    assert d["advice"] in out
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("ringcontact orbit: error: no periodic orbit at 15000 rpm")


def test_branch_says_why_there_was_no_orbit_at_the_start(one_iteration, capsys):
    assert cli.main(["branch", "paper-table4", "--rpm-start", "15000", "--rpm-end", "15100", "--mu", "0"]) == 1
    err = [ln for ln in capsys.readouterr().err.strip().splitlines()
           if not ln.startswith("ringcontact branch: estimated")]      # the work estimate (reports/cli/_budget.py)
    assert len(err) == 1 and re.match(r"ringcontact branch: error: no orbit at the start \(--rpm-start\): "
                                      r"no periodic orbit at 15000 rpm: [1-9] Newton attempts", err[0]), err
    assert "What to try: --period-revs" in err[0]


def test_cascade_marks_and_counts_points_not_converged(tmp_path, monkeypatch, capsys):
    """The bundled verify-jeffcott rotor has no damping: its transient never decays, so no speed converges
    within 24 revolutions; the summary counts them, the CSV says converged 0 and the figure rings them."""
    import reports.station_cascade as sc
    drawn = []
    real_save = sc.save
    monkeypatch.setattr(sc, "save", lambda fig, path: (drawn.append(fig), real_save(fig, path))[1])
    assert cli.main(["study", "cascade", "verify-jeffcott", "--rpm-min", "300", "--rpm-max", "900", "--points", "2",
                     "--max-revs", "24", "--workers", "1", "--no-progress", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "study cascade: 2 of 2 points not converged within --max-revs = 24 revolutions (at 300, 900 rpm)" in out
    rows = (tmp_path / "figures" / "cascade-stations.csv").read_text().splitlines()
    col = rows[0].split(",").index("converged")
    assert [r.split(",")[col] for r in rows[1:]] == ["0", "0"]
    labels = [ln.get_label() for ax in drawn[0].axes for ln in ax.get_lines()]
    assert "not converged (2 of 2)" in labels
