"""Figures and tables of the rotor studies (Dai et al. 2025, Sections 5–6, and beyond).

Every function reads a finished sweep directory (:mod:`sweep.store`, written by
``ringcontact study …``), writes PNG + SVG (units on every axis) and a CSV of the plotted
numbers, and returns the files written. Nothing here computes dynamics.

Quantities: as in the paper, cascades show the amplitude of the **y velocity** (mm/s; the
misalignment's static offset would swamp a displacement spectrum); Figs. 18–19 show
**displacement** amplitudes (µm). "3# bearing" is the *support* of the 3# bearing (node s), as
in the paper ("the response at 3# bearing represents the motion of the support").
"""
from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np

from contact.files import atomic_write_bytes, atomic_write_text
from sweep import load_sweep

LOCATIONS = (("disk1.y", "disk 1"), ("disk2.y", "disk 2"), ("s.y", "3# bearing (support)"))


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams["svg.hashsalt"] = "ringcontact"
    return plt


def save(fig, prefix: Path) -> list[Path]:
    """Write ``prefix.png`` and ``prefix.svg`` atomically and close the figure."""
    plt = _plt()
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


def load_points(out, tasks=None) -> list:
    """Verified points of a sweep in task order (missing/corrupt ones left out)."""
    res = load_sweep(out, tasks)
    keys = [t.key for t in tasks] if tasks is not None else sorted(res, key=lambda k: res[k].params.get("speed_rpm", 0))
    return [res[k] for k in keys if k in res]


def _col(p, name: str) -> int:
    return list(p.arrays["channels"]).index(name)


def harmonic_table(points, quantity: str = "v", channels=("disk1.y", "disk2.y", "s.y"), orders=(1, 2, 3, 4, 5)):
    """``(speeds_rpm (P,), amps (P, len(channels), len(orders)))`` of |harmonic| amplitudes (SI)."""
    rpm = np.array([p.params["speed_rpm"] for p in points])
    A = np.zeros((len(points), len(channels), len(orders)))
    for i, p in enumerate(points):
        h = np.abs(p.arrays[f"harm_{quantity}"])
        for j, c in enumerate(channels):
            col = _col(p, c) if quantity != "u" else {"y": 0, "z": 1, "θy": 2, "θz": 3}[c]
            A[i, j] = h[[o - 1 for o in orders], col]
    return rpm, A


# ---------------------------------------------------------------------------
# Figure 12/16/17: spectrum cascades
# ---------------------------------------------------------------------------


def _cascade_axes(ax, points, get, unit_scale, label, floor_rel=1e-4):
    plt = _plt()
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


def cascade_figures(out, figs, *, tasks=None, prefix: str = "study-cascade", title: str = "") -> list[Path]:
    """Velocity-y spectrum cascades at disk 1, disk 2, 3# bearing (Fig. 12 / 16), the relative-tilt
    cascade (Fig. 17), and ``<prefix>.csv`` with 1X–5X per speed, convergence and regime."""
    plt = _plt()
    figs = Path(figs)
    points = load_points(out, tasks)
    files = []
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6), constrained_layout=True)
    for ax, (ch, lab) in zip(axes, LOCATIONS):
        _cascade_axes(ax, points, lambda p, ch=ch: p.arrays["spec_v"][:, _col(p, ch)], 1e3,
                      f"{lab}: y-velocity amplitude (mm/s)")
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
    files.append(write_csv(figs / f"{prefix}.csv", header, rows))
    return files


# ---------------------------------------------------------------------------
# Figures 13-15: one speed in detail
# ---------------------------------------------------------------------------


