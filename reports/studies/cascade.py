"""Spectrum cascades over speed (Dai et al. 2025 Figs. 12, 16, 17): figures, CSV and the note."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import (LOCATIONS, channel_column, harmonic_table, integrator_text, load_points, pyplot,
                                    read_csv_rows, require_columns, save, write_csv)


#: order resolution of the cascade maps (a 32-revolution record resolves 1/32 of the rotation frequency)
ORDER_STEP = 1.0 / 32.0
#: highest order drawn, and the dynamic range of the shared colour scale (decades below the largest amplitude)
MAX_ORDER = 5.5
DECADES = 4


def shared_norm(groups, decades: int = DECADES):
    """One logarithmic colour scale for every panel compared (``groups``: lists of spectra as :func:`_cascade_axes`
    takes them): from the largest amplitude of them all down ``decades`` decades."""
    from matplotlib.colors import LogNorm

    top = max((float(np.max(a)) for spectra in groups for _, _, a, _ in spectra if len(a)), default=1.0)
    top = top if top > 0 else 1.0
    return LogNorm(vmin=top * 10.0 ** -decades, vmax=top)


def _order_rows(spectra):
    """Speeds (P,) and amplitudes (P, M) binned on the order grid 0 … :data:`MAX_ORDER` (largest per cell)."""
    n = int(round(MAX_ORDER / ORDER_STEP))
    grid = np.zeros((len(spectra), n))
    for i, (_, o, a, _) in enumerate(spectra):
        o, a = np.asarray(o, float), np.asarray(a, float)
        keep = (o > 0.5 * ORDER_STEP) & (o < MAX_ORDER)
        np.maximum.at(grid[i], np.clip(np.round(o[keep] / ORDER_STEP).astype(int), 0, n - 1), a[keep])
    return np.array([s[0] for s in spectra], float), grid


def _cascade_axes(ax, spectra, label, norm=None):
    """One cascade as a spectrogram map: rotor speed (rows) against frequency in orders of the rotation
    frequency (columns), colour the amplitude on the shared logarithmic scale ``norm`` (:func:`shared_norm`).

    ``spectra``: ``[(speed_rpm, orders (K,), amplitudes (K,), periodic)]`` in the unit of ``label``; the full
    spectrum of a study (fractional orders too: broadband content at a non-periodic speed shows as a
    smeared row) or the harmonics alone (from a CSV). Speeds without a periodic steady state are marked
    ◀ on the right edge. Returns the image (for a colour bar) or None.
    """
    spectra = sorted((s for s in spectra if s[0] > 0), key=lambda s: s[0])
    if not spectra:
        return None
    rpm, grid = _order_rows(spectra)
    norm = norm or shared_norm([spectra])
    mid = 0.5 * (rpm[1:] + rpm[:-1]) if len(rpm) > 1 else np.array([])
    step = float(np.median(np.diff(rpm))) if len(rpm) > 1 else max(rpm[0] * 0.05, 1.0)
    yedges = np.concatenate([[rpm[0] - step / 2], mid, [rpm[-1] + step / 2]])
    xedges = (np.arange(grid.shape[1] + 1) - 0.5) * ORDER_STEP
    shown = np.ma.masked_less_equal(grid, norm.vmin)
    import matplotlib
    cmap = matplotlib.colormaps["magma_r"].with_extremes(bad="white")
    im = ax.pcolormesh(xedges, yedges, shown, norm=norm, cmap=cmap, shading="flat", rasterized=True)
    for k in range(1, 6):
        ax.axvline(k, color="0.75", lw=0.4, zorder=0)
    ax.set_xlim(0, MAX_ORDER)
    ax.set_ylim(yedges[0], yedges[-1])
    ax.set_xticks(range(0, 6), [f"{k}X" if k else "0" for k in range(0, 6)])
    irregular = [s[0] for s in spectra if not s[3]]
    if irregular:
        ax.plot(np.full(len(irregular), MAX_ORDER), irregular, "<", color="tab:blue", ms=4, clip_on=False,
                label="no periodic steady state (full spectrum drawn)")
        ax.legend(fontsize=7, loc="lower right", framealpha=0.85)
    ax.set_xlabel("frequency / rotation frequency (order)")
    ax.set_ylabel("rotor speed (rpm)")
    ax.set_title(label, fontsize=9)
    return im


#: how ``--method shooting`` marks a speed whose orbit is not a stable periodic one (rotor.studies.shooting_point)
STABILITY_MARKS = {"quasi_periodic": ("D", "tab:orange", "unstable: complex pair out (quasi-periodic)"),
                   "period_doubling": ("s", "tab:purple", "unstable: multiplier < −1 (period doubling)"),
                   "unstable_fold": ("x", "tab:red", "unstable: real multiplier > 1"),
                   "non_periodic": ("o", "0.3", "no orbit; transient not periodic"),
                   "no_orbit_found": ("o", "0.6", "no orbit found")}


def mark_stability(ax, marks) -> None:
    """Markers at the right edge of a cascade at the speeds classified unstable, quasi-periodic or
    non-periodic. ``marks``: ``(speed_rpm, classification)`` pairs of ``study cascade --method shooting``
    (empty for transient points: nothing drawn)."""
    if not marks:
        return
    x = ax.get_xlim()[1]
    for cls, (mark, colour, label) in STABILITY_MARKS.items():
        rpm = [r for r, c in marks if c == cls]
        if rpm:
            ax.plot([0.97 * x] * len(rpm), rpm, mark, color=colour, ms=5, mfc="none", mew=1.2, label=label)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=6, loc="upper left", framealpha=0.8)


def cascade_plots(velocity: dict, tilt: dict, figs: Path, prefix: str, title: str, source: str = "",
                  marks=(), scale_with=()) -> list[Path]:
    """``<prefix>`` (y velocity at disk 1, disk 2, the support: Figs. 12/16) and ``<prefix>-tilt`` (Fig. 17).

    ``velocity``: ``{location label: spectra}`` in mm/s; ``tilt``: ``{"θy": spectra, "θz": spectra}`` in mrad;
    spectra as :func:`_cascade_axes` takes them. ``source`` is a note under the titles (what was drawn);
    ``marks``: ``(speed_rpm, classification)`` of the speeds :func:`mark_stability` marks; ``scale_with``:
    ``(velocity, tilt)`` dicts of a cascade drawn beside this one (Fig. 16 beside Fig. 12) whose spectra share
    the colour scale.
    """
    plt = pyplot()
    sub = f"\n{source}" if source else ""
    fig, axes = plt.subplots(1, 3, figsize=(15, 5.2), constrained_layout=True, sharey=True)
    norm = shared_norm(list(velocity.values()) + [v for vt in scale_with for v in vt[0].values()])
    im = None
    for ax, (lab, spectra) in zip(axes, velocity.items()):
        im = _cascade_axes(ax, spectra, f"{lab}: y velocity", norm) or im
        mark_stability(ax, marks)
    if im is not None:
        fig.colorbar(im, ax=list(axes), pad=0.01, label="y-velocity amplitude (mm/s), one scale for the three panels")
    fig.suptitle((title or "Steady-state spectrum cascades (y velocity), Table 4 rotor") + sub, fontsize=10)
    files = save(fig, Path(figs) / prefix)
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 5.2), constrained_layout=True, sharey=True)
    norm = shared_norm(list(tilt.values()) + [v for vt in scale_with for v in vt[1].values()])
    im = None
    for ax, (axis, spectra) in zip(axes, tilt.items()):
        im = _cascade_axes(ax, spectra, f"bearing − support: relative tilt {axis}", norm) or im
    if im is not None:
        fig.colorbar(im, ax=list(axes), pad=0.01, label="relative tilt amplitude (mrad), one scale for both panels")
    fig.suptitle("Relative angular deflection between bearing and support (paper Fig. 17)" + sub, fontsize=10)
    return files + save(fig, Path(figs) / f"{prefix}-tilt")


CSV_SOURCE = "harmonics 1X–5X (tilt 1X–3X) from {name}; broadband content between them is not in the CSV"


def cascade_redraw(csv_path, figs, prefix: str, title: str = ""):
    """The cascades of :func:`cascade_plots` from a committed ``study-cascade*.csv`` (harmonic orders only).

    The CSV is read and checked now (DatasetError if unreadable or lacking a column); the returned
    function draws and returns the files written.
    """
    rows = read_csv_rows(csv_path)
    vel = [f"{c}_v{o}X_mm_s" for c in ("disk1", "disk2", "support") for o in range(1, 6)]
    tilt = [f"tilt_{a}_{o}X_mrad" for a in ("y", "z") for o in range(1, 4)]
    require_columns(csv_path, rows, ["speed_rpm", "converged"] + vel + tilt)
    try:
        numbers = [[float(r[c]) for c in ["speed_rpm"] + vel + tilt] for r in rows]
    except ValueError as exc:
        from contact.errors import DatasetError
        raise DatasetError(f"{csv_path}: a cell is not a number ({exc})") from None

    def spectra(cols):
        orders = np.arange(1, len(cols) + 1, dtype=float)
        at = [1 + (vel + tilt).index(c) for c in cols]
        return [(n[0], orders, np.array([n[i] for i in at]), r["converged"] == "1") for n, r in zip(numbers, rows)]
    marks = [(float(r["speed_rpm"]), r["classification"]) for r in rows if r.get("classification")]
    velocity = {lab: spectra(vel[5 * j:5 * j + 5]) for j, (_, lab) in enumerate(LOCATIONS)}
    tilts = {"θy": spectra(tilt[:3]), "θz": spectra(tilt[3:])}
    return lambda: cascade_plots(velocity, tilts, figs, prefix, title, CSV_SOURCE.format(name=Path(csv_path).name),
                                 marks)


#: the titles of the cascades of tilt on and off (``{mesh}``: "" or ", N elements per segment"), shared by
#: ``study publish`` and ``study redraw`` so that both draw the same figure
CASCADE_TITLE = "Steady-state spectrum cascades (y velocity), Table 4 rotor{mesh} (paper Fig. 12)"
NOTILT_TITLE = "Spectrum cascades with the tilt ignored{mesh} (paper Fig. 16; colour scale shared with Fig. 12)"


def _point_spectra(points):
    """``(velocity, tilt)`` spectra of a study's points as the maps draw them: binned and rounded as the
    spectrum CSV holds them (:mod:`reports.studies.spectrum_csv`)."""
    from reports.studies.spectrum_csv import spectra_from_rows, spectrum_rows
    return spectra_from_rows(spectrum_rows(points, ORDER_STEP, MAX_ORDER, DECADES))


def spectrum_redraw(csv_path, figs, prefix: str, title: str, scale_csv=None):
    """The cascades of :func:`cascade_plots` from a committed ``<prefix>-spectrum.csv`` (the full spectra, as
    ``study publish`` drew them; ``scale_csv``: the compared cascade's, for the shared colour scale). The CSVs
    are read and checked now; the returned function draws and returns the files written."""
    from reports.studies.spectrum_csv import read_spectrum_csv
    velocity, tilts = read_spectrum_csv(csv_path)
    other = [read_spectrum_csv(scale_csv)] if scale_csv is not None else ()
    return lambda: cascade_plots(velocity, tilts, figs, prefix, title, scale_with=other)


def cascade_figures(out, figs, *, tasks=None, prefix: str = "study-cascade", title: str = "",
                    scale_with=None) -> list[Path]:
    """Velocity-y spectrum cascades at disk 1, disk 2, 3# bearing (Fig. 12 / 16), the relative-tilt
    cascade (Fig. 17) from the full spectra of the study (also written, binned, to ``<prefix>-spectrum.csv``,
    from which ``study redraw`` draws them again), and ``<prefix>.csv`` with 1X–5X per speed,
    convergence and regime, and (points that record it) the loose support's peak and mean contact force (N),
    peak contact moment (N m), contact share and each face's stick share (:data:`CONTACT_COLUMNS`).
    ``scale_with``: the points of a cascade compared with this one (the other of tilt on / off), whose
    spectra share the colour scale."""
    from reports.studies.spectrum_csv import write_spectrum_csv

    figs = Path(figs)
    points = load_points(out, tasks)
    velocity, tilts = _point_spectra(points)
    spectrum = write_spectrum_csv(points, figs / f"{prefix}-spectrum.csv", ORDER_STEP, MAX_ORDER, DECADES)
    marks = [(p.params["speed_rpm"], p.info["classification"]) for p in points if "classification" in p.info]
    files = cascade_plots(velocity, tilts, figs, prefix, title, marks=marks,
                          scale_with=[_point_spectra(scale_with)] if scale_with else ())
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
    if any("peak_contact_force_N" in p.info for p in points):   # the support's contact force and face stick
        header += list(CONTACT_COLUMNS)
        for r, p in zip(rows, points):
            r += [_number(p.info.get(k)) for k in CONTACT_COLUMNS]
    if any("law_validity_max_penetration_m" in p.info for p in points):   # a calibrated law: its fitted range
        header += ["max_edge_penetration_mm", "law_validity_max_penetration_mm", "beyond_law_validity"]
        for r, p in zip(rows, points):
            r += [p.info.get("max_edge_penetration_m", float("nan")) * 1e3,
                  p.info.get("law_validity_max_penetration_m", float("nan")) * 1e3,
                  int(p.info.get("beyond_law_validity", False))]
    files.append(write_csv(figs / f"{prefix}.csv", header, rows))
    return files + [spectrum]


#: the point info's contact fields (rotor.dynamics.support_record.contact_summary) the cascade CSV carries
CONTACT_COLUMNS = ("peak_contact_force_N", "mean_contact_force_N", "peak_contact_moment_Nm", "contact_share",
                   "stick_share_right_face", "stick_share_left_face")


def _number(x):
    """A CSV cell of an info field: empty where the point has none (no contact: no mean contact force; one face:
    no left face; or stored before the field), never NaN (the study tables hold finite numbers only)."""
    return "" if x is None else float(x)


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
             "law as published, scene `paper-table4` with its documented assumptions (its reading of Eq. 34: "
             "section5-readings.md).", "", integrator_text([p.info for p in points] + [p.info for p in notilt or []]), ""]
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
    lines.append(f"| Response primarily at 1X | 1X is {100 * np.median(share1[rpm > 0]):.1f} % (median over speeds and "
                 f"locations) of the 1X–5X sum; lowest {100 * share1[rpm > 0].min():.1f} % | yes |")
    lo = (rpm > 0) & (rpm < 9000)
    r2 = V[lo][:, :, 1] / V[lo][:, :, 0]
    lines.append(f"| 2X present (misalignment) | 2X/1X below 9 000 rpm: disk 1 median {_fmt(np.median(r2[:, 0]))}, "
                 f"disk 2 {_fmt(np.median(r2[:, 1]))}, support {_fmt(np.median(r2[:, 2]))} | "
                 f"{'yes' if np.median(r2[:, 2]) >= 0.05 else 'yes (small)'} |")
    if hi.any():
        r = hi3 / np.maximum(hi3[:, [0]], 1e-30)
        lines.append(f"| At high speed 3X–5X significant at disk 2 and the 3# bearing, more than at disk 1 | "
                     f"sum 3X–5X ≥ 9 000 rpm, ratio to disk 1: disk 2 median {_fmt(np.median(r[:, 1]))}, support "
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
            lines.append(f"| Fig. 16: harmonics markedly reduced when tilt is ignored | sum 3X–5X tilt-ignored / "
                         f"with tilt, median over {common.size} speeds ≥ 9 000 rpm: disk 1 {_fmt(np.median(ratio[:, 0]))}, "
                         f"disk 2 {_fmt(np.median(ratio[:, 1]))}, support {_fmt(np.median(ratio[:, 2]))} | "
                         f"{'yes' if np.median(ratio[:, 1:]) < 0.7 else 'no'} (a median over regimes; per speed band "
                         "and periodic speeds: study-findings.md) |")
    tmax = U[:, :, 0].max() * 1e3
    lines.append(f"| Fig. 17: relative tilt grows at high speed, with the harmonics | 1X relative tilt (max of θy, θz): "
                 f"{_fmt(U[lo][:, :, 0].max() * 1e3, 'mrad')} below 9 000 rpm, up to {_fmt(tmax, 'mrad')} above | "
                 f"{'yes' if tmax > 2 * U[lo][:, :, 0].max() * 1e3 else 'no'} (magnitude set by the assumed support tilt stiffness) |")
    lines += ["", "Files: `study-cascade.png/.svg` (Fig. 12), `study-cascade-tilt.png/.svg` (Fig. 17), "
              "`study-cascade-notilt.png/.svg` (Fig. 16): spectrogram maps (speed against order, the full spectrum "
              "on one logarithmic colour scale for tilt on and off); CSV tables of 1X–5X per speed beside them, and "
              "the binned spectra the maps draw (`*-spectrum.csv`). The converged mesh's: `study-cascade-e2*`.", ""]
    return "\n".join(lines)
