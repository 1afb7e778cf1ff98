"""One speed in detail (Figs. 13–15): deflection, orbits, time histories, spectra, r1/r2; figures and note."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import LOCATIONS, channel_column, harmonic_table, integrator_text, load_points, pyplot, save


def point_figures(out, figs, *, tasks=None, prefix: str = "study-point") -> list[Path]:
    """Per speed: rotor deflection, orbits, time histories, spectra (Figs. 13–14) and r1/r2 vs δ0 (Fig. 15)."""
    from rotor.studies.steady_state import _scene_model

    plt = pyplot()
    figs = Path(figs)
    files = []
    for p in load_points(out, tasks):
        rpm = p.params["speed_rpm"]
        _, model = _scene_model(p.params["scene"], p.params.get("elements_per_segment"))
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
        step = max(1, spr // 8)
        for k in range(0, spr, step):
            ax.plot(xs[order] * 1e3, Q[k, order] * 1e6, "-o", ms=3, lw=1, label=f"{k // step}/8 rev")
        ax.legend(fontsize=6, ncol=2, title="instant", title_fontsize=6)
        ax.set_xlabel("axial position x (mm)")
        ax.set_ylabel("dynamic deflection y (µm)")
        ax.set_title("(a) rotor deflection over one revolution", fontsize=9)
        for j, (ch, lab) in enumerate(LOCATIONS):
            c = channel_column(p, ch)
            cz = channel_column(p, ch.replace(".y", ".z"))
            y = (a["q"][:, c] - a["q"][:, c].mean()) * 1e6
            z = (a["q"][:, cz] - a["q"][:, cz].mean()) * 1e6
            ax = fig.add_subplot(gs[0, j + 1])
            ax.plot(y, z, lw=0.8, label="y–z, mean removed")
            ax.legend(fontsize=7, loc="upper right")
            ax.set_aspect("equal", "datalim")
            ax.set_xlabel("y (µm)")
            ax.set_ylabel("z (µm)")
            ax.set_title(f"orbit, {lab}", fontsize=9)
            ax = fig.add_subplot(gs[1, j + 1])
            ax.plot((a["t"] - a["t"][0]) * 1e3, y, lw=0.8, label="y − mean")
            ax.legend(fontsize=7, loc="upper right")
            ax.set_xlabel("time (ms)")
            ax.set_ylabel("y − mean (µm)")
            ax.set_title(f"time history, {lab}", fontsize=9)
            ax = fig.add_subplot(gs[2, j + 1])
            f = rpm / 60 * a["spec_orders"]
            ax.semilogy(f, a["spec_v"][:, c] * 1e3, lw=0.8, label="y velocity")
            for k in range(1, 6):
                ax.axvline(k * rpm / 60, color="0.8", lw=0.5, zorder=0, label="1X–5X" if k == 1 else None)
            ax.legend(fontsize=7, loc="upper right")
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


def point_note(points) -> str:
    lines = ["# Response at the paper's points A and B (Figs. 13–15)", "",
             "`ringcontact study point` (4 500 and 10 500 rpm): deflection over one revolution (static misalignment "
             "removed), orbits, time histories and y-velocity spectra at disk 1, disk 2 and the 3# bearing support, "
             "and the relative edge offsets r1, r2 against the clearance.", "", integrator_text([p.info for p in points]), "",
             "| speed (rpm) | regime | contact (% time) | periodic (period) | 2X/1X disk 1 | 2X/1X support | "
             "(3X+4X+5X)/1X disk 1 | disk 2 | support | max r/δ0 |", "|---|---|---|---|---|---|---|---|---|---|"]
    for p in points:
        _, V = harmonic_table([p], "v")
        v = V[0]
        lines.append(f"| {p.params['speed_rpm']:.0f} | {p.info['label']} | {100 * p.info['contact_fraction']:.0f} | "
                     f"{p.info['converged']} ({p.info['period_revs']}) | {v[0, 1] / v[0, 0]:.2e} | {v[2, 1] / v[2, 0]:.2e} | "
                     f"{v[0, 2:].sum() / v[0, 0]:.2e} | {v[1, 2:].sum() / v[1, 0]:.2e} | {v[2, 2:].sum() / v[2, 0]:.2e} | "
                     f"{p.info['max_r_over_clearance']:.3f} |")
    lines += ["", "Paper, point A (Fig. 13): near-circular orbits, spectra dominated by 1X with 2X from misalignment, "
              "the support moving with the rotor (no relative motion), 2X relatively higher at the 3# bearing. "
              "Paper, point B (Figs. 14–15): non-circular orbits, 3X–5X besides 1X and 2X, more pronounced near the "
              "loose support; r1, r2 fluctuate periodically about δ0 (periodic contact and separation).", "",
              _ours(points), ""]
    return "\n".join(lines)


def _ours(points) -> str:
    """Our reading of the table, from the numbers (not a fixed text: it follows the model)."""
    out = []
    for p in points:
        _, V = harmonic_table([p], "v")
        v = V[0]
        r2 = v[:, 1] / v[:, 0]
        r35 = v[:, 2:].sum(axis=1) / v[:, 0]
        moves = "moves with the rotor (end faces stuck)" if p.info["stick_fraction"] == 1.0 else \
            f"slips on its end faces {100 * (1 - p.info['stick_fraction']):.0f} % of the time"
        out.append(f"at {p.params['speed_rpm']:.0f} rpm the support {moves}, the ring touches the bore "
                   f"{100 * p.info['contact_fraction']:.0f} % of the time (max r/δ0 {p.info['max_r_over_clearance']:.3f}); "
                   f"2X/1X is {r2[2] / max(r2[0], 1e-30):.1f}× larger at the support than at disk 1, and (3X+4X+5X)/1X "
                   f"{r35[2] / max(r35[0], 1e-30):.1f}× larger")
    return "Ours: " + "; ".join(out) + "."

