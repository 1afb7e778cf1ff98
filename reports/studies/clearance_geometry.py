"""Where the ring rides in its support in the clearance study (paper Fig. 18): ``study-clearance-geometry.csv`` and
the mechanism line of ``study-findings.md`` drawn from it.

At every speed of ``study params`` and each clearance δ0 = 0.03 / 0.05 / 0.08 mm (δ = 1 mm), on both meshes: the
ring's mean radial offset in the support and its swing (:func:`rotor.studies.section5.ring_offset`), the contact
share, the contact force's 1X and 2X (:func:`rotor.studies.section5.contact_pattern`) and the support's 2X
displacement. The mechanism line is written from the CSV's rows as read back (six digits), so the committed CSV
alone gives the published text (tests/test_published_studies.py).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

#: the clearance cases of ``study params`` (key prefix, δ0 in mm)
CASES = (("c0.03mm-rpm", 0.03), ("base-rpm", 0.05), ("c0.08mm-rpm", 0.08))
HEADER = ["mesh", "speed_rpm", "clearance_mm", "periodic", "contact_share", "offset_mean_um", "offset_swing_um",
          "force_1x_N", "force_2x_N", "support_2x_um"]
#: the band where 2X rises with δ0 against Fig. 18 on both meshes (study-findings.md)
H1 = (9000.0, 12000.0)


def geometry_rows(points, mesh: str) -> list[list]:
    """CSV rows (:data:`HEADER`) of a finished ``study params`` (its points, ``load_points``) on ``mesh``
    (the mesh column, as study-findings.csv names it); speeds in order, clearances 0.03 / 0.05 / 0.08 mm."""
    from rotor.studies.section5 import contact_pattern, ring_offset

    by = {p.key: p for p in points}
    speeds = sorted({p.params["speed_rpm"] for p in points})
    rows = []
    for rpm in speeds:
        for prefix, d0_mm in CASES:
            p = by.get(f"{prefix}{float(rpm)}")
            if p is None or "r1" not in p.arrays:        # beyond the contact law's domain: no record
                continue
            mean, swing = ring_offset(p.arrays)
            pat = contact_pattern(p.arrays, p.info)
            s2 = abs(p.arrays["harm_q"][1, list(p.arrays["channels"]).index("s.y")])
            rows.append([mesh, float(rpm), d0_mm, int(bool(p.info["converged"])), pat["contact_share"], mean * 1e6,
                         swing * 1e6, pat["force_1x_N"], pat["force_2x_N"], s2 * 1e6])
    return rows


def both_meshes(paper_points, converged_points, elements: int) -> list[list]:
    """:func:`geometry_rows` of the clearance study on the paper's mesh, then on the converged one."""
    return geometry_rows(paper_points or [], "paper") + geometry_rows(converged_points or [], f"{elements}/segment")


def as_read(rows: list[list]) -> list[dict]:
    """Rows as the written CSV reads back (:func:`reports.studies.common.write_csv`'s six digits), as dicts."""
    return [dict(zip(HEADER, (f"{x:.6g}" if isinstance(x, (float, np.floating)) else str(x) for x in r))) for r in rows]


def write_geometry_csv(paper_points, converged_points, elements: int, path: Path) -> Path:
    """``study-clearance-geometry.csv`` of the clearance study on the paper's mesh and the converged one."""
    from reports.studies.common import write_csv

    return write_csv(path, HEADER, both_meshes(paper_points, converged_points, elements))


def _speeds(rows: list[dict]) -> dict:
    """``{(mesh, rpm): [row at 0.03, 0.05, 0.08 mm]}`` of the speeds with a record at every clearance."""
    by: dict = {}
    for r in rows:
        by.setdefault((r["mesh"], float(r["speed_rpm"])), []).append(r)
    return {k: sorted(v, key=lambda r: float(r["clearance_mm"])) for k, v in by.items() if len(v) == len(CASES)}


def judged(rows: list[dict]) -> dict:
    """``{(mesh, rpm): (rows, offset_follows result)}`` at the speeds where the ring is in contact at every
    clearance (rows as :func:`reports.studies.common.read_csv_rows` gives them)."""
    from rotor.studies.section5 import offset_follows

    out = {}
    for key, rs in _speeds(rows).items():
        if min(float(r["contact_share"]) for r in rs) > 0:
            col = {c: [float(r[c]) for r in rs] for c in ("clearance_mm", "offset_mean_um", "offset_swing_um")}
            out[key] = (rs, offset_follows(np.array(col["clearance_mm"]) * 1e-3, np.array(col["offset_mean_um"]) * 1e-6,
                                           np.array(col["offset_swing_um"]) * 1e-6))
    return out