def point_figures(out, figs, *, tasks=None, prefix: str = "study-point") -> list[Path]:
    """Per speed: rotor deflection, orbits, time histories, spectra (Figs. 13–14) and r1/r2 vs δ0 (Fig. 15)."""
    from rotor.studies.steady_state import _scene_model

    plt = _plt()
    figs = Path(figs)
    files = []
    for p in load_points(out, tasks):
        rpm = p.params["speed_rpm"]
        _, model = _scene_model(p.params["scene"])
        a = p.arrays
        tag = f"{prefix}-{rpm:.0f}rpm"
        fig = plt.figure(figsize=(14, 9), constrained_layout=True)
        gs = fig.add_gridspec(3, 4)
        # (a) deflection: y of the stations (static misalignment offset and mean removed), 8 instants
        ax = fig.add_subplot(gs[0, 0])
        names = [n for n in model.node_names if f"{n}.y" in set(model.dof_names) and n != "s"]
        xs = np.array([model.node_x_m[list(model.node_names).index(n)] for n in names])
        iy = [list(a["dof_names"]).index(f"{n}.y") for n in names]
        order = np.argsort(xs, kind="stable")
        Q = a["q_all"][:, iy] - a["q_all"][:, iy].mean(axis=0)
        spr = p.info["samples_per_rev"]
        for k in range(0, spr, max(1, spr // 8)):
            ax.plot(xs[order] * 1e3, Q[k, order] * 1e6, "-o", ms=3, lw=1)
        ax.set_xlabel("axial position x (mm)")
        ax.set_ylabel("dynamic deflection y (µm)")
        ax.set_title("(a) rotor deflection over one revolution", fontsize=9)
        for j, (ch, lab) in enumerate(LOCATIONS):
            c = _col(p, ch)
            cz = _col(p, ch.replace(".y", ".z"))
            y = (a["q"][:, c] - a["q"][:, c].mean()) * 1e6
            z = (a["q"][:, cz] - a["q"][:, cz].mean()) * 1e6
            ax = fig.add_subplot(gs[0, j + 1])
            ax.plot(y, z, lw=0.8)
            ax.set_aspect("equal", "datalim")
            ax.set_xlabel("y (µm)")
            ax.set_ylabel("z (µm)")
            ax.set_title(f"orbit, {lab}", fontsize=9)
            ax = fig.add_subplot(gs[1, j + 1])
            ax.plot((a["t"] - a["t"][0]) * 1e3, y, lw=0.8)
            ax.set_xlabel("time (ms)")
            ax.set_ylabel("y − mean (µm)")
            ax.set_title(f"time history, {lab}", fontsize=9)
            ax = fig.add_subplot(gs[2, j + 1])
            f = rpm / 60 * a["spec_orders"]
            ax.semilogy(f, a["spec_v"][:, c] * 1e3, lw=0.8)
            for k in range(1, 6):
                ax.axvline(k * rpm / 60, color="0.8", lw=0.5, zorder=0)
            ax.set_ylim(max(a["spec_v"][:, c].max() * 1e3 * 1e-6, 1e-9), a["spec_v"][:, c].max() * 1e3 * 3)
            ax.set_xlabel("frequency (Hz)")
            ax.set_ylabel("y-velocity amplitude (mm/s)")
            ax.set_title(f"spectrum, {lab}", fontsize=9)
        # Fig. 15: r1, r2 against the clearance
        ax = fig.add_subplot(gs[1:, 0])
        d0 = p.info["clearance_m"]
        tt = (a["t"] - a["t"][0]) * 1e3
        ax.plot(tt, a["r1"] * 1e3, lw=0.9, label="r1 (right edge)")
        ax.plot(tt, a["r2"] * 1e3, lw=0.9, label="r2 (left edge)")
        ax.axhline(d0 * 1e3, color="k", ls="--", lw=0.8, label=f"clearance δ0 = {d0 * 1e3:g} mm")
        ax.set_xlabel("time (ms)")
        ax.set_ylabel("relative edge offset (mm)")
        ax.legend(fontsize=8)
        ax.set_title(f"r1, r2 vs δ0 ({p.info['label']}, contact {100 * p.info['contact_fraction']:.0f} % of time)",
                     fontsize=9)
        fig.suptitle(f"{p.params['scene']} at {rpm:.0f} rpm (converged: {p.info['converged']}, "
                     f"period {p.info['period_revs']} rev)", fontsize=10)
        files += save(fig, figs / tag)
    return files


# ---------------------------------------------------------------------------
# Figures 18-19: harmonic amplitudes vs speed for several parameter values
# ---------------------------------------------------------------------------


def _groups(points, key):
    g = {}
    for p in points:
        g.setdefault(p.params.get(key), []).append(p)
    return {k: sorted(v, key=lambda p: p.params["speed_rpm"]) for k, v in g.items()}


def amplitude_grid(groups: dict, label, title: str):
    plt = _plt()
    fig, axes = plt.subplots(3, 3, figsize=(13, 9.5), constrained_layout=True, sharex=True)
    for val, pts in sorted(groups.items(), key=lambda kv: kv[0]):
        rpm, A = harmonic_table(pts, "q", orders=(1, 2, 3))
        for i in range(3):
            for j, (_, lab) in enumerate(LOCATIONS):
                ax = axes[i, j]
                ax.semilogy(rpm, np.maximum(A[:, j, i] * 1e6, 1e-6), "-o", ms=2.5, lw=1, label=label(val))
                ax.set_title(f"{i + 1}f, {lab}", fontsize=9)
                ax.set_ylabel("displacement amplitude (µm)")
                if i == 2:
                    ax.set_xlabel("rotor speed (rpm)")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle(title, fontsize=10)
    return fig


def params_figures(out, figs, *, tasks=None, prefix: str = "study-params") -> list[Path]:
    """1X/2X/3X displacement amplitude vs speed for several clearances (Fig. 18) and misalignments (Fig. 19)."""
    figs = Path(figs)
    pts = load_points(out, tasks)
    files = []
    base = [p for p in pts if "clearance_m" not in p.params and "misalignment_m" not in p.params]

    def grouped(key):
        g = {}
        for p in [q for q in pts if key in q.params] + base:
            g.setdefault(p.info[key], []).append(p)
        return {k: sorted(v, key=lambda p: p.params["speed_rpm"]) for k, v in g.items()}

    byc = grouped("clearance_m") if any("clearance_m" in p.params for p in pts) else {}
    if byc:
        fig = amplitude_grid(byc, lambda v: f"δ0 = {v * 1e3:g} mm", "Harmonic amplitudes vs speed, several clearances (paper Fig. 18)")
        files += save(fig, figs / f"{prefix}-clearance")
    bym = grouped("misalignment_m") if any("misalignment_m" in p.params for p in pts) else {}
    if bym:
        fig = amplitude_grid(bym, lambda v: f"δ = {v * 1e3:g} mm", "Harmonic amplitudes vs speed, several misalignments (paper Fig. 19)")
        files += save(fig, figs / f"{prefix}-misalignment")
    rows = []
    for p in pts:
        rpm, A = harmonic_table([p], "q", orders=(1, 2, 3))
        rows.append([p.key, p.info["clearance_m"] * 1e3, p.info["misalignment_m"] * 1e3, rpm[0], p.info["label"], int(p.info["converged"])] + list((A[0] * 1e6).ravel()))
    files.append(write_csv(figs / f"{prefix}.csv", ["key", "clearance_mm", "misalignment_mm", "speed_rpm", "regime",
                                                    "converged"] + [f"{c}_{o}X_um" for c in ("disk1", "disk2", "support")
                                                                    for o in (1, 2, 3)], rows))
    return files


# ---------------------------------------------------------------------------
# Test rig (Figs. 27-28), regime map
# ---------------------------------------------------------------------------


def testrig_figures(out, figs, *, tasks=None, prefix: str = "study-testrig") -> list[Path]:
    """Spectra of disk 2 and the 3# bearing support at each speed step for the clearance pair and the
    misalignment pair (paper Figs. 27–28), plus the 1X–5X table."""
    plt = _plt()
    figs = Path(figs)
    pts = load_points(out, tasks)
    files = []
    rows = []
    for rpm in sorted({p.params["speed_rpm"] for p in pts}):
        fig, axes = plt.subplots(2, 2, figsize=(11, 7), constrained_layout=True)
        cases = {"clearance (δ = 1 mm)": [p for p in pts if p.params["speed_rpm"] == rpm and p.params["misalignment_m"] == 1e-3],
                 "misalignment (δ0 = 0.05 mm)": [p for p in pts if p.params["speed_rpm"] == rpm and p.params["clearance_m"] == 0.05e-3]}
        for i, (case, cps) in enumerate(cases.items()):
            for j, (ch, lab) in enumerate(LOCATIONS[1:]):
                ax = axes[i, j]
                for p in cps:
                    c = _col(p, ch)
                    lbl = (f"δ0 = {p.params['clearance_m'] * 1e3:g} mm" if i == 0 else f"δ = {p.params['misalignment_m'] * 1e3:g} mm")
                    ax.semilogy(p.arrays["spec_orders"] * rpm / 60, p.arrays["spec_v"][:, c] * 1e3, lw=0.9,
                                label=f"{lbl} ({p.info['label']})")
                ax.set_xlabel("frequency (Hz)")
                ax.set_ylabel("y-velocity amplitude (mm/s)")
                ax.set_title(f"{lab}, varying {case}", fontsize=9)
                ax.legend(fontsize=8)
        fig.suptitle(f"Test rig (Table 5 scene) at {rpm:.0f} rpm", fontsize=10)
        files += save(fig, figs / f"{prefix}-{rpm:.0f}rpm")
    for p in pts:
        _, A = harmonic_table([p], "v")
        rows.append([p.params["speed_rpm"], p.params["clearance_m"] * 1e3, p.params["misalignment_m"] * 1e3,
                     p.info["label"], p.info["contact_fraction"], int(p.info["converged"])] + list((A[0] * 1e3).ravel()))
    files.append(write_csv(figs / f"{prefix}.csv", ["speed_rpm", "clearance_mm", "misalignment_mm", "regime",
                                                    "contact_fraction", "converged"]
                           + [f"{c}_v{o}X_mm_s" for c in ("disk1", "disk2", "support") for o in range(1, 6)], rows))
    return files


REGIMES = ("stick", "slip", "impact", "contact")


def map_figures(out, figs, *, tasks=None, prefix: str = "study-map") -> list[Path]:
    """Where the support sticks, slips and impacts over (speed, clearance); contact fraction as number."""
    plt = _plt()
    from matplotlib.colors import ListedColormap

    figs = Path(figs)
    pts = load_points(out, tasks)
    rpms = sorted({p.params["speed_rpm"] for p in pts})
    cls = sorted({p.params["clearance_m"] for p in pts})
    grid = np.full((len(cls), len(rpms)), np.nan)
    frac = np.full_like(grid, np.nan)
    conv = np.ones_like(grid, dtype=bool)
    for p in pts:
        i, j = cls.index(p.params["clearance_m"]), rpms.index(p.params["speed_rpm"])
        grid[i, j] = REGIMES.index(p.info["label"])
        frac[i, j] = p.info["contact_fraction"]
        conv[i, j] = p.info["converged"]
    fig, ax = plt.subplots(figsize=(11, 4.2), constrained_layout=True)
    cmap = ListedColormap(["#4c72b0", "#dd8452", "#c44e52", "#8172b2"])
    ax.imshow(grid, origin="lower", aspect="auto", cmap=cmap, vmin=-0.5, vmax=3.5,
              extent=(-0.5, len(rpms) - 0.5, -0.5, len(cls) - 0.5))
    for i in range(len(cls)):
        for j in range(len(rpms)):
            if np.isfinite(frac[i, j]):
                ax.text(j, i, f"{100 * frac[i, j]:.0f}%" + ("" if conv[i, j] else "*"), ha="center", va="center",
                        fontsize=7, color="w")
    ax.set_xticks(range(len(rpms)), [f"{r:.0f}" for r in rpms], rotation=45, fontsize=8)
    ax.set_yticks(range(len(cls)), [f"{c * 1e3:g}" for c in cls])
    ax.set_xlabel("rotor speed (rpm)")
    ax.set_ylabel("radial clearance δ0 (mm)")
    from matplotlib.patches import Patch
    ax.legend(handles=[Patch(color=cmap(k), label=r) for k, r in enumerate(REGIMES)], loc="upper left",
              bbox_to_anchor=(1.0, 1.0), fontsize=8)
    ax.set_title("Loose-support regime (numbers: % of time in radial contact; * = no periodic steady state)",
                 fontsize=9)
    files = save(fig, figs / prefix)
    rows = [[p.params["speed_rpm"], p.params["clearance_m"] * 1e3, p.info["label"], p.info["contact_fraction"],
             p.info["stick_fraction"], p.info["max_r_over_clearance"], int(p.info["converged"]), p.info["period_revs"]]
            for p in pts]
    files.append(write_csv(figs / f"{prefix}.csv", ["speed_rpm", "clearance_mm", "regime", "contact_fraction",
                                                    "stick_fraction", "max_r_over_clearance", "converged",
                                                    "period_revs"], rows))
    return files


def runup_figures(out, figs, *, prefix: str = "study-runup") -> list[Path]:
    """Time–frequency cascade of a run-up (see :mod:`rotor.studies.runup`)."""
    from rotor.studies.runup import load_runup, stft_cascade

    plt = _plt()
    from matplotlib.colors import LogNorm

    figs = Path(figs)
    r = load_runup(out)
    files = []
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), constrained_layout=True)
    for ax, (ch, lab) in zip(axes, LOCATIONS):
        tc, fr, A, rpm_c = stft_cascade(r, ch)
        A = A * 1e3
        top = A.max()
        m = ax.pcolormesh(fr, rpm_c, A, norm=LogNorm(vmin=top * 1e-4, vmax=top), cmap="viridis", shading="auto",
                          rasterized=True)
        for k in range(1, 6):
            ax.plot(k * rpm_c / 60, rpm_c, ":", color="w", lw=0.6)
        ax.set_xlim(0, 5.5 * rpm_c.max() / 60)
        ax.set_xlabel("frequency (Hz)")
        ax.set_ylabel("rotor speed (rpm)")
        ax.set_title(f"{lab}: y-velocity (mm/s)", fontsize=9)
        plt.colorbar(m, ax=ax, pad=0.01)
    fig.suptitle(f"Run-up {r['rpm'][0]:.0f} → {r['rpm'][-1]:.0f} rpm in {r['t'][-1] - r['t'][0]:.1f} s: "
                 "time–frequency cascade (STFT)", fontsize=10)
    files += save(fig, figs / prefix)
    fig, axes = plt.subplots(2, 1, figsize=(11, 6), constrained_layout=True, sharex=True)
    for ch, lab in LOCATIONS:
        c = list(r["channels"]).index(ch)
        axes[0].plot(r["rpm"], r["q"][:, c] * 1e6 - np.median(r["q"][:, c]) * 1e6, lw=0.4, label=lab, rasterized=True)
    axes[0].set_ylabel("y − median (µm)")
    axes[0].legend(fontsize=8)
    axes[1].plot(r["rpm"], r["r1"] * 1e3, lw=0.4, label="r1", rasterized=True)
    axes[1].plot(r["rpm"], r["r2"] * 1e3, lw=0.4, label="r2", rasterized=True)
    axes[1].axhline(r["clearance_m"] * 1e3, color="k", ls="--", lw=0.8, label="δ0")
    axes[1].set_ylabel("relative edge offset (mm)")
    axes[1].set_xlabel("rotor speed (rpm)")
    axes[1].legend(fontsize=8)
    files += save(fig, figs / f"{prefix}-time")
    return files


