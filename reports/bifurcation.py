"""Bifurcation diagram of a branch of periodic orbits (``ringcontact branch --plot``).

Top: a harmonic velocity amplitude at one channel against speed, stable orbits solid, unstable dashed,
each bifurcation marked with its kind (Seydel 2010, *Practical Bifurcation and Stability Analysis*, the usual
drawing). Bottom: the spectral radius of the non-neutral Floquet multipliers against speed, with the unit
circle's radius 1, so that the reader sees how far each orbit is from losing its stability.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import pyplot, save

#: marker and colour of each bifurcation kind
KINDS = {"fold": ("o", "tab:red", "fold"), "period_doubling": ("s", "tab:purple", "period doubling"),
         "neimark_sacker": ("D", "tab:orange", "Neimark–Sacker"),
         "grazing_fold": ("v", "tab:green", "grazing fold"), "grazing": ("^", "tab:green", "grazing"),
         "branch_point": ("P", "tab:brown", "branch point"),
         "discontinuous": ("X", "tab:pink", "discontinuous (at a switch)")}


def stability_runs(stable) -> list[tuple[int, int, bool]]:
    """``(first, last, stable)`` index runs of equal stability; neighbouring runs share their end point so
    that the drawn curve is continuous."""
    stable = [bool(s) for s in stable]
    runs, start = [], 0
    for i in range(1, len(stable) + 1):
        if i == len(stable) or stable[i] != stable[start]:
            runs.append((start, min(i, len(stable) - 1), stable[start]))
            start = i
    return runs


def branch_curve(branch: dict, channel: str, order: int = 1):
    """``(speed_rpm, amplitude_mm_s, spectral_radius, stable)`` arrays of the branch's points."""
    pts = branch["points"]
    rpm = np.array([p["speed_rpm"] for p in pts], float)
    amp = np.array([p["velocity_amplitudes_mm_s_1X_to_5X"][channel][order - 1] for p in pts], float)
    rad = np.array([p["spectral_radius"] for p in pts], float)
    return rpm, amp, rad, np.array([bool(p["stable"]) for p in pts])


def bifurcation_figure(branch, channel, prefix, order: int = 1, labels: dict | None = None) -> list[Path]:
    """Draw ``prefix.png`` and ``prefix.svg`` of ``branch`` (the JSON of ``ringcontact branch``, or a list of
    them: segments of one speed range, each drawn on its own). ``channel``: one channel (``disk1.y``) or a
    sequence of them, one amplitude panel each, the first on top; ``labels``: a channel's name in words."""
    plt = pyplot()
    channels = (channel,) if isinstance(channel, str) else tuple(channel)
    labels = labels or {}
    segments = branch if isinstance(branch, (list, tuple)) else [branch]
    fig, axes = plt.subplots(len(channels) + 1, 1, figsize=(7.5, 3.4 + 2.8 * len(channels)), sharex=True,
                             height_ratios=(3,) * len(channels) + (1.4,), constrained_layout=True)
    *amp_axes, axr = axes
    for k, (ax, ch) in enumerate(zip(amp_axes, channels)):
        seen: set = set()             # legend labels drawn, and (kind, speed) of the bifurcations labelled
        for seg in segments:
            if seg["points"]:
                _draw(ax, axr if k == 0 else None, seg, ch, order, seen)
        ax.set_ylabel(f"{order}X velocity amplitude (mm/s)")
        ax.set_title(f"at {labels.get(ch, ch)}", fontsize=9, loc="left")
        ax.legend(fontsize=8, loc="best")
    axr.axhline(1.0, color="k", lw=0.8, label="unit circle")
    axr.set_yscale("log")            # from well inside the circle to far outside on one axis
    axr.set_ylabel("largest |multiplier| (log)")
    axr.set_xlabel("rotor speed (rpm)")
    axr.legend(fontsize=8, loc="upper left")
    periods = sorted({s.get("period_revs", 1) for s in segments})
    fig.suptitle(f"{segments[0].get('scene', '')}: periodic orbits by shooting, continued in speed "
                 f"(period {', '.join(map(str, periods))} rev)", fontsize=9)
    for a in axes:
        a.grid(True, lw=0.3, alpha=0.5)
    return save(fig, Path(prefix))


