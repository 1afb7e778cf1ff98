"""Every job that runs the rotor takes the same scene argument and the same loose-support overrides
(reports/cli/_scene_options.py), with the same defaults, and an override gives the answer of the same value
written into the scene file.

Parse level: every command of the ``JOBS`` table (reports/cli/__init__.py) is walked; the commands that
run a scene must be exactly :data:`ROTOR_COMMANDS`, each parses the scene in both spellings and the
overrides to the same :class:`~reports.cli._scene_options.SceneChoice`, with identical option strings and
defaults. End to end (lean): simulate, orbit, branch and ``rotor unbalance`` run once with the overrides
and once on a scene file holding the same values, and must agree to the last digit (the override and the
file reach the same code: rotor.dynamics.build.system_from_model); every study builds its points' tasks with
the overrides (one computed: it used the law and clearance), the whole ``study cascade`` run is the slow case;
the linear jobs refuse what a locked support cannot apply.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import pytest

from reports import cli
from reports.cli import JOBS
from reports.cli._scene_options import DEFAULT_SCENE, MAX_TRANSIENT_REVS, OVERRIDES, SceneChoice, finish, scene_from_args

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "docs" / "_ext"))
from cli_parsers import job_parsers, subparsers  # noqa: E402

#: every command that runs the rotor (linear or time integration) on a scene
ROTOR_COMMANDS = {"rotor modes", "rotor campbell", "rotor critical-speeds", "rotor unbalance", "rotor response",
                  "rotor static",
                  "simulate", "orbit", "branch", "study cascade", "study point", "study params", "study testrig",
                  "study map", "study runup", "study readings"}
#: the commands that detect a steady state and so take --max-revs
TRANSIENT_COMMANDS = {"simulate", "study cascade", "study point", "study params", "study testrig", "study map",
                      "study runup", "study readings"}
#: what each command needs besides the scene to parse
REQUIRED = {"simulate": ["--speed-rpm", "3000"], "orbit": ["--speed-rpm", "3000"],
            "branch": ["--rpm-start", "3000", "--rpm-end", "3010"], "rotor response": ["--speed-rpm", "3000"]}
OVERRIDE_ARGS = ["--law", "pereira", "--mu", "0.2", "--preload-N", "3000", "--clearance-mm", "0.08",
                 "--misalignment-mm", "1", "--tilt-ignored"]
#: the same values in SI, as the keywords of rotor.studies.steady_state.point_system
OVERRIDE_SI = {"law": "pereira", "mu": 0.2, "preload_n": 3000.0, "clearance_m": 0.08e-3, "misalignment_m": 1e-3,
               "tilt_ignored": True}


def _commands() -> dict[str, tuple[argparse.ArgumentParser, argparse.ArgumentParser]]:
    """``command -> (top parser, the command's parser)`` for every command of the JOBS table."""
    out = {}
    for job in JOBS:
        for name, top in job_parsers(job):
            subs = subparsers(top)
            for sub, p in subs or [(None, top)]:
                out[f"{name.removeprefix('ringcontact ')}{' ' + sub if sub else ''}"] = (top, p)
    return out


COMMANDS = _commands()


def _parse(command: str, argv: list[str]) -> argparse.Namespace:
    top, _ = COMMANDS[command]
    words = command.split()
    args = top.parse_args([*words[1:], *argv])
    return finish(top, args, sub=words[1] if len(words) > 1 else None)


def test_the_commands_that_run_a_scene_are_exactly_the_rotor_commands():
    takes_scene = {c for c, (_, p) in COMMANDS.items() if any(a.dest == "scene_positional" for a in p._actions)}
    assert takes_scene == ROTOR_COMMANDS
    assert {c.split()[0] for c in ROTOR_COMMANDS} <= set(JOBS)


@pytest.mark.parametrize("command", sorted(ROTOR_COMMANDS))
def test_same_scene_spellings_and_overrides(command, tmp_path):
    scene = str(tmp_path / "my-rotor.toml")
    extra = REQUIRED.get(command, [])
    by_position = scene_from_args(_parse(command, [scene, *extra, *OVERRIDE_ARGS]))
    by_option = scene_from_args(_parse(command, [*extra, "--scene", scene, *OVERRIDE_ARGS]))
    assert by_position == by_option == SceneChoice(scene, OVERRIDE_SI)
    assert scene_from_args(_parse(command, extra)) == SceneChoice(
        "paper-table5-testrig" if command == "study testrig" else DEFAULT_SCENE, {})
    assert _parse(command, [*extra, "--preload-n", "3000"]).preload_n == 3000.0     # the older spelling


@pytest.mark.parametrize("command", sorted(ROTOR_COMMANDS))
def test_same_option_strings_and_defaults(command):
    def table(p):
        return {s: (a.dest, a.default, a.type.__name__ if a.type else None) for a in p._actions
                for s in a.option_strings if s in OVERRIDES or s in ("--scene", "--preload-n", "--max-revs")}
    got, ref = table(COMMANDS[command][1]), table(COMMANDS["simulate"][1])
    if command not in TRANSIENT_COMMANDS:
        ref.pop("--max-revs")
    assert got == ref


@pytest.mark.parametrize("command", sorted(TRANSIENT_COMMANDS))
def test_one_transient_cap(command):
    args = _parse(command, REQUIRED.get(command, []))
    from reports.cli._scene_options import max_revs
    assert args.max_revs is None and max_revs(args) == MAX_TRANSIENT_REVS == 8000


def test_two_different_scenes_are_refused(capsys):
    assert cli.main(["orbit", "a.toml", "--scene", "b.toml", "--speed-rpm", "3000"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--scene = b.toml" in err[0] and "a.toml" in err[0]


# ---------------------------------------------------------------- end to end

#: paper-table4 with the values of the overrides written into [loose_support]
EDITS = {"clearance_mm = 0.05\n": "clearance_mm = 0.08\nlaw = \"pereira\"\n", "friction_coefficient = 0.3\n":
         "friction_coefficient = 0.2\n", "preload_n = 5000\n": "preload_n = 3000\n"}
OVERRIDES_E2E = ["--law", "pereira", "--clearance-mm", "0.08", "--mu", "0.2", "--preload-N", "3000",
                 "--misalignment-mm", "1"]       # 1 mm: the scene's own offset (a scale of 1)


@pytest.fixture(scope="module")
def edited_scene(tmp_path_factory) -> Path:
    text = (ROOT / "rotor/scenes/paper-table4.toml").read_text(encoding="utf-8")
    for old, new in EDITS.items():
        assert text.count(old) == 1
        text = text.replace(old, new)
    path = tmp_path_factory.mktemp("scene") / "table4-edited.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _run(argv) -> int:
    return cli.main([str(a) for a in argv])


def _same(a: dict, b: dict, skip=("wall_s", "compile_s", "run_s", "compiled_from_cache", "files")) -> None:
    for d in (a, b):
        for k in skip:
            d.pop(k, None)
        d.get("start", {}).pop("wall_s", None)
    assert a == b


def test_simulate_override_equals_scene_file(edited_scene, tmp_path, capsys):
    base = ["--speed-rpm", 3000, "--revolutions", 2]
    assert _run(["simulate", "paper-table4", *base, *OVERRIDES_E2E, "--out", tmp_path / "o"]) == 0
    assert _run(["simulate", "--scene", edited_scene, *base, "--out", tmp_path / "f"]) == 0
    a, b = (json.loads((tmp_path / d / "simulate-summary.json").read_text()) for d in "of")
    assert a["law"] == "pereira" and a["clearance_mm"] == pytest.approx(0.08, rel=1e-12)
    _same(a, b)
    assert (tmp_path / "o/simulate.csv").read_bytes() == (tmp_path / "f/simulate.csv").read_bytes()


@pytest.mark.parametrize("job,argv", [("orbit", ["--speed-rpm", 3000]),
                                      pytest.param("branch", ["--rpm-start", 3000, "--rpm-end", 3010, "--max-points", 2],
                                                   marks=pytest.mark.slow)])     # branch: orbit's own _overrides
def test_orbit_and_branch_override_equals_scene_file(job, argv, edited_scene, tmp_path, capsys):
    rc_o = _run([job, "paper-table4", *argv, *OVERRIDES_E2E, "--json", "--out", tmp_path / "o.json"])
    rc_f = _run([job, "--scene", edited_scene, *argv, "--json", "--out", tmp_path / "f.json"])
    assert rc_o == rc_f and rc_o in (0, 1)        # branch: 1 = stopped at --max-points, the orbits are written
    a, b = (json.loads((tmp_path / f).read_text()) for f in ("o.json", "f.json"))
    assert a["law"] == "pereira"
    _same(a, b)


def test_unbalance_misalignment_override_equals_scene_file(tmp_path, capsys):
    text = (ROOT / "rotor/scenes/paper-table4.toml").read_text(encoding="utf-8").replace("offset_mm = 1.0", "offset_mm = 2.5")
    (tmp_path / "d.toml").write_text(text, encoding="utf-8")
    base = ["--order", 2, "--points", 3, "--json"]
    assert _run(["rotor", "unbalance", "paper-table4", *base, "--misalignment-mm", 2.5]) == 0
    a = json.loads(capsys.readouterr().out)
    assert _run(["rotor", "unbalance", "--scene", tmp_path / "d.toml", *base]) == 0
    b = json.loads(capsys.readouterr().out)
    assert a == b


@pytest.mark.parametrize("option", [["--mu", "0.2"], ["--law", "pereira"], ["--clearance-mm", "0.08"],
                                    ["--tilt-ignored"], ["--misalignment-mm", "2"]])
def test_modes_refuse_what_a_locked_support_cannot_apply(option, capsys):
    assert _run(["rotor", "modes", "paper-table4", *option]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"ringcontact rotor modes: error: {option[0]}")


class _Tasks(Exception):
    """Raised by the stand-in of the study's sweep with the tasks it was given."""


STUDY_ARGS = {"cascade": ["--rpm-min", "3000", "--rpm-max", "3000", "--points", "1"],
              "point": ["--speed-rpm", "3000"], "params": ["--rpm-max", "3000", "--points", "1"],
              "testrig": [], "map": ["--rpm-max", "3000", "--points", "1"],
              "runup": ["--rpm-start", "3000", "--rpm-end", "3100", "--duration-s", "0.3"]}
#: the overrides a study varies itself (refused there: tests/reports/bad_inputs.py)
OWN = {"testrig": ("--clearance-mm", "--misalignment-mm"), "map": ("--clearance-mm",)}


@pytest.mark.parametrize("sub", sorted(STUDY_ARGS))
def test_every_study_point_gets_the_overrides(sub, tmp_path, monkeypatch):
    """The tasks each study builds (what its points are computed from) hold every override given, and one of
    them, computed, used the law and clearance (rotor.studies.steady_state.run_point)."""
    from reports.cli import study
    from rotor.studies import runup

    def capture(tasks, *a, **k):
        raise _Tasks(tasks)
    monkeypatch.setattr(study, "run_study_sweep", capture)
    monkeypatch.setattr(runup, "run_runup", lambda spec, *a, **k: capture([spec]))
    typed = dict(zip(OVERRIDES_E2E[::2], OVERRIDES_E2E[1::2]))
    argv = [a for f, v in typed.items() if f not in OWN.get(sub, ()) for a in (f, v)]
    with pytest.raises(_Tasks) as got:
        study.main([sub, "paper-table4", *STUDY_ARGS[sub], "--out", str(tmp_path), *argv])
    si = {"--law": ("law", "pereira"), "--clearance-mm": ("clearance_m", 0.08e-3), "--mu": ("mu", 0.2),
          "--preload-N": ("preload_n", 3000.0), "--misalignment-mm": ("misalignment_m", 1e-3)}
    want = dict(si[f] for f in typed if f not in OWN.get(sub, ()))
    tasks = got.value.args[0]
    if sub == "params":       # the curves that vary the clearance or the misalignment hold their own value of it
        tasks = [t for t in tasks if t.key.startswith("base-")]
    assert tasks
    for task in tasks:
        params = vars(task) if sub == "runup" else task.params
        assert {k: params[k] for k in want} == want
    if sub == "cascade":
        task = got.value.args[0][0]
        _, info = task.func(**{**task.params, "options": {"steps_per_rev": 64, "max_revs": 24}})
        assert info["law"] == "pereira" and info["clearance_m"] == pytest.approx(0.08e-3, rel=1e-12)


@pytest.mark.slow
def test_study_cascade_points_hold_the_overrides(tmp_path, capsys):
    out = tmp_path / "c"
    assert _run(["study", "cascade", "paper-table4", "--rpm-min", 3000, "--rpm-max", 3000, "--points", 1,
                 "--max-revs", 24, "--steps-per-rev", 64, "--workers", 1, "--no-progress", "--out", out,
                 *OVERRIDES_E2E]) == 0
    point = json.loads((out / "points" / "rpm3000.0.json").read_text())
    assert point["info"]["law"] == "pereira" and point["info"]["clearance_m"] == pytest.approx(0.08e-3, rel=1e-12)
    assert {k: point["params"][k] for k in ("law", "mu", "preload_n")} == {"law": "pereira", "mu": 0.2,
                                                                           "preload_n": 3000.0}
