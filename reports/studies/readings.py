"""Point B (10 500 rpm) under every reading of Eq. 34 on both meshes, judged by the paper's text of Figs. 14–15.

Dai et al. (2025), §5.1, of point B: "The trajectories of different positions are non-circular";
the spectra are "primarily dominated by the rotational frequency f and harmonic frequency 2 f
caused by misalignment, but are also accompanied by noticeable harmonic frequency components such
as 3 f, 4 f, 5 f", "the closer to the loose support, the more pronounced"; "there is a certain amount
of relative movement between the support and rotor"; r1, r2 "fluctuate periodically within a
certain range near clearance δ0, indicating that there is periodic contact and separation".
Each statement is a row (:data:`STATEMENTS`) with a measured number and a stated threshold; the
readings are :data:`rotor.studies.readings.READINGS`; the points come from ``ringcontact study
readings`` (:func:`rotor.studies.readings.reading_tasks`). :func:`readings_table` judges them,
:func:`protocol_scores` scores them as the comparison protocol (reports/protocols/section5-readings.toml,
reports/studies/protocol.py) states, :func:`readings_note` and :func:`readings_csv` write
reports/published/section5-readings.md and .csv.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import LOCATIONS, channel_column, harmonic_table, write_csv

#: an orbit is non-circular when its largest radius about the mean is ≥ this times its smallest
#: (a 20 % departure shows on an orbit plot; a whirl at 1X alone with isotropic bearings gives 1.0)
NONCIRCULAR_RATIO = 1.2
#: a harmonic is "noticeable" on a linear spectrum when it is ≥ 5 % of 1X (as reports/studies/findings.py, point A)
VISIBLE = 0.05
#: "periodic contact and separation": each takes at least this share of the record
SHARE = 0.05

POINT_B_RPM = 10500.0
POINT_A_RPM = 4500.0
#: the low-speed sweep of each reading: where the end faces first slip (§5.3.1 (1) says they do not below 9 000 rpm)
LOW_RPM = tuple(float(s) for s in range(3000, 9000, 300))

STATEMENTS = (
    ("B: contact and separation", "r1, r2 \"fluctuate ... near clearance δ0 ... periodic contact and separation\": "
     f"contact and separation each ≥ {100 * SHARE:.0f} % of the record"),
    ("B: r1 and r2 cross δ0", "r1 and r2 each range across δ0 (min < δ0 < max)"),
    ("B: orbits non-circular", f"\"trajectories of different positions are non-circular\": largest/smallest orbit "
     f"radius ≥ {NONCIRCULAR_RATIO} at disk 1, disk 2 and the support"),
    ("B: relative movement", "\"a certain amount of relative movement between the support and rotor\": end faces "
     "slip part of the record"),
    ("B: 2X noticeable at the support", f"spectra \"dominated by ... f and ... 2 f\": 2X/1X ≥ {VISIBLE} at the support"),
    ("B: 3X–5X noticeable, most near the support", f"(3X+4X+5X)/1X ≥ {VISIBLE} at the support and rising from "
     "disk 1 to disk 2 to the support"),
)
#: the paper's text of Fig. 13 (point A), the cross-check: a reading must not lose point A to win point B
STATEMENTS_A = (
    ("A: orbits approximately circular", f"\"trajectories ... (at disk 1 and disk 2) are approximately circular\": "
     f"largest/smallest radius < {NONCIRCULAR_RATIO} at both"),
    ("A: no relative movement", "\"the support moves together with the rotor ... no relative movement\": end faces "
     "stuck the whole record"),
    ("A: 1X dominates", "\"primarily dominated by the rotational frequency f\": 1X the largest of 1X–5X at every station"),
    ("A: 2X relatively highest at the 3# bearing", f"2X/1X ≥ {VISIBLE} at the support and larger there than at "
     "disk 1 and disk 2"),
)


def orbit_radius_ratios(p) -> np.ndarray:
    """Largest over smallest orbit radius about the mean (–) at disk 1, disk 2 and the support of a point's history."""
    a = p.arrays
    out = []
    for ch, _ in LOCATIONS:
        y = a["q"][:, channel_column(p, ch)]
        z = a["q"][:, channel_column(p, ch.replace(".y", ".z"))]
        r = np.hypot(y - y.mean(), z - z.mean())
        out.append(float(r.max() / max(r.min(), 1e-30)))
    return np.array(out)