def _draw(ax, axr, branch: dict, channel: str, order: int, seen: set) -> None:
    """One branch: its stability runs and its bifurcations (``seen``: legend labels already drawn); the
    multipliers on ``axr`` unless it is None (drawn once, with the first channel)."""
    rpm, amp, rad, stable = branch_curve(branch, channel, order)
    for a, b, st in stability_runs(stable):
        lab = "stable" if st else "unstable"
        sl = slice(a, b + 1)
        ax.plot(rpm[sl], amp[sl], "-" if st else "--", color="tab:blue" if st else "tab:gray", lw=1.6,
                label=lab if lab not in seen else None)
        if axr is not None:
            axr.plot(rpm[sl], rad[sl], "-" if st else "--", color="tab:blue" if st else "tab:gray", lw=1.2)
        seen.add(lab)
    for bif in branch["bifurcations"]:
        mark, colour, name = KINDS.get(bif["kind"], ("x", "k", bif["kind"]))
        i = int(bif["after_point"])
        x = float(bif["speed_rpm"])
        lo, hi = max(i - 1, 0), min(i, len(rpm) - 1)
        w = 0.0 if rpm[hi] == rpm[lo] else (x - rpm[lo]) / (rpm[hi] - rpm[lo])
        y = amp[lo] + min(max(w, 0.0), 1.0) * (amp[hi] - amp[lo])
        ax.plot([x], [y], mark, color=colour, ms=8, mfc="none", mew=1.8, label=name if name not in seen else None)
        seen.add(name)
        spot = (bif["kind"], round(x / 25.0))        # the same bifurcation met again (another segment): one label
        if spot in seen or (id(branch), bif["kind"]) in seen:   # and one label per kind and segment (an
            continue                                             # unstable branch meets many pairs leaving)
        seen.update({spot, (id(branch), bif["kind"])})
        k = sum(1 for t in seen if isinstance(t, tuple))
        ax.annotate(f"{name}\n{x:.0f} rpm", (x, y), textcoords="offset points", xytext=(-40 + 14 * (k % 2), 10 + 16 * (k % 3)),
                    fontsize=7, color=colour)
        if axr is not None:
            axr.axvline(x, color=colour, lw=0.8, ls=":")


def segments_table(segments) -> str:
    """Markdown table of branch segments (the JSON of ``ringcontact branch`` each): range covered, orbits,
    stable share, largest spectral radius, bifurcations, the points reached by restarts past a switch (by
    kind, :mod:`rotor.periodic.continuation`; a column only when the segments carry ``restarts``) and why each
    stopped."""
    restarts = any("restarts" in s for s in segments)
    extra = (" restarts past switches (secant/transient/cold/step-grid) |", "---|") if restarts else ("", "")
    lines = ["| start (rpm) | reached (rpm) | target (rpm) | orbits | stable | largest spectral radius | "
             "bifurcations |" + extra[0] + " stopped |", "|---|---|---|---|---|---|---|" + extra[1] + "---|"]
    for s in segments:
        pts = s["points"]
        r = s.get("restarts", {})
        rtext = (f" {r.get('secant', 0)}/{r.get('transient', 0)}/{r.get('cold', 0)}/{r.get('step-grid', 0)} |"
                 if restarts else "")
        if not pts:
            lines.append(f"| {s['rpm_start']:.0f} | – | {s['rpm_end']:.0f} | 0 | – | – | – |{rtext} {s['stop']} |")
            continue
        rpm = [p["speed_rpm"] for p in pts]
        stable = sum(bool(p["stable"]) for p in pts)
        bifs = _bifurcation_text(s["bifurcations"])
        lines.append(f"| {s['rpm_start']:.0f} | {max(rpm):.0f} | {s['rpm_end']:.0f} | {len(pts)} | "
                     f"{stable}/{len(pts)} | {max(p['spectral_radius'] for p in pts):.4f} | {bifs} |{rtext} {s['stop']} |")
    return "\n".join(lines)


def _bifurcation_text(bifurcations) -> str:
    """``kind speed`` of each bifurcation in order, a kind met more than twice as ``kind ×n (first–last)``."""
    by: dict = {}
    for b in bifurcations:
        by.setdefault(b["kind"], []).append(b["speed_rpm"])
    parts = []
    for kind, xs in by.items():
        name = kind.replace("_", " ")
        parts += ([f"{name} {x:.0f}" for x in xs] if len(xs) <= 2 else
                  [f"{name} ×{len(xs)} ({min(xs):.0f}–{max(xs):.0f})"])
    return "; ".join(parts) or "none"


