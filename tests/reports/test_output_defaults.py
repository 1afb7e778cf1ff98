"""The report jobs write into ``reports/published`` of the WORKING directory by default, never into the package.

Every report job shares one default (``reports.cli._edge.PUBLISHED``, relative): run from the
repository root it rebuilds the committed copy, run from anywhere else (an installed wheel) it
writes beside the user. The builders are replaced by recorders so the test takes milliseconds and
checks only where each job would write; the builders' own output is tested with the reports.
"""
from __future__ import annotations

from pathlib import Path

import pytest

import contact
from reports import cli
from reports.cli._edge import PUBLISHED

PACKAGE_ROOT = Path(contact.__file__).resolve().parents[1]


def _record(monkeypatch, module: str, name: str, seen: list, result=None):
    """Replace ``module.name`` by a function recording the output directory among its arguments."""
    import importlib
    mod = importlib.import_module(module)

    def fake(*args, **kwargs):
        seen.extend(Path(a) for a in (*args, *kwargs.values()) if isinstance(a, (str, Path)) and "published" in str(a))
        return result if result is not None else Path(seen[-1]) / "x.md"
    monkeypatch.setattr(mod, name, fake)


JOBS = {
    "report": (["report"], [("reports.cli.report", "run")]),
    "fem-report": (["fem-report"], [("reports.fem2d", "write_report")]),
    "fem-paper": (["fem-paper", "--quiet"], [("reports.fem2d_paper", "write_report")]),
    "fem3d report": (["fem3d", "report"], [("reports.fem3d", "write_report")]),
    "rotor report": (["rotor", "report"], [("reports.rotor_linear", "build_reports")]),
}


@pytest.mark.parametrize("job", sorted(JOBS))
def test_report_jobs_default_to_the_working_directory(job, tmp_path, monkeypatch, capsys):
    argv, replaced = JOBS[job]
    seen: list[Path] = []
    for module, name in replaced:
        _record(monkeypatch, module, name, seen, result=[] if name in ("run", "build_reports") else None)
    import fem_reference.paper_setup as paper_setup
    monkeypatch.setattr(paper_setup, "run", lambda *a, **k: [])      # the study itself is not under test
    monkeypatch.chdir(tmp_path)
    assert cli.main(argv) == 0, capsys.readouterr().err
    assert seen, f"{job}: the builder was not called with an output directory"
    for out in seen:
        where = (tmp_path / out).resolve()
        assert where == (tmp_path / PUBLISHED).resolve(), f"{job} writes to {where}"
        assert not where.is_relative_to(PACKAGE_ROOT / "reports"), f"{job} writes into the package"


def test_study_publish_and_sensitivity_default_to_the_same_folder(tmp_path, monkeypatch):
    from reports.cli import study
    monkeypatch.chdir(tmp_path)
    (tmp_path / PUBLISHED).mkdir(parents=True)              # study redraw reads from there: it must exist
    for argv in (["publish"], ["sensitivity", "--report-only"], ["redraw"]):
        args = study._parser().parse_args(argv)
        where = args.src if argv == ["redraw"] else args.to
        assert where == Path(PUBLISHED) and not where.is_absolute(), argv