# ---------------------------------------------------------------------------
# notes: what the paper reports and whether ours agrees (numbers from the data)
# ---------------------------------------------------------------------------


def _fmt(x, unit="", d=3):
    return f"{x:.{d}g}{(' ' + unit) if unit else ''}"


def _high(rpm, A, lo=9000.0):
    """Rows of speeds >= lo."""
    return rpm >= lo


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
                 f"disk 2 {_fmt(np.median(r2[:, 1]))}, support {_fmt(np.median(r2[:, 2]))} | yes (small) |")
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


def params_note(points) -> str:
    """Markdown: Figs. 18-19 trends over the high-speed range, from our numbers."""
    lines = ["# Harmonic amplitudes vs speed for several clearances and misalignments (paper Figs. 18–19)", "",
             "Displacement amplitudes (µm) of 1f, 2f, 3f at disk 1, disk 2 and the 3# bearing support, "
             "`ringcontact study params`. Trend checks below use the speeds ≥ 9 000 rpm (the paper's 'high speed').", ""]
    base = [p for p in points if "clearance_m" not in p.params and "misalignment_m" not in p.params]
    for key, name, unit in (("clearance_m", "clearance δ0", "mm"), ("misalignment_m", "misalignment δ", "mm")):
        groups = {}
        for p in [q for q in points if key in q.params] + base:
            groups.setdefault(p.info[key], []).append(p)
        if len(groups) < 2:
            continue
        vals = sorted(groups)
        lines += [f"## {name}", "", "| " + name + f" ({unit}) | median 1f disk 1 (µm) | median 2f disk 2 | median 3f disk 2 "
                  "| median 2f support | median 3f support | periodic points |", "|---|---|---|---|---|---|---|"]
        med = {}
        for v in vals:
            pts = sorted(groups[v], key=lambda p: p.params["speed_rpm"])
            rpm, A = harmonic_table(pts, "q", orders=(1, 2, 3))
            hi = rpm >= 9000
            m = np.median(A[hi], axis=0) * 1e6  # (loc, order)
            med[v] = m
            nconv = sum(p.info["converged"] for p, h in zip(pts, hi) if h)
            lines.append(f"| {v * 1e3:g} | {m[0, 0]:.3g} | {m[1, 1]:.3g} | {m[1, 2]:.3g} | {m[2, 1]:.3g} | {m[2, 2]:.3g} "
                         f"| {nconv}/{int(hi.sum())} |")
        lo_v, hi_v = vals[0], vals[-1]
        if key == "clearance_m":
            ok2 = med[lo_v][1:, 1].min() > med[hi_v][1:, 1].max()
            ok3 = med[lo_v][1:, 2].min() > med[hi_v][1:, 2].max()
            lines += ["", f"Paper: at high speed 2f and 3f decrease as the clearance increases. Ours (medians, "
                      f"smallest vs largest clearance, disk 2 and support): 2f {'decreases' if ok2 else 'does not decrease'}, "
                      f"3f {'decreases' if ok3 else 'does not decrease'} → {'agrees' if ok2 and ok3 else 'does not agree'}.", ""]
        else:
            one = np.array([med[v][:, 0] for v in vals])
            spread = (one.max(axis=0) / one.min(axis=0) - 1) * 100
            ok2 = all(med[vals[i]][1:, 1].max() < med[vals[i + 1]][1:, 1].min() for i in range(len(vals) - 1))
            ok3 = all(med[vals[i]][1:, 2].max() < med[vals[i + 1]][1:, 2].min() for i in range(len(vals) - 1))
            # speed by speed, on speeds where every δ gives a periodic steady state
            by_rpm = {}
            for v in vals:
                for p in groups[v]:
                    by_rpm.setdefault(p.params["speed_rpm"], {})[v] = p
            worst = 0.0
            for r_, d in by_rpm.items():
                if r_ > 0 and len(d) == len(vals) and all(p.info["converged"] for p in d.values()):
                    a1 = np.array([harmonic_table([d[v]], "q", orders=(1,))[1][0, :, 0] for v in vals])
                    worst = max(worst, float((a1.max(axis=0) / a1.min(axis=0) - 1).max() * 100))
            lines += ["", f"Speed by speed, where every δ has a periodic steady state: 1f varies by at most {worst:.1f} % "
                      "across δ (the median spread above includes the non-periodic high-speed points).", ""]
            lines += ["", f"Paper: as δ increases, f stays essentially unchanged while 2f and 3f increase. Ours: 1f "
                      f"median spread across δ {spread.max():.1f} % (largest location), 2f {'increases' if ok2 else 'does not increase monotonically'}, "
                      f"3f {'increases' if ok3 else 'does not increase monotonically'} → "
                      f"{'agrees' if ok2 and ok3 and spread.max() < 5 else 'partly' if ok2 else 'does not agree'}.", ""]
    return "\n".join(lines)