def restarts_table(segment: dict) -> str:
    """Markdown table of the points a branch reached by a restart past a switch: the speeds skipped, how the
    orbit was shot, and why the corrector failed before it (``restart_reason``); "none" if no restart."""
    lines = ["| skipped (rpm) | shot | why the corrector failed before it |", "|---|---|---|"]
    rows = [f"| {p['skipped_rpm'][0]:.1f} – {p['skipped_rpm'][1]:.1f} | {p['restarted']} | "
            f"{p.get('restart_reason') or '–'} |" for p in segment["points"] if p.get("skipped_rpm")]
    return "\n".join(lines + (rows or ["| none | | |"]))


def bifurcations_table(segment: dict) -> str:
    """Markdown table of a branch's bifurcations: kind, speed and, for a discontinuous one, both sides."""
    rows = [f"| {b['kind'].replace('_', ' ')} | {b['speed_rpm']:.1f} | {b.get('detail', '')} |"
            for b in segment["bifurcations"]]
    return "\n".join(["| kind | speed (rpm) | detail |", "|---|---|---|"] + (rows or ["| none | | |"]))


#: the published diagram's channels, the loose support first: the Table 4 scene's support "s" (the 3# bearing's
#: pedestal, "the support" of the Section 5 studies, reports/studies/common.py) and disk 1
PUBLISHED_CHANNELS = ("s.y", "disk1.y")
CHANNEL_WORDS = {"s.y": "the loose support (s.y, the 3# bearing's support)", "disk1.y": "disk 1 (disk1.y)"}


def publish(segments, out_dir, *, channel=PUBLISHED_CHANNELS, commands=(), reading: str = "") -> list[Path]:
    """``study-bifurcation.{png,svg,md,json}`` in ``out_dir`` from branch segments (the JSON of ``ringcontact
    branch`` each; the JSON keeps the amplitudes of ``channel`` only: one channel or a sequence, one panel each,
    the first on top). ``commands``: the command lines that made them; ``reading``: the hand-written reading
    appended (reports/notes/study-bifurcation-reading.md)."""
    import json

    from contact.files import atomic_write_text

    out_dir = Path(out_dir)
    channels = (channel,) if isinstance(channel, str) else tuple(channel)
    files = bifurcation_figure(list(segments), channels, out_dir / "study-bifurcation", labels=CHANNEL_WORDS)
    where = " and at ".join(CHANNEL_WORDS.get(c, c) for c in channels)
    scene = next((s.get("scene") for s in segments if s.get("scene")), "")
    how = ("in one run from its first speed" if len(segments) == 1 else
           "in segments started at speeds where the orbit exists")
    lines = [f"# Bifurcation diagram, {scene}: periodic orbits continued in speed", "",
             "Made by `ringcontact branch` (pseudo-arclength continuation of the shooting orbit, "
             "`rotor/periodic/continuation.py`, Floquet multipliers of each orbit) over the Fig. 12 speed range, "
             f"{how}:", "", "```sh", *commands, "```", "",
             f"Figure: `study-bifurcation.png/.svg`, 1X velocity amplitude at {where}, one panel each (stable solid, "
             "unstable dashed, bifurcations marked with their kind) and the largest non-neutral |multiplier| against "
             "speed. "
             "Data: `study-bifurcation.json` (each segment's points, bifurcations and why it stopped).", "",
             segments_table(segments), ""]
    if len(segments) == 1 and segments[0]["points"]:
        lines += ["Bifurcations (a *discontinuous* one: a multiplier that jumps across the unit circle between two "
                  "orbits whose stick/slip switches per period differ, Leine & van Campen 2002):", "",
                  bifurcations_table(segments[0]), "", "Restarts past switches:", "", restarts_table(segments[0]), ""]
    if reading:
        lines += [reading.strip(), ""]
    files.append(atomic_write_text(out_dir / "study-bifurcation.md", "\n".join(lines)))
    slim = [{**{k: v for k, v in s.items() if k not in ("points", "start")},
             "points": [{**{k: v for k, v in p.items() if k != "velocity_amplitudes_mm_s_1X_to_5X"},
                         **{f"velocity_amplitudes_mm_s_1X_to_5X_{c}": p["velocity_amplitudes_mm_s_1X_to_5X"][c]
                            for c in channels}}
                        for p in s["points"]]} for s in segments]
    files.append(atomic_write_text(out_dir / "study-bifurcation.json", json.dumps(slim, indent=1) + "\n"))
    return files
