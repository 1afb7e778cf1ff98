"""Redraw the study figures from the committed CSV tables (``ringcontact study redraw``), no study rerun.

The study run directories are hours of computing and are not committed; the numbers the figures show
are (``reports/published/study-*.csv``). Each figure here is drawn by the same plotting function
``study publish`` uses, fed from the CSV instead of the run directory:

* ``study-sensitivity.png/.svg`` from ``study-sensitivity-points.csv`` (:mod:`reports.sensitivity_figure`);
* ``study-params-clearance`` / ``-misalignment`` from ``study-params.csv`` (``study publish`` draws them from
  that CSV too, so both give the same figure);
* ``study-cascade`` (+ ``-tilt``) and ``study-cascade-notilt`` (+ ``-tilt``) from ``study-cascade-spectrum.csv``
  and ``study-cascade-notilt-spectrum.csv`` (the full spectra binned as published, on one colour scale), or,
  without them, from ``study-cascade.csv`` and ``study-cascade-notilt.csv``: those hold the harmonics 1X–5X
  (tilt 1X–3X) per speed only, and the redrawn cascades say so under their titles; speeds without a
  periodic steady state are marked.

The CSV and Markdown files are read, never written.
"""
from __future__ import annotations

from pathlib import Path

from contact.errors import DatasetError, InputError
from reports.studies.cascade import CASCADE_TITLE, NOTILT_TITLE, cascade_redraw, spectrum_redraw
from reports.studies.common import read_csv_rows, require_columns, require_finite
from reports.studies.params import COLUMNS, grids_from_rows, params_grids

#: the scene the committed study-sensitivity-points.csv was computed on (its factors are labelled with that
#: scene's values): the former reading of Eq. 34, paper-table4 until section5-readings.md; a rerun of
#: ``study sensitivity`` on paper-table4 moves it
SENSITIVITY_SCENE = "paper-table4-inertial"

#: committed CSV -> what is drawn from it
SOURCES = {
    "study-sensitivity-points.csv": "study-sensitivity.png/.svg",
    "study-params.csv": "study-params-clearance, study-params-misalignment and their -ratio figures",
    "study-cascade.csv": "study-cascade, study-cascade-tilt",
    "study-cascade-notilt.csv": "study-cascade-notilt, study-cascade-notilt-tilt",
}


def redraw(src, dst) -> list[Path]:
    """Draw every figure whose CSV is in ``src`` into ``dst``; return the files written.

    Every CSV present is read and checked before the first figure is drawn, so a bad one writes nothing.

    Raises
    ------
    InputError
        none of :data:`SOURCES` in ``src``.
    DatasetError
        a CSV that cannot be read, is ragged or lacks the columns its figure needs.
    """
    from reports.sensitivity_figure import figure as sensitivity_figure
    from reports.sensitivity_figure import tables_from_points_csv

    src, dst = Path(src), Path(dst)
    present = [name for name in SOURCES if (src / name).is_file()]
    if not present:
        raise InputError(f"--from = {src}: holds none of {', '.join(SOURCES)} (the tables `study publish` writes)")
    for name in present:                          # a NaN or inf cell anywhere: refused before any figure
        require_finite(src / name, read_csv_rows(src / name))
    draws = []
    if "study-sensitivity-points.csv" in present:
        tabs, variants = tables_from_points_csv(src / "study-sensitivity-points.csv")
        draws.append(lambda: sensitivity_figure(tabs, variants, dst / "study-sensitivity", scene=SENSITIVITY_SCENE))
    if "study-params.csv" in present:
        rows = read_csv_rows(src / "study-params.csv")
        require_columns(src / "study-params.csv", rows, ["key", "clearance_mm", "misalignment_mm", "speed_rpm"] + COLUMNS)
        try:
            grids_from_rows(rows)
        except ValueError as exc:
            raise DatasetError(f"{src / 'study-params.csv'}: a cell is not a number ({exc})") from None
        draws.append(lambda: params_grids(rows, dst))
    pair = {"study-cascade": "study-cascade-notilt", "study-cascade-notilt": "study-cascade"}
    for name, prefix, title in (("study-cascade.csv", "study-cascade", CASCADE_TITLE.format(mesh="")),
                                ("study-cascade-notilt.csv", "study-cascade-notilt", NOTILT_TITLE.format(mesh=""))):
        full, other = src / f"{prefix}-spectrum.csv", src / f"{pair[prefix]}-spectrum.csv"
        if full.is_file():                   # the full spectra, as published: the same figure
            draws.append(spectrum_redraw(full, dst, prefix, title, other if other.is_file() else None))
        elif name in present:
            draws.append(cascade_redraw(src / name, dst, prefix, title))     # checked now, drawn below
    return [f for draw in draws for f in draw()]