def point_note(points) -> str:
    lines = ["# Response at the paper's points A and B (Figs. 13–15)", "",
             "`ringcontact study point` (4 500 and 10 500 rpm): deflection over one revolution (static misalignment "
             "removed), orbits, time histories and y-velocity spectra at disk 1, disk 2 and the 3# bearing support, "
             "and the relative edge offsets r1, r2 against the clearance.", "",
             "| speed (rpm) | regime | contact (% time) | periodic (period) | 2f/1f disk 1 | 2f/1f support | "
             "(3f+4f+5f)/1f disk 1 | disk 2 | support | max r/δ0 |", "|---|---|---|---|---|---|---|---|---|---|"]
    for p in points:
        _, V = harmonic_table([p], "v")
        v = V[0]
        lines.append(f"| {p.params['speed_rpm']:.0f} | {p.info['label']} | {100 * p.info['contact_fraction']:.0f} | "
                     f"{p.info['converged']} ({p.info['period_revs']}) | {v[0, 1] / v[0, 0]:.2e} | {v[2, 1] / v[2, 0]:.2e} | "
                     f"{v[0, 2:].sum() / v[0, 0]:.2e} | {v[1, 2:].sum() / v[1, 0]:.2e} | {v[2, 2:].sum() / v[2, 0]:.2e} | "
                     f"{p.info['max_r_over_clearance']:.3f} |")
    lines += ["", "Paper, point A (Fig. 13): near-circular orbits, spectra dominated by f with 2f from misalignment, "
              "the support moving with the rotor (no relative motion), 2f relatively higher at the 3# bearing. "
              "Paper, point B (Figs. 14–15): non-circular orbits, 3f–5f besides f and 2f, more pronounced near the "
              "loose support; r1, r2 fluctuate periodically about δ0 (periodic contact and separation).", "",
              "Ours: see the table — at 4 500 rpm the support sticks to the bearing (no contact, stick 100 %), 2f/1f is "
              "larger at the support than at disk 1; at 10 500 rpm the bearing collides with the support part of "
              "every revolution (periodic, period one revolution), and the 3f–5f content relative to 1f is larger at "
              "disk 2 and the support than at disk 1, and r1 crosses δ0 once per revolution while r2 stays just "
              "inside it (Fig. 15 shape). These agree qualitatively. They differ in degree: our harmonics are small "
              "(3f–5f are about 10⁻³ of 1f at point B), so our orbits at point B are still nearly circular where the "
              "paper shows visibly non-circular ones; the paper's spectra are not quantified in its text.", ""]
    return "\n".join(lines)


