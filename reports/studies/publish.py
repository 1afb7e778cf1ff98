"""Figures and notes of finished study directories into ``reports/published`` as ``study-*`` files."""
from __future__ import annotations

from pathlib import Path

from contact.files import atomic_write_text
from reports.studies.cascade import CASCADE_TITLE, NOTILT_TITLE, cascade_figures, cascade_note
from reports.studies.clearance_geometry import write_geometry_csv
from reports.studies.common import load_points
from reports.studies.mesh import KINDS, findings_csv, findings_figure, findings_note
from reports.studies.params import params_figures, params_note
from reports.studies.point import point_figures, point_note
from reports.studies.regime_map import map_figures, map_note
from reports.studies.runup import runup_figures, runup_note
from reports.studies.testrig import read_scan, testrig_figures, testrig_note


def publish(runs: dict, published, *, findings_extra: str = "") -> list[Path]:
    """Figures + notes of finished study directories into ``published`` as ``study-*`` files.

    ``runs``: ``{"cascade": dir, "notilt": dir, "params": dir, "point": dir, "testrig": dir, "map": dir,
    "runup": dir}`` (any subset), and the same studies on a converged mesh as ``"<kind>_converged"``
    with ``"elements"`` (elements per segment): their figures and CSVs are written as ``study-*-e<N>``, and
    ``study-findings.md`` judges the Section 5 findings per speed band on both meshes (``findings_extra``:
    the hand-written reading appended, reports/notes/study-findings-reading.md).
    """

    published = Path(published)
    files = []
    elements = int(runs.get("elements", 2))
    for suffix, tag in (("", ""), ("_converged", f"-e{elements}")):
        files += _family(runs, suffix, tag, published, elements)
    if "testrig" in runs:
        files += testrig_figures(runs["testrig"], published)
        files.append(atomic_write_text(published / "study-testrig.md",
                                       testrig_note(load_points(runs["testrig"]), read_scan(runs["testrig"]))))
    if "map" in runs:
        files += map_figures(runs["map"], published)
        files.append(atomic_write_text(published / "study-map.md", map_note(load_points(runs["map"]))))
    if "runup" in runs:
        files += runup_figures(runs["runup"], published)
        files.append(atomic_write_text(published / "study-runup.md", runup_note(runs["runup"])))
    if any(f"{k}_converged" in runs for k in KINDS):
        paper = {k: load_points(runs[k]) for k in KINDS if k in runs}
        conv = {k: load_points(runs[f"{k}_converged"]) for k in KINDS if f"{k}_converged" in runs}
        files += findings_figure(paper, conv, elements, published / "study-findings")
        files.append(atomic_write_text(published / "study-findings.md",
                                       findings_note(paper, conv, elements, extra=findings_extra)))
        files.append(findings_csv(paper, conv, elements, published / "study-findings.csv"))
        if paper.get("params") or conv.get("params"):
            files.append(write_geometry_csv(paper.get("params"), conv.get("params"), elements,
                                            published / "study-clearance-geometry.csv"))
    return files


def _family(runs: dict, suffix: str, tag: str, published: Path, elements: int) -> list[Path]:
    """The cascade (tilt on and off, one colour scale), params and point figures + CSVs of one mesh: the
    paper's (``suffix`` "", files ``study-*``) or the converged one (``_converged``, ``study-*-e<N>``)."""
    from sweep import read_timing

    files = []
    mesh = "" if not suffix else f", {elements} elements per segment"
    if f"cascade{suffix}" in runs:
        cas = load_points(runs[f"cascade{suffix}"])
        notilt = load_points(runs[f"notilt{suffix}"]) if f"notilt{suffix}" in runs else None
        files += cascade_figures(runs[f"cascade{suffix}"], published, prefix=f"study-cascade{tag}",
                                 title=CASCADE_TITLE.format(mesh=mesh), scale_with=notilt)
        if notilt:
            files += cascade_figures(runs[f"notilt{suffix}"], published, prefix=f"study-cascade-notilt{tag}",
                                     title=NOTILT_TITLE.format(mesh=mesh), scale_with=cas)
        if not suffix:
            files.append(atomic_write_text(published / "study-cascade.md",
                                           cascade_note(cas, notilt, read_timing(runs["cascade"]))))
    if f"params{suffix}" in runs:
        files += params_figures(runs[f"params{suffix}"], published, prefix=f"study-params{tag}")
        if not suffix:
            files.append(atomic_write_text(published / "study-params.md", params_note(load_points(runs["params"]))))
    if f"point{suffix}" in runs:
        files += point_figures(runs[f"point{suffix}"], published, prefix=f"study-point{tag}")
        if not suffix:
            files.append(atomic_write_text(published / "study-point.md", point_note(load_points(runs["point"]))))
    return files
