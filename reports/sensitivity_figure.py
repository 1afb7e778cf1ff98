"""The figure of the sensitivity study, readable without its Markdown: ``study-sensitivity.png/.svg``.

One row per variant, named by the parameter it changes in words, with the factor and the value it gives
(Table 4 rotor, ``rotor/scenes/paper-table4.toml``); one panel per finding of Dai et al. (2025) §5, its
output in words with its unit; one dot per speed. The ratios span ten decades over the variants, so the
axis is logarithmic over ±2 decades (1/100 … 100) with every decade labelled, and a ratio beyond is
drawn as a triangle on the edge (its value is in ``study-sensitivity-points.csv``).

Drawn from :class:`rotor.studies.sensitivity.AmplitudeTable` s: the study's own (``study publish``,
``study sensitivity``) or rebuilt from the committed ``study-sensitivity-points.csv``
(:func:`tables_from_points_csv`, ``study redraw``), with the same function.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from contact.errors import DatasetError, InputError
from reports.studies.common import pyplot, read_csv_rows, require_columns, save
from rotor.studies import sensitivity as sens

#: decades drawn each side of a ratio of 1; beyond, the ratio is clipped to the edge and drawn as a triangle
DECADES = 2
#: factor key -> (words, parameter of rotor.studies.sensitivity.PARAMETERS shown, scale to the unit, unit)
FACTOR_WORDS = {
    "ks_theta": ("support tilt stiffness & damping k_s,θ", "support_angular_stiffness_n_m_rad", 1e-3, "kN·m/rad"),
    "js": ("support tilt inertia J_s", "support_inertia_kg_m2", 1.0, "kg·m²"),
    "ks": ("support-to-ground stiffness & damping k_s", "support_stiffness_n_m", 1e-6, "MN/m"),
    "a0": ("coupling angular stiffness a0", "coupling_a0_n_m_rad", 1e-6, "MN·m/rad"),
    "a1": ("coupling cubic stiffness a1", "coupling_a1_n_m_rad3", 1e-12, "TN·m/rad³"),
    "msp": ("transition-shaft mass m_sp", "coupling_shaft_mass_kg", 1.0, "kg"),
    "lever": ("transition-shaft lever L", "coupling_lever_m", 1e3, "mm"),
    "cc": ("collision factor c_c", "collision_factor_s_m", 1.0, "s/m"),
    "preload": ("end-face friction limit μN", "preload_n", 1.0, "N"),
    "mu": ("end-face friction coefficient μ", "friction_coefficient", 1.0, "–"),
}
#: finding -> (output in words and unit, threshold, the paper's side)
PANELS = {
    "clearance": ("3X displacement amplitude at disk 2 (µm),\nclearance δ0 = 0.03 mm over δ0 = 0.08 mm  "
                  "[ratio, –]\npaper (Fig. 18): > 1", 1.0, "above"),
    "misalignment": ("3X displacement amplitude at disk 2 (µm),\nmisalignment δ = 2 mm over δ = 0.5 mm  "
                     "[ratio, –]\npaper (Fig. 19): > 1", 1.0, "above"),
    "tilt": ("3X+4X+5X y-velocity amplitude at disk 2 (mm/s),\ntilt ignored over tilt modelled  "
             f"[ratio, –]\npaper (Fig. 16): ≤ {sens.MARKEDLY:g} (markedly lower)", sens.MARKEDLY, "below"),
}


def variant_label(variant, base: dict) -> str:
    """``"support tilt stiffness & damping k_s,θ ×0.01 → 1.5 kN·m/rad"``; one line per factor."""
    reading = getattr(variant, "reading", None)
    if not variant.factors:
        return f"reading {reading} of Eq. 34, as it is" if reading else "Table 4 rotor as published (reference)"
    lines = [f"reading {reading}:"] if reading else []
    for key, factor in variant.factors.items():
        words, param, scale, unit = FACTOR_WORDS.get(key, (key, None, 1.0, ""))
        value = base.get(param, math.nan) * factor * scale
        if key == "preload":                         # only the product μN enters: show it
            value *= base.get("friction_coefficient", math.nan)
        shown = np.format_float_positional(value, precision=3, unique=True, fractional=False, trim="-") \
            if np.isfinite(value) else "?"
        lines.append(f"{words} ×{factor:g} → {shown} {unit}".rstrip())
    return "\n".join(lines)


def tables_from_points_csv(path) -> tuple[dict, list]:
    """``({variant: AmplitudeTable}, variants)`` rebuilt from ``study-sensitivity-points.csv``.

    The table holds disk 2 and the support (the CSV's locations), amplitudes back in SI; the variants
    are the study's (:func:`rotor.studies.sensitivity.all_variants`) where the names match, in the
    CSV's order, else a variant without factors named as in the CSV.
    """
    rows = read_csv_rows(path)
    locs = (("disk2", "disk2.y"), ("support", "s.y"))
    cols = [f"{lab}_{h}X_{u}" for lab, _ in locs for h in sens.ORDERS for u in ("um", "mm_s")]
    require_columns(path, rows, ["variant", "speed_rpm", "case", "periodic", "contact_fraction"] + cols)
    known = {v.name: v for v in sens.all_variants()}
    names = list(dict.fromkeys(r["variant"] for r in rows))
    try:
        tabs = {name: _table(rows, name, locs) for name in names}
    except InputError as exc:                       # negative or non-finite amplitudes
        raise DatasetError(f"{path}: {exc}") from None
    except ValueError as exc:
        raise DatasetError(f"{path}: a cell is not a number ({exc})") from None
    return tabs, [known.get(n, sens.Variant(n, {}, "")) for n in names]


def _table(rows: list[dict], name: str, locs) -> sens.AmplitudeTable:
    """One variant's rows of ``study-sensitivity-points.csv`` as an AmplitudeTable (SI)."""
    mine = [r for r in rows if r["variant"] == name]
    speeds = sorted({float(r["speed_rpm"]) for r in mine})
    cases = tuple(dict.fromkeys(r["case"] for r in mine))
    C, S, L = len(cases), len(speeds), len(locs)
    q, v = np.zeros((C, S, len(sens.ORDERS), L)), np.zeros((C, S, len(sens.ORDERS), L))
    per, cf = np.zeros((C, S), bool), np.zeros((C, S))
    for r in mine:
        ci, k = cases.index(r["case"]), speeds.index(float(r["speed_rpm"]))
        per[ci, k], cf[ci, k] = r["periodic"] == "True", float(r["contact_fraction"])
        for j, (lab, _) in enumerate(locs):
            q[ci, k, :, j] = [float(r[f"{lab}_{h}X_um"]) * 1e-6 for h in sens.ORDERS]
            v[ci, k, :, j] = [float(r[f"{lab}_{h}X_mm_s"]) * 1e-3 for h in sens.ORDERS]
    return sens.AmplitudeTable(np.array(speeds), cases, tuple(loc for _, loc in locs), q, v, per, cf)


def _decade_axis(ax, threshold: float, side: str) -> None:
    lim = DECADES + 0.25
    ax.set_xlim(-lim, lim)
    ticks = np.arange(-DECADES, DECADES + 1)
    ax.set_xticks(ticks, [("≤ " if t == -DECADES else "≥ " if t == DECADES else "")
                          + (f"{10.0 ** t:g}" if t >= 0 else f"1/{10 ** -t:g}") for t in ticks], fontsize=8)
    ax.set_xticks([math.log10(m * 10.0 ** d) for d in range(-DECADES, DECADES) for m in range(2, 10)], minor=True)
    t = math.log10(threshold)
    ax.axvline(t, color="k", lw=0.8, label=f"threshold {threshold:g}")
    span = (t, lim) if side == "above" else (-lim, t)
    ax.axvspan(*span, color="tab:green", alpha=0.08, label="paper's side")
    ax.grid(True, axis="x", which="major", alpha=0.4)
    ax.grid(True, axis="x", which="minor", alpha=0.12)


def _panel(ax, tabs: dict, names: list, rows_y, finding: str, colour) -> None:
    for i, n in zip(rows_y, names):
        t = tabs[n]
        r, per = per_speed_ratios(t)[finding]
        coll = (np.asarray(t.contact_fraction)[t.cases.index("base")] > 0 if t.contact_fraction is not None
                else np.ones(len(r), bool))
        for k, (x, ok, rpm) in enumerate(zip(r, per, t.speeds_rpm)):
            if not np.isfinite(x) or x <= 0:
                continue
            d = math.log10(x)
            marker = ">" if d > DECADES else "<" if d < -DECADES else "o" if coll[k] else "s"
            ax.scatter([min(max(d, -DECADES - 0.12), DECADES + 0.12)], [i + (k - len(t.speeds_rpm) / 2) * 0.1],
                       s=22, marker=marker, facecolors=colour(rpm) if ok else "none", edgecolors=colour(rpm),
                       linewidths=1.0, zorder=3, clip_on=False)


def per_speed_ratios(table) -> dict:
    """Per speed, the deciding ratio of each finding at disk 2 and whether every compared case is
    periodic: ``{finding: (ratios (S,), periodic (S,) bool)}``; clearance 3X(0.03)/3X(0.08) and
    misalignment 3X(2)/3X(0.5) of the displacement, tilt Σ3X–5X off/on of the y velocity."""
    j = table.locations.index("disk2.y")
    out = {}
    for f, (a, b, q, sl, cases) in {
            "clearance": ("clear0.03", "clear0.08", "q", slice(2, 3), ("clear0.03", "base", "clear0.08")),
            "misalignment": ("mis2", "mis0.5", "q", slice(2, 3), ("mis0.5", "base", "mis2")),
            "tilt": ("notilt", "base", "v", slice(2, 5), ("base", "notilt"))}.items():
        num = table.amp(q, a)[:, sl, j].sum(axis=1)
        den = table.amp(q, b)[:, sl, j].sum(axis=1)
        per = np.all([table.ok(c) for c in cases], axis=0)
        out[f] = (num / np.maximum(den, 1e-300), per)
    return out


def figure(tabs: dict, variants, prefix: Path, *, scene: str = "paper-table4") -> list:
    """Deciding ratio of each finding per variant and speed at disk 2; filled: every compared case periodic;
    square: the reference case does not collide; triangles: beyond the ±2-decade axis; green: the paper's side."""
    from rotor.model.scene import load_scene

    plt = pyplot()
    chosen = [v for v in variants if v.name in tabs]
    names = [v.name for v in chosen]
    from rotor.studies.readings import reading_scene

    sc = load_scene(scene)
    labels = [variant_label(v, sens.base_values(reading_scene(sc, v.reading) if v.reading else sc)) for v in chosen]
    pitch = np.array([1.0 + 0.45 * lab.count("\n") for lab in labels])      # a row per label line, in row units
    rows_y = np.cumsum(pitch) - pitch / 2
    fig, axes = plt.subplots(1, 3, figsize=(16, 0.34 * pitch.sum() + 2.6), sharey=True)
    cmap = plt.get_cmap("plasma")
    speeds = np.array(sens.SPEEDS_RPM)

    def colour(rpm):
        return cmap((rpm - speeds.min()) / max(np.ptp(speeds), 1.0) * 0.85)
    for ax, (f, (lab, thr, side)) in zip(axes, PANELS.items()):
        _panel(ax, tabs, names, rows_y, f, colour)
        _decade_axis(ax, thr, side)
        ax.set_xlabel(lab, fontsize=8)
    axes[0].set_yticks(rows_y, labels, fontsize=7)
    axes[0].set_ylim(pitch.sum(), 0)
    for rpm in speeds:
        axes[2].scatter([], [], s=22, color=colour(rpm), label=f"{rpm:.0f} rpm")
    for kw, text in (({"facecolors": "none", "edgecolors": "k"}, "not every compared case periodic"),
                     ({"marker": "s", "color": "k"}, "reference case does not collide"),
                     ({"marker": ">", "color": "k"}, f"beyond ×{10 ** DECADES} (or below 1/{10 ** DECADES}),\n"
                                                     "drawn on the edge")):
        axes[2].scatter([], [], s=22, label=text, **kw)
    axes[2].legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))     # speeds and marks: all panels
    for ax, where in zip(axes[:2], ("lower right", "lower left")):                  # each panel: its threshold,
        ax.legend(fontsize=7, loc=where, framealpha=0.9)                             # where its dots leave room
    fig.suptitle("Do the §5 findings of Dai et al. (2025) hold when the inputs Table 4 does not give are changed?\n"
                 "Deciding ratio per changed input (rows) and speed (dots), Table 4 rotor; green: the paper's side",
                 fontsize=10)
    fig.tight_layout()
    return save(fig, prefix)


def redraw(points_csv, prefix: Path, *, scene: str = "paper-table4") -> list:
    """``study-sensitivity.png/.svg`` from the committed ``study-sensitivity-points.csv``."""
    tabs, variants = tables_from_points_csv(points_csv)
    return figure(tabs, variants, prefix, scene=scene)