def testrig_note(points) -> str:
    lines = ["# Test rig (Table 5 scene) at the paper's speed steps (Figs. 27–28 trends)", "",
             "`ringcontact study testrig`: steady state at 3 600 and 5 500 rpm, clearance 0.01/0.05 mm (δ = 1 mm) "
             "and misalignment 1/3 mm (δ0 = 0.05 mm). The rig's shaft geometry is assumed (scene comments).", "",
             "| speed (rpm) | δ0 (mm) | δ (mm) | regime | contact % | sum 2f–5f disk 2 (mm/s) | sum 2f–5f support (mm/s) |",
             "|---|---|---|---|---|---|---|"]
    res = {}
    for p in sorted(points, key=lambda p: (p.params["speed_rpm"], p.params["clearance_m"], p.params["misalignment_m"])):
        _, V = harmonic_table([p], "v")
        s2, ss = V[0, 1, 1:].sum() * 1e3, V[0, 2, 1:].sum() * 1e3
        res[(p.params["speed_rpm"], p.params["clearance_m"], p.params["misalignment_m"])] = (s2, ss)
        lines.append(f"| {p.params['speed_rpm']:.0f} | {p.params['clearance_m'] * 1e3:g} | {p.params['misalignment_m'] * 1e3:g} "
                     f"| {p.info['label']} | {100 * p.info['contact_fraction']:.0f} | {s2:.4g} | {ss:.4g} |")
    lines.append("")
    for rpm in sorted({k[0] for k in res}):
        a, b = res.get((rpm, 0.01e-3, 1e-3)), res.get((rpm, 0.05e-3, 1e-3))
        c = res.get((rpm, 0.05e-3, 3e-3))
        if a and b:
            lines.append(f"- {rpm:.0f} rpm, Fig. 27 (harmonics rise as the clearance decreases): 0.01 vs 0.05 mm gives "
                         f"{a[0]:.3g} vs {b[0]:.3g} mm/s at disk 2, {a[1]:.3g} vs {b[1]:.3g} at the support → "
                         f"{'agrees' if a[0] > b[0] and a[1] > b[1] else 'does not agree'}.")
        if b and c:
            lines.append(f"- {rpm:.0f} rpm, Fig. 28 (harmonics rise with the misalignment): 3 vs 1 mm gives "
                         f"{c[0]:.3g} vs {b[0]:.3g} mm/s at disk 2, {c[1]:.3g} vs {b[1]:.3g} at the support → "
                         f"{'agrees' if c[0] > b[0] and c[1] > b[1] else 'does not agree'}.")
    lines.append("")
    return "\n".join(lines)


