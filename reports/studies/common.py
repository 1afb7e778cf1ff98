"""Shared by the study reports: figure saving (PNG + SVG), CSV tables, a sweep's points, harmonic tables."""
from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np

from contact.files import atomic_write_bytes, atomic_write_text
from sweep import load_sweep


LOCATIONS = (("disk1.y", "disk 1"), ("disk2.y", "disk 2"), ("s.y", "3# bearing (support)"))


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams["svg.hashsalt"] = "ringcontact"
    return plt


def save(fig, prefix: Path) -> list[Path]:
    """Write ``prefix.png`` and ``prefix.svg`` atomically and close the figure."""
    plt = pyplot()
    out = []
    for ext in ("png", "svg"):
        buf = io.BytesIO()
        fig.savefig(buf, format=ext, dpi=130 if ext == "png" else 110, bbox_inches="tight", metadata={"Date": None} if ext == "svg" else None)
        out.append(atomic_write_bytes(f"{prefix}.{ext}", buf.getvalue()))
    plt.close(fig)
    return out


def write_csv(path: Path, header: list[str], rows) -> Path:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for r in rows:
        w.writerow([f"{x:.6g}" if isinstance(x, (float, np.floating)) else x for x in r])
    return atomic_write_text(path, buf.getvalue())


def read_csv_rows(path) -> list[dict]:
    """The rows of a CSV written by :func:`write_csv` (or committed beside the reports) as dicts of strings.

    Raises
    ------
    DatasetError
        unreadable file, no header, or a row whose length differs from the header's.
    """
    from contact.errors import DatasetError
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise DatasetError(f"{path}: cannot read ({exc})") from None
    table = list(csv.reader(io.StringIO(text)))
    if not table or not table[0]:
        raise DatasetError(f"{path}: empty, no header")
    header = table[0]
    bad = [i + 2 for i, r in enumerate(table[1:]) if len(r) != len(header)]
    if bad:
        raise DatasetError(f"{path}: line {bad[0]} has a different number of cells than the header")
    return [dict(zip(header, r)) for r in table[1:]]


#: the ``regime`` of a point whose load drove the ring past the contact law's domain: it has no harmonics, and its
#: amplitude cells are NaN on purpose (rotor.studies.steady_state.beyond_law_record)
BEYOND_LAW = "beyond law"


def require_finite(path, rows: list[dict]) -> None:
    """Refuse (DatasetError) a table with a NaN or infinite number in any cell, naming its line and column: the
    tables ``study publish`` writes hold finite numbers only, so such a cell was edited or damaged, and a figure
    would silently leave the point out. The one exception is a point beyond the contact law's domain (``regime``
    :data:`BEYOND_LAW`), whose amplitudes do not exist and are written NaN."""
    import math

    from contact.errors import DatasetError
    for i, row in enumerate(rows):
        if row.get("regime", "").strip() == BEYOND_LAW:
            continue
        for col, cell in row.items():
            try:
                bad = not math.isfinite(float(cell))
            except (TypeError, ValueError):
                continue                         # text columns (keys, regimes) and empty cells: their readers say
            if bad:
                raise DatasetError(f"{path}: line {i + 2}, column {col} = {cell.strip()}: not a finite number (the "
                                   "study tables hold finite numbers only); restore the file or run the study again")


def require_columns(path, rows: list[dict], columns) -> None:
    """Refuse (DatasetError) a CSV without rows or lacking any of ``columns``."""
    from contact.errors import DatasetError
    if not rows:
        raise DatasetError(f"{path}: no rows")
    missing = [c for c in columns if c not in rows[0]]
    if missing:
        raise DatasetError(f"{path}: lacks the column(s) {', '.join(missing)}")


def load_points(out, tasks=None) -> list:
    """Verified points of a sweep in task order; a missing, damaged or stale point (of ``tasks``, else of
    the sweep's ``sweep.json``) is refused with a DatasetError naming each, so nothing is published short."""
    res = load_sweep(out, tasks, complete=True)
    keys = [t.key for t in tasks] if tasks is not None else sorted(res, key=lambda k: res[k].params.get("speed_rpm", 0))
    return [res[k] for k in keys if k in res]


def channel_column(p, name: str) -> int:
    return list(p.arrays["channels"]).index(name)


def harmonic_table(points, quantity: str = "v", channels=("disk1.y", "disk2.y", "s.y"), orders=(1, 2, 3, 4, 5)):
    """``(speeds_rpm (P,), amps (P, len(channels), len(orders)))`` of harmonic amplitudes (magnitudes, SI)."""
    rpm = np.array([p.params["speed_rpm"] for p in points])
    A = np.zeros((len(points), len(channels), len(orders)))
    for i, p in enumerate(points):
        h = np.abs(p.arrays[f"harm_{quantity}"])
        for j, c in enumerate(channels):
            col = channel_column(p, c) if quantity != "u" else {"y": 0, "z": 1, "θy": 2, "θz": 3}[c]
            A[i, j] = h[[o - 1 for o in orders], col]
    return rpm, A


def integrator_text(infos, commit: str = "") -> str:
    """One sentence naming the time integrator's options the points were computed with: ``info["integrator"]``
    of the points (rotor.dynamics.system.NewmarkOptions as recorded by rotor/studies/steady_state.py), or, for
    points that predate that record, the options' defaults at the points' commit (``commit``) as this code has
    them. Says whether slip reversals, stick onsets, releases and contact onsets and losses were located inside the
    step (``locate_events``)."""
    import dataclasses

    from rotor.dynamics.system import NewmarkOptions

    rec = [i.get("integrator") for i in infos if isinstance(i, dict)]
    kinds = {tuple(sorted(r.items())) for r in rec if r}
    if len(kinds) > 1:
        return "Integrator: the points were computed with different options (their info.integrator)."
    o = dict(kinds.pop()) if kinds else dataclasses.asdict(NewmarkOptions())
    said = "" if rec and all(rec) else (" (the points predate the record of the options: NewmarkOptions' defaults"
                                         + (f"; {commit}" if commit else "") + ")")
    return (f"Integrator: the production Newmark scheme (rotor.dynamics.production), NewmarkOptions β {o['beta']:g}, "
            f"γ {o['gamma']:g}, Newton tol {o['tol']:g}, w_reg {o['w_reg']:g} m/s, locate_events "
            f"{o['locate_events']}{said}: friction events (slip reversals, stick onsets, releases) and contact onsets "
            f"and losses {'located' if o['locate_events'] else 'not located'} inside the step.")