def point_measures(p) -> dict:
    """The numbers each statement is judged on, for one point (SI and ratios)."""
    _, V = harmonic_table([p], "v")
    v = V[0]
    d0 = p.info["clearance_m"]
    r1, r2 = np.asarray(p.arrays["r1"]), np.asarray(p.arrays["r2"])
    disk2 = [channel_column(p, "disk2.y"), channel_column(p, "disk2.z")]
    q2 = p.arrays["q"][:, disk2]
    rad2 = np.hypot(*(q2 - q2.mean(axis=0)).T)
    return {"contact_share": float(p.info["contact_fraction"]), "stick_share": float(p.info["stick_fraction"]),
            "r1_min_over_d0": float(r1.min() / d0), "r1_max_over_d0": float(r1.max() / d0),
            "r2_min_over_d0": float(r2.min() / d0), "r2_max_over_d0": float(r2.max() / d0),
            "orbit_ratio": orbit_radius_ratios(p), "disk2_radius_um": (float(rad2.min() * 1e6), float(rad2.max() * 1e6)),
            "v2_over_v1": v[:, 1] / v[:, 0], "v35_over_v1": v[:, 2:].sum(axis=1) / v[:, 0],
            "largest_order": np.argmax(v, axis=1) + 1,
            "periodic": bool(p.info["converged"]), "period_revs": int(p.info["period_revs"]),
            **_noise_inputs(p)}


def _noise_inputs(p) -> dict:
    """What the protocol's noise needs (reports/studies/protocol.py): the (3, 5) amplitudes of 1X–5X of y velocity
    and y displacement at disk 1, disk 2 and the support (SI), their spectral floors (zero on a periodic record;
    reports.studies.findings.spectral_floor) and the record's samples per revolution."""
    from reports.studies.findings import spectral_floor

    out = {"samples_per_rev": int(p.info.get("samples_per_rev", 0))}
    for qty in ("v", "q"):
        out[f"amps_{qty}"] = harmonic_table([p], qty)[1][0]
        out[f"floor_{qty}"] = np.zeros((3, 5)) if p.info.get("converged") else spectral_floor(p, qty)
    return out


def judge(m: dict) -> list[tuple[str, bool]]:
    """``[(our numbers, holds)]`` per statement of :data:`STATEMENTS` (point B), in order."""
    c = m["contact_share"]
    cross1 = m["r1_min_over_d0"] < 1 < m["r1_max_over_d0"]
    cross2 = m["r2_min_over_d0"] < 1 < m["r2_max_over_d0"]
    o, v2, v35 = m["orbit_ratio"], m["v2_over_v1"], m["v35_over_v1"]
    lo, hi = m["disk2_radius_um"]
    return [(f"contact {100 * c:.0f} % / separation {100 * (1 - c):.0f} %", SHARE <= c <= 1 - SHARE),
            (f"r1/δ0 {m['r1_min_over_d0']:.3f}–{m['r1_max_over_d0']:.3f}, r2/δ0 {m['r2_min_over_d0']:.3f}–"
             f"{m['r2_max_over_d0']:.3f}", cross1 and cross2),
            (f"max/min radius {o[0]:.2f} / {o[1]:.2f} / {o[2]:.2f} (disk 2 {lo:.2f}–{hi:.2f} µm)",
             bool(np.all(o >= NONCIRCULAR_RATIO))),
            (f"faces stuck {100 * m['stick_share']:.0f} % of the record", m["stick_share"] < 1.0),
            (f"2X/1X {v2[0]:.3f} / {v2[1]:.3f} / {v2[2]:.3f}", bool(v2[2] >= VISIBLE)),
            (f"(3X+4X+5X)/1X {v35[0]:.4f} / {v35[1]:.4f} / {v35[2]:.4f}",
             bool(v35[2] >= VISIBLE and v35[0] < v35[1] < v35[2]))]


