"""The Table 5 test rig at the paper's speed steps (Figs. 27–28 trends): spectra, table and note."""
from __future__ import annotations

from pathlib import Path

from reports.studies.common import LOCATIONS, channel_column, harmonic_table, load_points, pyplot, save, write_csv


def testrig_figures(out, figs, *, tasks=None, prefix: str = "study-testrig") -> list[Path]:
    """Spectra of disk 2 and the 3# bearing support at each speed step for the clearance pair and the
    misalignment pair (paper Figs. 27–28), plus the 1X–5X table."""
    plt = pyplot()
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
                    c = channel_column(p, ch)
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


def testrig_note(points) -> str:
    lines = ["# Test rig (Table 5 scene) at the paper's speed steps (Figs. 27–28 trends)", "",
             "`ringcontact study testrig`: steady state at 3 600 and 5 500 rpm, clearance 0.01/0.05 mm (δ = 1 mm) "
             "and misalignment 1/3 mm (δ0 = 0.05 mm). The rig's shaft geometry is assumed (scene comments).", "",
             "| speed (rpm) | δ0 (mm) | δ (mm) | regime | contact % | sum 2X–5X disk 2 (mm/s) | sum 2X–5X support (mm/s) |",
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
