"""Report builder: every analytic law against the FEM reference, Tables 2–3 style, with the calibration.

Table 2 style (straight ring, 2D dataset ``fem_reference/data/fem2d-reference.json``): per
boundary-condition scene, rows = laws, columns = penetrations 0.01 … 0.05 mm, cells =
``100 (P_law − P_FEM)/P_FEM`` (signed), '–' where a law has no solution. Laws:

* the conformal law (Dai et al. 2025 Eq. 5) in each documented reading — plane-stress modulus
  (the paper's) and plane-strain modulus; the β readings coincide here (β = 0, equal materials);
* Johnson (Eq. 26) and Pereira et al. 2015 (Eq. 28);
* the calibrated law of the scene (:mod:`contact.calibrate`), both as stored (fitted on all
  points) and **held out** (each displacement predicted by a fit that never saw it).

The paper's own Table 2 percentages (``|law − FEM|/FEM`` of its law against its own FEM, whose
boundary conditions are not stated) stand beside ours, with one sentence per systematic
difference. Table 3 style (tilted ring) needs the 3D dataset (``fem_reference/data/3d/*.json``);
without one the report says so.

Writes ``accuracy-table2.md``, ``accuracy-table2.csv``, ``accuracy-table3.csv`` (when 3D data
exist), ``accuracy-force-displacement.png/.svg``.

Modules: :mod:`~reports.accuracy.straight` (Table 2, 2D), :mod:`~reports.accuracy.tilted`
(Table 3, 3D), :mod:`~reports.accuracy.markdown` (the Markdown file),
:mod:`~reports.accuracy.common` (the paper's numbers). :func:`build` is the report builder.
"""
from __future__ import annotations

from pathlib import Path

from contact import calibrate as cal
from contact.dataset import read_dataset
from contact.files import atomic_write_bytes, atomic_write_text
from reports.accuracy import tilted
from reports.accuracy.common import LAW_LABELS, PAPER_TABLE2_PCT, PAPER_TABLE3_PCT, PENETRATIONS_MM, pct_cell
from reports.accuracy.markdown import write_markdown
from reports.accuracy.straight import (CSV2_COLUMNS, law_forces, make_figure, must_show_lines, scene_table,
                                       systematic_sentences, table2_csv)
from reports.accuracy.tilted import T3_CSV_COLUMNS, T3_METHODS, make_figure_3d, table3_csv, table3_rows


DATA_3D_DIR = cal.DATA_3D_DIR

__all__ = [
    "CSV2_COLUMNS", "DATA_3D_DIR", "LAW_LABELS", "PAPER_TABLE2_PCT", "PAPER_TABLE3_PCT", "PENETRATIONS_MM",
    "T3_CSV_COLUMNS", "T3_METHODS", "build", "compute", "law_forces", "make_figure", "make_figure_3d",
    "must_show_lines", "pct_cell", "scene_table", "systematic_sentences", "table2_csv", "table3", "table3_csv",
    "table3_rows", "write_markdown",
]


def table3() -> dict:
    """Table 3-style comparison from every committed 3D dataset in :data:`DATA_3D_DIR` (:func:`tilted.table3`)."""
    return tilted.table3(DATA_3D_DIR)


def compute(dataset_path=cal.DATASET_2D) -> tuple[list[dict], dict]:
    ds = read_dataset(dataset_path)
    info = cal.dataset_provenance(Path(dataset_path), ds)
    tables = []
    for scene in ds.scenes():
        try:
            t = scene_table(ds, scene, info)
        except cal.DatasetError as exc:       # a scene without the Table 2 displacements: say so, go on
            print(f"[accuracy] scene {scene!r} skipped: {exc}")
            continue
        tables.append(t)
    return tables, table3()


def build(out_dir: Path) -> list[Path]:
    """Write the accuracy report files into ``out_dir``; return their paths."""
    out_dir = Path(out_dir)
    tables, t3 = compute()
    png, svg = make_figure(tables)
    files = [atomic_write_text(out_dir / "accuracy-table2.csv", table2_csv(tables))]
    if t3["have_data"]:
        files.append(atomic_write_text(out_dir / "accuracy-table3.csv", table3_csv(t3["rows"])))
        if t3["rows"]:
            png3, svg3 = make_figure_3d(t3)
            files += [atomic_write_bytes(out_dir / "accuracy-table3-force-displacement.png", png3),
                      atomic_write_bytes(out_dir / "accuracy-table3-force-displacement.svg", svg3)]
    files += [atomic_write_bytes(out_dir / "accuracy-force-displacement.png", png),
              atomic_write_bytes(out_dir / "accuracy-force-displacement.svg", svg),
              atomic_write_text(out_dir / "accuracy-table2.md", write_markdown(tables, t3))]
    return files