def judge_a(m: dict) -> list[tuple[str, bool]]:
    """``[(our numbers, holds)]`` per statement of :data:`STATEMENTS_A` (point A), in order."""
    o, v2 = m["orbit_ratio"], m["v2_over_v1"]
    return [(f"max/min radius {o[0]:.2f} / {o[1]:.2f}", bool(np.all(o[:2] < NONCIRCULAR_RATIO))),
            (f"faces stuck {100 * m['stick_share']:.0f} % of the record", m["stick_share"] >= 1.0),
            (f"largest order {' / '.join(f'{k}X' for k in m['largest_order'])}", bool(np.all(m["largest_order"] == 1))),
            (f"2X/1X {v2[0]:.3f} / {v2[1]:.3f} / {v2[2]:.3f}", bool(v2[2] >= VISIBLE and v2[2] > v2[:2].max()))]


def _label(mesh) -> str:
    return "paper's mesh" if mesh is None else f"{mesh} elements/segment"


def _mesh_tag(mesh) -> str:
    """The protocol's name of a mesh: ``paper`` (the scene's own, 1 element per segment) or ``converged``."""
    return "paper" if mesh is None else "converged"


def readings_table(points) -> dict:
    """``{(reading, mesh): (measures at B, [(text, holds)] for B then A, {row id: (verdict, effect, noise)})}`` of
    finished points (mesh None = the paper's; the verdicts of reports/studies/protocol.py); the point A rows are
    left out when no 4 500 rpm point is there."""
    from reports.studies.protocol import judged_rows

    by = {}
    for p in points:
        key = (p.params["reading_name"], p.params.get("elements_per_segment"))
        by.setdefault(key, {})[round(p.params["speed_rpm"])] = None if "outside_law_domain" in p.info else \
            point_measures(p)
    out = {}
    for key, m in by.items():
        if round(POINT_B_RPM) not in m:
            continue
        mb, ma = m[round(POINT_B_RPM)], m.get(round(POINT_A_RPM), "none")
        rows = judge(mb) if mb is not None else [(BEYOND, False)] * len(STATEMENTS)
        judged = judged_rows(mb, None if ma == "none" else ma)
        if ma != "none":
            rows += judge_a(ma) if ma is not None else [(BEYOND, False)] * len(STATEMENTS_A)
        else:
            judged = {k: v for k, v in judged.items() if k.startswith("B")}
        out[key] = (mb, rows, judged)
    return out


#: the cell of a point whose load drives the ring past the conformal law's neat-fit limit (no record)
BEYOND = "beyond the contact law's domain (neat-fit limit)"


def protocol_scores(table: dict, current: str) -> tuple:
    """``(protocol, {weighting name: {case: score}}, {weighting name: highest reading}, unscored row ids)`` of
    :func:`readings_table` under reports/protocols/section5-readings.toml; the control is scored but never
    chosen (it is not a reading of Eq. 34); a tie keeps ``current``."""
    from reports.studies.protocol import load_protocol, score, unscored_rows, winner
    from rotor.studies.readings import CONTROL

    proto = load_protocol()
    judged = {(n, _mesh_tag(m)): j for (n, m), (_, _, j) in table.items()}
    readings = [n for n in dict.fromkeys(n for n, _ in judged) if n != CONTROL.name]
    scores = {w.name: score(proto, judged, w, CONTROL.name) for w in proto.weightings}
    best = {w: winner(s, readings, current) for w, s in scores.items()}
    return proto, scores, best, unscored_rows(judged)


_SYMBOL = {"meets": "✔", "within noise": "≈", "fails": "✘"}


def _cells(table: dict, keys, i: int, rid: str) -> list[str]:
    out = []
    for k in keys:
        text = table[k][1][i][0]
        v, e, n = table[k][2][rid]
        out.append(f"{_SYMBOL[v]} {text}" + ("" if np.isnan(e) else f"; e {e:+.3g}, noise {n:.2g}"))
    return out


