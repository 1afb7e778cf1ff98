"""The full spectra of a cascade as a CSV (``study-cascade*-spectrum.csv``), binned as the maps draw them.

A cascade map (:func:`reports.studies.cascade.cascade_plots`) shows each speed's whole spectrum, broadband
content at a non-periodic speed included, binned on an order grid (:data:`reports.studies.cascade.ORDER_STEP`,
the largest amplitude per cell). This module writes those cells, values rounded to the CSV's six significant
digits, and reads them back; ``study publish`` and ``study redraw`` both draw from the rounded cells, so a
redraw from the committed CSV gives the published figure byte for byte. Cells more than ``decades`` (the
maps' colour range) below the cascade's largest amplitude (of velocity, or of tilt) are left out: a map's
scale starts that far below the largest amplitude of the cascades it shares the scale with, never lower.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import LOCATIONS, channel_column, read_csv_rows, require_columns, write_csv

VELOCITY = ("disk1_v_mm_s", "disk2_v_mm_s", "support_v_mm_s")
TILT = ("tilt_y_mrad", "tilt_z_mrad")
HEADER = ["speed_rpm", "periodic", "order"] + list(VELOCITY) + list(TILT)


def _r6(x) -> np.ndarray:
    """Round as write_csv writes (6 significant digits), so drawn values equal the CSV's."""
    return np.array([float(f"{v:.6g}") for v in np.ravel(x)]).reshape(np.shape(x))


def spectrum_rows(points, step: float, max_order: float, decades: int) -> list[list]:
    """One row per (speed, order cell) with any amplitude within ``decades`` of the cascade's largest:
    y velocity (mm/s) at disk 1, disk 2, the support, and the relative tilt θy, θz (mrad)."""
    n = int(round(max_order / step))
    per = []
    for p in points:
        if p.params["speed_rpm"] <= 0 or len(p.arrays["spec_orders"]) == 0:
            continue
        o = np.asarray(p.arrays["spec_orders"], float)
        keep = (o > 0.5 * step) & (o < max_order)
        idx = np.clip(np.round(o[keep] / step).astype(int), 0, n - 1)
        cols = [p.arrays["spec_v"][:, channel_column(p, ch)] * 1e3 for ch, _ in LOCATIONS]
        cols += [p.arrays["spec_u"][:, 2] * 1e3, p.arrays["spec_u"][:, 3] * 1e3]
        grid = np.zeros((n, len(cols)))
        for j, c in enumerate(cols):
            np.maximum.at(grid[:, j], idx, np.asarray(c, float)[keep])
        per.append((float(p.params["speed_rpm"]), bool(p.info["converged"]), _r6(grid)))
    if not per:
        return []
    vtop = max(g[:, :3].max() for _, _, g in per) or 1.0
    ttop = max(g[:, 3:].max() for _, _, g in per) or 1.0
    rows = []
    for rpm, ok, g in per:
        show = (g[:, :3] >= vtop * 10.0 ** -decades).any(axis=1) | (g[:, 3:] >= ttop * 10.0 ** -decades).any(axis=1)
        rows += [[rpm, int(ok), _r6(k * step)[()], *g[k]] for k in np.flatnonzero(show)]
    return rows


def write_spectrum_csv(points, path, step: float, max_order: float, decades: int) -> Path:
    return write_csv(Path(path), HEADER, spectrum_rows(points, step, max_order, decades))


def spectra_from_rows(rows) -> tuple[dict, dict]:
    """``(velocity, tilt)`` spectra as :func:`reports.studies.cascade.cascade_plots` takes them, from rows of
    :func:`spectrum_rows` or of the CSV (strings)."""
    by: dict = {}
    for r in rows:
        rec = r if isinstance(r, dict) else dict(zip(HEADER, r))
        rpm = float(rec["speed_rpm"])
        by.setdefault(rpm, {"periodic": str(rec["periodic"]) == "1", "rows": []})["rows"].append(
            [float(rec[c]) for c in HEADER[2:]])
    speeds = sorted(by)
    arr = {s: np.array(by[s]["rows"]) for s in speeds}

    def spectra(j):
        return [(s, arr[s][:, 0], arr[s][:, 1 + j], by[s]["periodic"]) for s in speeds]
    velocity = {lab: spectra(j) for j, (_, lab) in enumerate(LOCATIONS)}
    return velocity, {"θy": spectra(3), "θz": spectra(4)}


def read_spectrum_csv(path) -> tuple[dict, dict]:
    """:func:`spectra_from_rows` of a committed spectrum CSV (DatasetError if unreadable or a column is missing)."""
    rows = read_csv_rows(path)
    require_columns(path, rows, HEADER)
    try:
        return spectra_from_rows(rows)
    except ValueError as exc:
        from contact.errors import DatasetError
        raise DatasetError(f"{path}: a cell is not a number ({exc})") from None
