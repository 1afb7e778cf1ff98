"""Figures and notes of finished study directories into ``reports/published`` as ``study-*`` files."""
from __future__ import annotations

from pathlib import Path

from contact.files import atomic_write_text
from reports.studies.cascade import cascade_figures, cascade_note
from reports.studies.common import load_points
from reports.studies.mesh import KINDS, findings_figure, findings_note
from reports.studies.params import params_figures, params_note
from reports.studies.point import point_figures, point_note
from reports.studies.regime_map import map_figures, map_note
from reports.studies.runup import runup_figures, runup_note
from reports.studies.testrig import testrig_figures, testrig_note


def publish(runs: dict, published) -> list[Path]:
    """Figures + notes of finished study directories into ``published`` as ``study-*`` files.

    ``runs``: ``{"cascade": dir, "notilt": dir, "params": dir, "point": dir, "testrig": dir, "map": dir,
    "runup": dir}`` (any subset), and the same studies on a converged mesh as ``"<kind>_converged"``
    with ``"elements"`` (elements per segment): then ``study-findings.md`` judges the five Section 5
    findings on both meshes.
    """
    from sweep import read_timing

    published = Path(published)
    files = []
    if "cascade" in runs:
        files += cascade_figures(runs["cascade"], published, prefix="study-cascade")
        notilt = None
        if "notilt" in runs:
            files += cascade_figures(runs["notilt"], published, prefix="study-cascade-notilt",
                                     title="Spectrum cascades with the tilt ignored (paper Fig. 16)")
            notilt = load_points(runs["notilt"])
        timing = read_timing(runs["cascade"])
        files.append(atomic_write_text(published / "study-cascade.md",
                                       cascade_note(load_points(runs["cascade"]), notilt, timing)))
    if "params" in runs:
        files += params_figures(runs["params"], published)
        files.append(atomic_write_text(published / "study-params.md", params_note(load_points(runs["params"]))))
    if "point" in runs:
        files += point_figures(runs["point"], published)
        files.append(atomic_write_text(published / "study-point.md", point_note(load_points(runs["point"]))))
    if "testrig" in runs:
        files += testrig_figures(runs["testrig"], published)
        files.append(atomic_write_text(published / "study-testrig.md", testrig_note(load_points(runs["testrig"]))))
    if "map" in runs:
        files += map_figures(runs["map"], published)
        files.append(atomic_write_text(published / "study-map.md", map_note(load_points(runs["map"]))))
    if "runup" in runs:
        files += runup_figures(runs["runup"], published)
        files.append(atomic_write_text(published / "study-runup.md", runup_note(runs["runup"])))
    if any(f"{k}_converged" in runs for k in KINDS):
        paper = {k: load_points(runs[k]) for k in KINDS if k in runs}
        conv = {k: load_points(runs[f"{k}_converged"]) for k in KINDS if f"{k}_converged" in runs}
        elements = int(runs.get("elements", 2))
        files += findings_figure(paper, conv, elements, published / "study-findings")
        files.append(atomic_write_text(published / "study-findings.md", findings_note(paper, conv, elements)))
    return files