def readings_note(table: dict, current: str, speed_rpm: float, integrator: str = "") -> str:
    """reports/published/section5-readings.md from :func:`readings_table`; ``integrator``: the sentence naming the
    time integrator's options the points were computed with (:func:`reports.studies.common.integrator_text`)."""
    from rotor.studies.readings import reading

    keys = sorted(table, key=lambda k: (k[0] == "no-excitation", k[0] != current, k[0], k[1] is not None, k[1] or 0))
    proto, scores, best, skip = protocol_scores(table, current)
    head = "| statement of the paper (B: Figs. 14–15; A: Fig. 13) | " + " | ".join(f"`{n}`, {_label(m)}" for n, m in keys) + " |"
    lines = [f"# Point B ({speed_rpm:.0f} rpm): which reading of Eq. 34", "",
             "Generated by `ringcontact study readings` (rotor.studies.readings, reports.studies.readings, "
             "reports.studies.protocol). Scene `paper-table4` (δ0 = 0.05 mm, δ = 1 mm, μ = 0.3, preload 5 000 N, tilt "
             "on) with each reading's placement, m_sp and L, and the no-excitation control (m_sp = 0: Eq. 34's F = M = "
             "0, the joint's misalignment offset kept); the paper's mesh (1 element per segment) and the converged "
             "mesh. Point B is the paper's high-speed point (§5.1: \"point B (10,500 rpm)\"). Each row is a sentence of "
             "the paper's text of Figs. 14–15 (B) or, as a cross-check, of Fig. 13 at point A (4 500 rpm), judged as "
             "the comparison protocol reports/protocols/section5-readings.toml states (committed before this run): "
             "the effect e is the signed margin to the row's threshold (positive: it holds; relative unless the "
             "protocol says absolute), the noise the model's numerical noise of that margin (the time step's "
             "amplitude error, or a non-periodic point's spectral floor; one sample for the contact share; stick "
             "shares exact); ✔ meets (e > noise), ≈ within noise, ✘ fails (e < −noise). Three numbers are disk 1 / "
             "disk 2 / support (y velocity for spectra). Scores: meets 1, within noise 0.5, fails 0, times the "
             "row's weight, over both meshes.", "",
             *([integrator, ""] if integrator else []),
             "| case | placement | m_sp (kg) | L (mm) | m_sp L² vs the 150 mm sleeve | the sentences it rests on |",
             "|---|---|---|---|---|---|"]
    for n in dict.fromkeys(k[0] for k in keys):
        r = reading(n)
        lines.append(f"| `{n}` | {r.excitation} | {r.shaft_mass_kg:g} | {r.lever_m * 1e3:g} | ×{r.moment_factor:.2f} | "
                     f"{r.rests_on} |")
    lines += ["", head, "|---|" + "---|" * len(keys)]
    n_rows = min(len(table[k][1]) for k in keys)
    for i, ((title, rule), row) in enumerate(list(zip(STATEMENTS + STATEMENTS_A, proto.rows))[:n_rows]):
        lines.append(f"| {row.id} {title}: {rule}{' (unscored)' if row.id in skip else ''} | "
                     + " | ".join(_cells(table, keys, i, row.id)) + " |")
    per = ["✘ no record" if table[k][0] is None else
           f"{'✔' if table[k][0]['periodic'] else '✘'} period {table[k][0]['period_revs']} rev" for k in keys]
    lines.append("| (point B periodic; not a row) | " + " | ".join(per) + " |")
    lines += ["", *_score_lines(proto, scores, best, skip, current), "",
              "Figure `section5-readings-scores.png/.svg`: the verdict of every row per case and mesh, and every case's "
              "score under each weighting.", ""]
    return "\n".join(lines)


def _score_lines(proto, scores: dict, best: dict, skip, current: str) -> list[str]:
    """The weightings' table and what it says about the scene's reading."""
    names = sorted(scores[proto.primary], key=lambda n: (n == "no-excitation", n))      # the control last
    lines = [f"Rows left unscored (met by every reading and the control on both meshes): "
             f"{', '.join(skip) or 'none'}.", "",
             "| weighting | why (protocol) | " + " | ".join(f"`{n}`" for n in names) + " | highest reading |",
             "|---|---|" + "---|" * len(names) + "---|"]
    for w in proto.weightings:
        tag = " (primary)" if w.name == proto.primary else ""
        sc = scores[w.name]
        tied = [n for n in names if n != "no-excitation" and abs(sc[n] - sc[best[w.name]]) < 1e-9]
        top = f"`{best[w.name]}`" if len(tied) == 1 else "tie: " + ", ".join(f"`{n}`" for n in tied)
        lines.append(f"| {w.name}{tag} | {w.why} | " + " | ".join(f"{sc[n]:.4g}" for n in names) + f" | {top} |")
    alt = [w.name for w in proto.weightings if w.name != proto.primary]
    held = [w + (" (tied)" if _tied(scores[w], best[w]) else "") for w in alt if best[w] == current]
    lost = [w for w in alt if best[w] != current]
    p = proto.primary
    top = f"`{best[p]}` scores highest under the primary weighting ({p}: {scores[p][best[p]]:.4g}"
    top += (f"; the scene's `{current}` {scores[p][current]:.4g})" if best[p] != current else ")")
    lines += ["", top + (", the scene's reading." if best[p] == current else ": the scene should carry it, or the "
                         "choice be argued on other grounds."),
              f"Under the {len(alt)} other weightings the protocol states, `{current}` scores highest under "
              f"{len(held)} ({', '.join(held) or 'none'}) and not under {len(lost)}"
              + (": " + "; ".join(f"{w} (`{best[w]}`)" for w in lost) if lost else "") + ".",
              "The no-excitation control scores " + f"{scores[p]['no-excitation']:.4g}" + " under the primary weighting."
              if "no-excitation" in scores[p] else ""]
    return lines