def map_note(points) -> str:
    lines = ["# Where the support sticks, slips and impacts (beyond the paper)", "",
             "`ringcontact study map`: steady state over a (speed, clearance) grid; regime from the recorded "
             "revolutions: *stick* (both end faces stuck, no radial contact), *slip* (faces slide, no contact), "
             "*impact* (radial contact part of the time), *contact* (contact all the time). "
             "`study-map.csv` has the fractions.", ""]
    from collections import Counter
    c = Counter(p.info["label"] for p in points)
    lines.append("Counts: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())) + f" of {len(points)} points; "
                 f"{sum(not p.info['converged'] for p in points)} without a periodic steady state.")
    lines.append("")
    return "\n".join(lines)


def publish(runs: dict, published) -> list[Path]:
    """Figures + notes of finished study directories into ``published`` as ``study-*`` files.

    ``runs``: ``{"cascade": dir, "notilt": dir, "params": dir, "point": dir, "testrig": dir, "map": dir,
    "runup": dir}`` (any subset).
    """
    import json

    published = Path(published)
    files = []
    if "cascade" in runs:
        files += cascade_figures(runs["cascade"], published, prefix="study-cascade")
        notilt = None
        if "notilt" in runs:
            files += cascade_figures(runs["notilt"], published, prefix="study-cascade-notilt",
                                     title="Spectrum cascades with the tilt ignored (paper Fig. 16)")
            notilt = load_points(runs["notilt"])
        tp = Path(runs["cascade"]) / "timing.json"
        timing = json.loads(tp.read_text()) if tp.exists() else None
        files.append(atomic_write_text(published / "study-cascade.md",
                                       cascade_note(load_points(runs["cascade"]), notilt, timing)))
    if "params" in runs:
        files += params_figures(runs["params"], published)
        files.append(atomic_write_text(published / "study-params.md", params_note(load_points(runs["params"]))))
    if "point" in runs:
        files += point_figures(runs["point"], published)
        files.append(atomic_write_text(published / "study-point.md", point_note(load_points(runs["point"]))))
    if "testrig" in runs:
        files += testrig_figures(runs["testrig"], published)
        files.append(atomic_write_text(published / "study-testrig.md", testrig_note(load_points(runs["testrig"]))))
    if "map" in runs:
        files += map_figures(runs["map"], published)
        files.append(atomic_write_text(published / "study-map.md", map_note(load_points(runs["map"]))))
    if "runup" in runs:
        files += runup_figures(runs["runup"], published)
        files.append(atomic_write_text(published / "study-runup.md", runup_note(runs["runup"])))
    return files