def _runs(speeds: list[float], grid: list[float]) -> str:
    """Speeds as runs of consecutive grid speeds: "5400–12600, 13800 rpm"."""
    out, run = [], []
    for s in grid:
        if s in speeds:
            run.append(s)
        elif run:
            out.append(run)
            run = []
    out += [run] if run else []
    return ", ".join(f"{r[0]:.0f}" if len(r) == 1 else f"{r[0]:.0f}–{r[-1]:.0f}" for r in out) + " rpm" if out else "none"


def _rpm(x: float) -> str:
    """A speed with a space between thousands, as the reports write them ("12 000")."""
    return f"{x:,.0f}".replace(",", " ")


def _span(x, fmt: str = ".3g", unit: str = "") -> str:
    return f"{min(x):{fmt}}–{max(x):{fmt}}{unit}" if len(x) else "–"


def _between(x, fmt: str) -> str:
    """ "between -25 % and +336 %" of relative changes (–, written in %)."""
    return f"between {100 * min(x):{fmt}} % and {100 * max(x):{fmt}} %"


def relative_change(rs: list[dict], col: str) -> float:
    """Relative change of ``col`` from the smallest to the largest clearance (–)."""
    return float(rs[-1][col]) / float(rs[0][col]) - 1.0


def mesh_line(rows: list[dict], mesh: str, tag: str) -> str | None:
    """The mechanism bullet of one mesh, or None when the CSV has no speed with contact at every clearance."""
    from rotor.studies.section5 import FOLLOW_TOL

    j = {rpm: v for (m, rpm), v in judged(rows).items() if m == mesh}
    if not j:
        return None
    grid = sorted(j)
    hold = [s for s in grid if j[s][1]["holds"]]
    fail = [s for s in grid if not j[s][1]["holds"]]
    h1 = [s for s in grid if H1[0] <= s <= H1[1]]
    dd = 1e3 * (float(j[grid[0]][0][-1]["clearance_mm"]) - float(j[grid[0]][0][0]["clearance_mm"]))
    text = (f"- Clearance, where the ring rides (study-clearance-geometry.csv), {tag}: at the {len(grid)} speeds with "
            f"the ring in contact at all three δ0 ({grid[0]:.0f}–{grid[-1]:.0f} rpm), its mean radial offset in the "
            "support (the mean of its two edges' offsets r1, r2 over the record) follows the clearance with the same "
            f"swing (moves by 1 ± {FOLLOW_TOL:g} of δ0's change from 0.03 to 0.08 mm, and the swings, peak to peak, "
            f"differ by less than {FOLLOW_TOL:g} of it, {FOLLOW_TOL * dd:g} µm) at {len(hold)} of {len(grid)}: "
            f"{_runs(hold, grid)}. ")
    if h1:
        rs = [j[s][0] for s in h1]
        text += (f"At {_rpm(H1[0])}–{_rpm(H1[1])} rpm ({len(h1)} speeds, the band where 2X rises with δ0 against Fig. 18) "
                 f"it holds at {sum(j[s][1]['holds'] for s in h1)} of {len(h1)}: the offset moves by "
                 f"{_span([j[s][1]['slope'] for s in h1], '.3f')} of δ0's change and sits "
                 f"{_span([1e6 * x for s in h1 for x in j[s][1]['inside_m']], '.2f', ' µm')} inside the clearance, "
                 f"with swings of {_span([float(r['offset_swing_um']) for g in rs for r in g], '.2f', ' µm')}; from "
                 "δ0 = 0.03 to 0.08 mm the contact force's 2X changes "
                 f"{_between([relative_change(g, 'force_2x_N') for g in rs], '+.0f')} "
                 f"({' / '.join(str(round(float(r['force_2x_N']))) for r in rs[0])} N at {h1[0]:.0f} rpm), the "
                 f"support's 2X displacement {_between([relative_change(g, 'support_2x_um') for g in rs], '+.1f')}. ")
    if fail:
        text += (f"Where it does not hold ({_runs(fail, grid)}), the offset moves by "
                 f"{_span([j[s][1]['slope'] for s in fail], '.2f')} of δ0's change and swings "
                 f"{_span([float(r['offset_swing_um']) for s in fail for r in j[s][0]], '.3g', ' µm')}.")
    return text.rstrip()


def geometry_lines(rows: list[dict], elements: int) -> list[str]:
    """The clearance-geometry bullets of study-findings.md (both meshes) and what they say together."""
    lines = [x for x in (mesh_line(rows, "paper", "paper's mesh"),
                         mesh_line(rows, f"{elements}/segment", f"{elements} elements/segment")) if x]
    if lines:
        lines[-1] += (" So δ0 shifts where the ring rides and leaves its swing nearly unchanged where the mechanism "
                      "holds, as the support's 2X barely changes there; the contact force, which the paper does not "
                      "show, does change with δ0. This does not say why the support's few per cent go against Fig. 18.")
    return lines