def _tied(sc: dict, best: str) -> bool:
    return sum(abs(v - sc[best]) < 1e-9 for n, v in sc.items() if n != "no-excitation") > 1


def readings_csv(table: dict, path: Path) -> Path:
    """One row per (case, mesh) with every measured number, each row's verdict, effect and noise (protocol)."""
    from reports.studies.protocol import load_protocol
    ids = [r.id for r in load_protocol().rows]
    head = ["reading", "elements_per_segment", "contact_share", "stick_share", "r1_min_over_d0", "r1_max_over_d0",
            "r2_min_over_d0", "r2_max_over_d0", "orbit_ratio_disk1", "orbit_ratio_disk2", "orbit_ratio_support",
            "disk2_radius_min_um", "disk2_radius_max_um", "v2_over_v1_disk1", "v2_over_v1_disk2",
            "v2_over_v1_support", "v345_over_v1_disk1", "v345_over_v1_disk2", "v345_over_v1_support", "periodic",
            "period_revs", *[f"{i}_{c}" for i in ids for c in ("verdict", "effect", "noise")]]
    rows = []
    for (n, mesh), (m, _, judged) in sorted(table.items(), key=lambda kv: (kv[0][0], kv[0][1] or 0)):
        if m is None:
            continue
        rows.append([n, mesh or 1, m["contact_share"], m["stick_share"], m["r1_min_over_d0"], m["r1_max_over_d0"],
                     m["r2_min_over_d0"], m["r2_max_over_d0"], *m["orbit_ratio"], *m["disk2_radius_um"],
                     *m["v2_over_v1"], *m["v35_over_v1"], int(m["periodic"]), m["period_revs"],
                     *[x for i in ids for x in (judged[i][0], float(judged[i][1]), float(judged[i][2]))]])
    return write_csv(path, head, rows)


def slip_lines(points) -> list[str]:
    """Markdown rows: per reading and mesh, the lowest speed of the low sweep where the end faces slip."""
    from rotor.studies.section5 import first_slip

    by: dict = {}
    for p in points:
        by.setdefault((p.params["reading_name"], p.params.get("elements_per_segment")), []).append(p)
    lines = ["| reading | mesh | faces first slip at (rpm) | contact there | beyond the law's domain at (rpm) | "
             "speeds swept (rpm) |", "|---|---|---|---|---|---|"]
    for (n, m), pts in sorted(by.items(), key=lambda kv: (kv[0][0], kv[0][1] or 0)):
        rpm, share = first_slip(pts)
        sp = sorted(p.params["speed_rpm"] for p in pts)
        out = [f"{p.params['speed_rpm']:.0f}" for p in sorted(pts, key=lambda p: p.params["speed_rpm"])
               if "outside_law_domain" in p.info]
        lines.append(f"| `{n}` | {_label(m)} | {'none' if rpm is None else f'{rpm:.0f}'} | "
                     f"{100 * share:.0f} % | {', '.join(out) or '—'} | {sp[0]:.0f}–{sp[-1]:.0f} |")
    return lines


