"""Spectrum cascades over speed (Dai et al. 2025 Figs. 12, 16, 17): figures, CSV and the note."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import LOCATIONS, channel_column, harmonic_table, load_points, pyplot, save, write_csv


def _cascade_axes(ax, points, get, unit_scale, label, floor_rel=1e-4):
    plt = pyplot()
    from matplotlib.colors import LogNorm

    xs, ys, cs = [], [], []
    for p in points:
        rpm = p.params["speed_rpm"]
        if rpm <= 0:
            continue
        f = rpm / 60.0
        amp = get(p) * unit_scale
        orders = p.arrays["spec_orders"]
        xs.append(orders * f)
        ys.append(np.full(orders.shape, rpm))
        cs.append(amp)
    if not xs:
        return None
    x, y, c = np.concatenate(xs), np.concatenate(ys), np.concatenate(cs)
    top = c.max() if c.size else 1.0
    keep = c > top * floor_rel
    order = np.argsort(c[keep])
    sc = ax.scatter(x[keep][order], y[keep][order], c=c[keep][order], s=6 + 30 * (c[keep][order] / top) ** 0.5,
                    norm=LogNorm(vmin=top * floor_rel, vmax=top), cmap="viridis", linewidths=0,
                    rasterized=True)  # thousands of dots: raster inside the SVG, axes stay vector
    rmax = max(p.params["speed_rpm"] for p in points)
    for k in range(1, 6):
        ax.plot([0, k * rmax / 60], [0, rmax], ":", color="0.6", lw=0.7)
        ax.annotate(f"{k}f", (min(k * rmax / 60, 5.4 * rmax / 60), min(rmax, 5.4 * rmax / k)), fontsize=7, color="0.4")
    ax.set_xlim(0, 5.5 * rmax / 60)
    ax.set_ylim(0, rmax * 1.02)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("rotor speed (rpm)")
    ax.set_title(label, fontsize=9)
    plt.colorbar(sc, ax=ax, pad=0.01)
    return sc


#: how ``--method shooting`` marks a speed whose orbit is not a stable periodic one (rotor.studies.shooting_point)
STABILITY_MARKS = {"quasi_periodic": ("D", "tab:orange", "unstable: complex pair out (quasi-periodic)"),
                   "period_doubling": ("s", "tab:purple", "unstable: multiplier < −1 (period doubling)"),
                   "unstable_fold": ("x", "tab:red", "unstable: real multiplier > 1"),
                   "non_periodic": ("o", "0.3", "no orbit; transient not periodic"),
                   "no_orbit_found": ("o", "0.6", "no orbit found")}


def mark_stability(ax, points) -> None:
    """Markers at the right edge of a cascade at the speeds classified unstable, quasi-periodic or
    non-periodic (points of ``study cascade --method shooting``; nothing for transient points)."""
    if not any("classification" in p.info for p in points):
        return
    x = ax.get_xlim()[1]
    for cls, (mark, colour, label) in STABILITY_MARKS.items():
        rpm = [p.params["speed_rpm"] for p in points if p.info.get("classification") == cls]
        if rpm:
            ax.plot([0.97 * x] * len(rpm), rpm, mark, color=colour, ms=5, mfc="none", mew=1.2, label=label)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=6, loc="upper left", framealpha=0.8)


def cascade_figures(out, figs, *, tasks=None, prefix: str = "study-cascade", title: str = "") -> list[Path]:
    """Velocity-y spectrum cascades at disk 1, disk 2, 3# bearing (Fig. 12 / 16), the relative-tilt
    cascade (Fig. 17), and ``<prefix>.csv`` with 1X–5X per speed, convergence and regime."""
    plt = pyplot()
    figs = Path(figs)
    points = load_points(out, tasks)
    files = []
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6), constrained_layout=True)
    for ax, (ch, lab) in zip(axes, LOCATIONS):
        _cascade_axes(ax, points, lambda p, ch=ch: p.arrays["spec_v"][:, channel_column(p, ch)], 1e3,
                      f"{lab}: y-velocity amplitude (mm/s)")
        mark_stability(ax, points)
    fig.suptitle(title or "Steady-state spectrum cascades (y velocity), Table 4 rotor", fontsize=10)
    files += save(fig, figs / prefix)
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 4.6), constrained_layout=True)
    for ax, (k, lab) in zip(axes, ((2, "relative tilt θy (mrad)"), (3, "relative tilt θz (mrad)"))):
        _cascade_axes(ax, points, lambda p, k=k: p.arrays["spec_u"][:, k], 1e3, f"bearing − support: {lab}")
    fig.suptitle("Relative angular deflection between bearing and support (paper Fig. 17)", fontsize=10)
    files += save(fig, figs / f"{prefix}-tilt")
    rpm, V = harmonic_table(points, "v")
    _, U = harmonic_table(points, "u", channels=("θy", "θz"), orders=(1, 2, 3))
    header = ["speed_rpm", "converged", "period_revs", "regime", "contact_fraction", "stick_fraction",
              "transient_revs", "wall_s"]
    header += [f"{c}_v{o}X_mm_s" for c in ("disk1", "disk2", "support") for o in range(1, 6)]
    header += [f"tilt_{a}_{o}X_mrad" for a in ("y", "z") for o in range(1, 4)]
    rows = []
    for i, p in enumerate(points):
        inf = p.info
        rows.append([rpm[i], int(inf["converged"]), inf["period_revs"], inf["label"], inf["contact_fraction"],
                     inf["stick_fraction"], inf["transient_revs"], p.record.get("run", {}).get("wall_s", float("nan"))]
                    + list((V[i] * 1e3).ravel()) + list((U[i] * 1e3).ravel()))
    if any("classification" in p.info for p in points):      # --method shooting: the Floquet verdict per speed
        header += ["classification", "classified_by", "stable", "spectral_radius", "critical_kind"]
        for r, p in zip(rows, points):
            r += [p.info.get(k, "") for k in ("classification", "classified_by", "stable", "spectral_radius",
                                               "critical_kind")]
    files.append(write_csv(figs / f"{prefix}.csv", header, rows))
    return files


def _fmt(x, unit="", d=3):
    return f"{x:.{d}g}{(' ' + unit) if unit else ''}"


def cascade_note(points, notilt=None, timing=None) -> str:
    """Markdown: Figs. 12, 16, 17 against the paper's statements, with our numbers."""
    rpm, V = harmonic_table(points, "v")
    _, U = harmonic_table(points, "u", channels=("θy", "θz"), orders=(1,))
    lab = [p.info["label"] for p in points]
    conv = np.array([p.info["converged"] for p in points])
    hi = rpm >= 9000
    lines = ["# Spectrum cascades, Table 4 rotor (paper Figs. 12, 16, 17)", "",
             "Regenerated by `ringcontact study cascade` (+ `--tilt-ignored`), steady state detected per speed "
             "(Poincaré section, `rotor.studies.steady_state`), spectra over whole revolutions (exact bins). Paper's conformal "
             "law as published, scene `paper-table4` with its documented assumptions.", ""]
    if timing:
        t = timing[-1]
        lines += [f"**Timing:** {len(points)} speeds in {t['wall_s']:.0f} s wall with {t['workers']} worker "
                  f"processes ({t['wall_s'] / max(len(points), 1):.1f} s per point on the sweep clock; median "
                  f"{t['point_wall_s_median']:.1f} s per point inside a worker), shared 2-core machine, "
                  f"load average at the end {t['load_avg_end'][0]:.1f}.", ""]
    # regimes by speed band
    bands = []
    cur = None
    for r, l in zip(rpm, lab):
        if cur is None or cur[0] != l:
            cur = [l, r, r]
            bands.append(cur)
        else:
            cur[2] = r
    lines += ["**Loose-support regime by speed:** " + "; ".join(f"{a:.0f}–{b:.0f} rpm {l}" for l, a, b in bands) + ".",
              "", "**Speeds without a periodic steady state within the transient cap** (quasi-periodic or chaotic; "
              "their spectra carry broadband content between the harmonics): "
              + (", ".join(f"{r:.0f}" for r in rpm[~conv]) or "none") + " rpm.", ""]
    share1 = V[:, :, 0] / np.maximum(V.sum(axis=2), 1e-30)
    hi3 = V[hi][:, :, 2:5].sum(axis=2)
    lines += ["| statement of the paper | ours | agrees? |", "|---|---|---|"]
    lines.append(f"| Response primarily at f | 1f is {100 * np.median(share1[rpm > 0]):.1f} % (median over speeds and "
                 f"locations) of the 1f–5f sum; lowest {100 * share1[rpm > 0].min():.1f} % | yes |")
    lo = (rpm > 0) & (rpm < 9000)
    r2 = V[lo][:, :, 1] / V[lo][:, :, 0]
    lines.append(f"| 2f present (misalignment) | 2f/1f below 9 000 rpm: disk 1 median {_fmt(np.median(r2[:, 0]))}, "
                 f"disk 2 {_fmt(np.median(r2[:, 1]))}, support {_fmt(np.median(r2[:, 2]))} | "
                 f"{'yes' if np.median(r2[:, 2]) >= 0.05 else 'yes (small)'} |")
    if hi.any():
        r = hi3 / np.maximum(hi3[:, [0]], 1e-30)
        lines.append(f"| At high speed 3f–5f significant at disk 2 and the 3# bearing, more than at disk 1 | "
                     f"sum 3f–5f ≥ 9 000 rpm, ratio to disk 1: disk 2 median {_fmt(np.median(r[:, 1]))}, support "
                     f"median {_fmt(np.median(r[:, 2]))}; largest at disk 2 {_fmt(hi3[:, 1].max() * 1e3, 'mm/s')} "
                     f"({rpm[hi][np.argmax(hi3[:, 1])]:.0f} rpm) | "
                     f"{'yes' if np.median(r[:, 1]) > 1 and np.median(r[:, 2]) > 1 else 'no'} |")
    if notilt:
        rpm0, V0 = harmonic_table(notilt, "v")
        common = np.intersect1d(rpm[hi], rpm0[rpm0 >= 9000])
        if common.size:
            a = np.array([V[rpm == s][0, :, 2:5].sum(axis=1) for s in common])
            b = np.array([V0[rpm0 == s][0, :, 2:5].sum(axis=1) for s in common])
            ratio = b / np.maximum(a, 1e-30)
            lines.append(f"| Fig. 16: harmonics markedly reduced when tilt is ignored | sum 3f–5f tilt-ignored / "
                         f"with tilt, median over {common.size} speeds ≥ 9 000 rpm: disk 1 {_fmt(np.median(ratio[:, 0]))}, "
                         f"disk 2 {_fmt(np.median(ratio[:, 1]))}, support {_fmt(np.median(ratio[:, 2]))} | "
                         f"{'yes' if np.median(ratio[:, 1:]) < 0.7 else 'no'} |")
    tmax = U[:, :, 0].max() * 1e3
    lines.append(f"| Fig. 17: relative tilt grows at high speed, with the harmonics | 1f relative tilt (max of θy, θz): "
                 f"{_fmt(U[lo][:, :, 0].max() * 1e3, 'mrad')} below 9 000 rpm, up to {_fmt(tmax, 'mrad')} above | "
                 f"{'yes' if tmax > 2 * U[lo][:, :, 0].max() * 1e3 else 'no'} (magnitude set by the assumed support tilt stiffness) |")
    lines += ["", "Files: `study-cascade.png/.svg` (Fig. 12), `study-cascade-tilt.png/.svg` (Fig. 17), "
              "`study-cascade-notilt.png/.svg` (Fig. 16), CSV tables of 1X–5X per speed beside them.", ""]
    return "\n".join(lines)