def runup_note(out) -> str:
    """Markdown: what the run-up shows (first contact speed, 1X peaks), from the stored run."""
    from rotor.studies.runup import load_runup, stft_cascade

    r = load_runup(out)
    info = r["info"]
    d0 = r["clearance_m"]
    contact = (r["r1"] > d0) | (r["r2"] > d0)
    first = r["rpm"][np.argmax(contact)] if contact.any() else None
    lines = ["# Run-up through the critical speeds (beyond the paper)", "",
             f"`ringcontact study runup`: linear ramp {r['rpm'][0]:.0f} → {r['rpm'][-1]:.0f} rpm in "
             f"{r['t'][-1] - r['t'][0]:.1f} s ({info['accel_rpm_per_s']:.0f} rpm/s), Table 4 rotor, integrated in "
             f"{info['segments']} constant-speed segments with the rotation angle carried across (`rotor.studies.runup`); "
             f"{info['steps']} steps of {info['dt_s'] * 1e6:.1f} µs in {info['wall_s']:.0f} s wall. Cascade: Hann-window "
             "STFT of the y velocity, amplitude-corrected.", ""]
    for ch, lab in LOCATIONS:
        tc, fr, A, rpm_c = stft_cascade(r, ch)
        one = np.array([A[i, np.argmin(np.abs(fr - rpm_c[i] / 60))] for i in range(len(tc))])
        k = np.argmax(one)
        lines.append(f"- {lab}: largest 1X {one[k] * 1e3:.3g} mm/s at {rpm_c[k]:.0f} rpm.")
    lines += ["", f"- First radial contact during the ramp: {first:.0f} rpm." if first is not None else
              "- No radial contact during the ramp.",
              f"- Contact during {100 * contact.mean():.1f} % of the run; end faces stuck "
              f"{100 * np.mean((r['modes'][:, 0] == 1) & (r['modes'][:, 1] == 1)):.1f} % of the time.", "",
              "Linear forward 1X critical speeds of this rotor (support locked, `rotor-table4.md`): 2 441, 4 271 and "
              "9 608 rpm. Compare with the steady-state cascade (`study-cascade.md`): in the ramp the harmonics and "
              "the broadband band appear at speeds close to, but not identical with, the steady-state ones, since "
              "a ramp passes through regimes with coexisting states in the order it meets them.", ""]
    return "\n".join(lines)