def publish_readings(out, published, *, scene, tasks=None, low_tasks=None, extra: str = "") -> list[Path]:
    """section5-readings.md and .csv in ``published`` from the finished ``study readings`` directory ``out``;
    ``extra``: the hand-written reading appended (reports/notes/section5-readings-reading.md)."""
    from contact.files import atomic_write_text
    from reports.studies.common import integrator_text, load_points
    from rotor.model.scene import load_scene
    from rotor.studies.readings import scene_reading

    points = load_points(out, tasks)
    low = load_points(out, low_tasks) if low_tasks else []
    table = readings_table(points)
    current = scene_reading(load_scene(scene)) or "(none of the readings)"
    published = Path(published)
    # a point beyond the law's domain has no record, hence no integrator options: the others name them
    note = readings_note(table, current, POINT_B_RPM,
                         integrator_text([p.info for p in points + low if "outside_law_domain" not in p.info]))
    if low_tasks:
        note += ("\n## Relative displacement below 9 000 rpm, every reading\n\nDai et al. (2025) §5.3.1 (1): \"In the "
                 "low speed range (0~9000 rpm) ... there is no relative displacement between the bearing and "
                 "support\". Lowest speed of a 300 rpm sweep where the end faces slip (stuck < 100 % of the "
                 "record):\n\n" + "\n".join(slip_lines(low)) + "\n")
    note += "\n" + extra if extra else ""
    return [atomic_write_text(published / "section5-readings.md", note),
            readings_csv(table, published / "section5-readings.csv"),
            *scores_figure(table, current, published / "section5-readings-scores")]


def scores_figure(table: dict, current: str, prefix: Path) -> list[Path]:
    """Left: each row's verdict per case and mesh (meets / within noise / fails, unscored rows marked); right: each
    case's score under every weighting of the protocol, the scene's reading and the control marked."""
    from reports.studies.common import pyplot, save
    from reports.studies.protocol import FAILS, MEETS, WITHIN

    plt = pyplot()
    proto, scores, best, skip = protocol_scores(table, current)
    keys = sorted(table, key=lambda k: (k[0] == "no-excitation", k[0], k[1] or 0))
    ids = [r.id for r in proto.rows]
    code = {MEETS: 2, WITHIN: 1, FAILS: 0}
    grid = np.array([[code[table[k][2][i][0]] if i in table[k][2] else np.nan for i in ids] for k in keys])
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(14, 5.5), constrained_layout=True,
                                 gridspec_kw={"width_ratios": [1.1, 1.4]})
    from matplotlib.colors import ListedColormap
    ax.imshow(grid, cmap=ListedColormap(["#d62728", "#ffbf00", "#2ca02c"]), vmin=0, vmax=2, aspect="auto")
    ax.set_xticks(range(len(ids)), [f"{i}{' (unscored)' if i in skip else ''}" for i in ids], rotation=60, fontsize=8)
    ax.set_yticks(range(len(keys)), [f"{n}, {'paper' if m is None else f'{m}/segment'}" for n, m in keys], fontsize=8)
    ax.set_xlabel("row of the protocol (B: Figs. 14–15, A: Fig. 13)")
    ax.set_title("verdict per row (reports/protocols/section5-readings.toml)", fontsize=9)
    from matplotlib.patches import Patch
    ax.legend(handles=[Patch(color=c, label=l) for c, l in (("#2ca02c", MEETS), ("#ffbf00", WITHIN), ("#d62728", FAILS))],
              fontsize=7, loc="upper left", bbox_to_anchor=(0.0, -0.28), ncol=3)
    names = sorted(scores[proto.primary], key=lambda n: (n == "no-excitation", n))
    width = 0.8 / len(names)
    for j, n in enumerate(names):
        vals = [scores[w.name][n] for w in proto.weightings]
        style = {"hatch": "//", "edgecolor": "k"} if n == current else {"alpha": 0.5} if n == "no-excitation" else {}
        bx.bar(np.arange(len(proto.weightings)) + (j - len(names) / 2 + 0.5) * width, vals, width, label=n, **style)
    bx.set_xticks(range(len(proto.weightings)), [w.name + (" (primary)" if w.name == proto.primary else "")
                                                 for w in proto.weightings], rotation=25, ha="right", fontsize=8)
    bx.set_ylabel("score, both meshes (–)")
    bx.set_title(f"score per weighting (meets 1, within noise 0.5, fails 0, × weight); hatched: the scene's reading",
                 fontsize=9)
    bx.legend(fontsize=7)
    fig.suptitle("Which reading of Eq. 34: points B and A, every reading and the no-excitation control", fontsize=10)
    return save(fig, prefix)
