"""The Table 5 test rig (Section 6): spectra at the paper's speed steps, the statements of Figs. 25–28 judged, and
whether the rig's loose support can slip at all within the paper's stated rig data (the stick-margin scan)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import LOCATIONS, channel_column, harmonic_table, load_points, pyplot, save, write_csv

#: the stick-margin scan's table in a ``study testrig`` directory (rotor/studies/testrig_scan.py), and its summary
SCAN_CSV = "stick-scan.csv"
SCAN_HEAD = ["variant", "placement", "sleeve", "misalignment_mm", "speed_rpm", "peak_face_force_N",
             "static_face_force_N", "limit_N"]


def _key(p) -> tuple:
    return (round(p.params["speed_rpm"], 1), round(p.params["clearance_m"] * 1e3, 4),
            round(p.params["misalignment_m"] * 1e3, 4))


def _is_base_scene(p) -> bool:
    return not str(p.params["scene"]).endswith(".toml")


def testrig_figures(out, figs, *, tasks=None, prefix: str = "study-testrig") -> list[Path]:
    """Spectra of disk 2 and the 3# bearing support at each speed step for the clearance pair (δ 2 mm) and the
    misalignment pair (δ0 0.05 mm), paper Figs. 27–28; the 1X–5X table; the stick-margin figure and summary."""
    plt = pyplot()
    figs = Path(figs)
    pts = [p for p in load_points(out, tasks) if _is_base_scene(p)]
    files = []
    for rpm in sorted({p.params["speed_rpm"] for p in pts}):
        fig, axes = plt.subplots(2, 2, figsize=(11, 7), constrained_layout=True)
        at = {(_key(p)[1], _key(p)[2]): p for p in pts if p.params["speed_rpm"] == rpm}
        cases = {"clearance (δ = 2 mm)": [at[k] for k in ((0.01, 2.0), (0.05, 2.0)) if k in at],
                 "misalignment (δ0 = 0.05 mm)": [at[k] for k in ((0.05, 1.0), (0.05, 2.0), (0.05, 3.0)) if k in at]}
        for i, (case, cps) in enumerate(cases.items()):
            for j, (ch, lab) in enumerate(LOCATIONS[1:]):
                ax = axes[i, j]
                for p in cps:
                    c = channel_column(p, ch)
                    lbl = (f"δ0 = {p.params['clearance_m'] * 1e3:g} mm" if i == 0 else f"δ = {p.params['misalignment_m'] * 1e3:g} mm")
                    ax.semilogy(p.arrays["spec_orders"] * rpm / 60, np.maximum(p.arrays["spec_v"][:, c] * 1e3, 1e-7),
                                lw=0.9, label=f"{lbl} ({p.info['label']}, contact {100 * p.info['contact_fraction']:.0f} %)")
                ax.set_xlabel("frequency (Hz)")
                ax.set_ylabel("y-velocity amplitude (mm/s)")
                ax.set_title(f"{lab}, varying {case}", fontsize=9)
                ax.legend(fontsize=8)
        fig.suptitle(f"Test rig (Table 5 scene) at {rpm:.0f} rpm", fontsize=10)
        files += save(fig, figs / f"{prefix}-{rpm:.0f}rpm")
    rows = []
    for p in load_points(out, tasks):
        _, A = harmonic_table([p], "v")
        rows.append([Path(str(p.params["scene"])).stem, p.params["speed_rpm"], p.params["clearance_m"] * 1e3,
                     p.params["misalignment_m"] * 1e3, p.info["label"], p.info["contact_fraction"],
                     p.info["stick_fraction"], int(p.info["converged"])] + list((A[0] * 1e3).ravel()))
    files.append(write_csv(figs / f"{prefix}.csv", ["scene", "speed_rpm", "clearance_mm", "misalignment_mm", "regime",
                                                    "contact_fraction", "stick_fraction", "converged"]
                           + [f"{c}_v{o}X_mm_s" for c in ("disk1", "disk2", "support") for o in range(1, 6)], rows))
    scan = read_scan(out)
    if scan:
        files += scan_figure(scan, figs / f"{prefix}-stick-margin")
        files.append(write_csv(figs / f"{prefix}-stick-margin.csv", *_summary_table(scan)))
    return files


def read_scan(out) -> list[dict]:
    """The stick-margin scan a ``study testrig`` run left in ``out`` (rows of :data:`SCAN_HEAD`), or [] if none."""
    from reports.studies.common import read_csv_rows
    path = Path(out) / SCAN_CSV
    if not path.is_file():
        return []
    rows = read_csv_rows(path)
    for r in rows:
        for k in SCAN_HEAD[3:]:
            r[k] = float(r[k])
    return rows


def write_scan(points, out) -> Path:
    """The scan's :class:`rotor.studies.testrig_scan.ScanPoint` rows into ``out``/:data:`SCAN_CSV`."""
    return write_csv(Path(out) / SCAN_CSV, SCAN_HEAD,
                     [[p.variant, p.placement, p.sleeve, p.misalignment_mm, p.speed_rpm, p.peak_face_force_N,
                       p.static_face_force_N, p.limit_N] for p in points])


def _cases(scan) -> dict:
    by: dict = {}
    for r in scan:
        by.setdefault((r["variant"], r["placement"], r["sleeve"], r["misalignment_mm"]), []).append(r)
    return by


def _summary_table(scan) -> tuple[list, list]:
    """Per reading and δ: the largest demand over μN and its speed, the slip band, the demand at the paper's steps."""
    head = ["variant", "placement", "sleeve", "misalignment_mm", "largest_ratio", "at_rpm", "slip_from_rpm",
            "slip_to_rpm", "ratio_3600rpm", "ratio_5500rpm"]
    rows = []
    for (v, pl, sl, d), rs in _cases(scan).items():
        ratio = {r["speed_rpm"]: r["peak_face_force_N"] / r["limit_N"] for r in rs}
        top = max(ratio, key=ratio.get)
        slip = [s for s, x in ratio.items() if x >= 1.0]
        rows.append([v, pl, sl, d, ratio[top], top, min(slip) if slip else "", max(slip) if slip else "",
                     ratio.get(3600.0, float("nan")), ratio.get(5500.0, float("nan"))])
    return head, rows


def scan_figure(scan, prefix: Path) -> list[Path]:
    """End-face demand over μN against speed: per variant the envelope over placements, sleeves and δ, and the
    Table 5 reading (δ 2 mm, the scene's placement and sleeve); μN and the paper's speed steps marked."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(9, 4.8), constrained_layout=True)
    for variant, colour in zip(dict.fromkeys(r["variant"] for r in scan), ("C0", "C1", "C2", "C3")):
        rs = [r for r in scan if r["variant"] == variant]
        speeds = sorted({r["speed_rpm"] for r in rs})
        env = {s: 0.0 for s in speeds}
        for r in rs:
            env[r["speed_rpm"]] = max(env[r["speed_rpm"]], r["peak_face_force_N"] / r["limit_N"])
        ax.semilogy(speeds, [env[s] for s in speeds], color=colour, lw=1.0, label=f"{variant}: envelope")
        t5 = sorted((r["speed_rpm"], r["peak_face_force_N"] / r["limit_N"]) for r in rs
                    if r["misalignment_mm"] == 2.0 and r["placement"] == "opposed-at-joint" and r["sleeve"] == "rig sleeve")
        ax.semilogy(*zip(*t5), color=colour, lw=0.8, ls="--", label=f"{variant}: δ 2 mm, opposed-at-joint, rig sleeve")
    ax.axhline(1.0, color="k", lw=0.8, label="demand = μN (a face slips)")
    for s in (3600, 5500):
        ax.axvline(s, color="grey", lw=0.6, ls=":")
    ax.set_xlabel("speed (rpm); dotted: the paper's steps 3 600 and 5 500 rpm")
    ax.set_ylabel("peak end-face demand / μN (–)")
    ax.set_title("Test rig stuck: end-face demand over the friction limit (N = 10 000 N, μ = 0.3)", fontsize=10)
    ax.legend(fontsize=7, loc="lower right")
    return save(fig, prefix)


def rig_inputs(p) -> dict:
    """A point's inputs to :func:`rotor.studies.section6.judge_rig` (y velocity; noise from the step or the floor)."""
    from reports.studies.findings import spectral_floor
    from reports.studies.readings import orbit_radius_ratios
    from rotor.studies.section5 import amplitude_noise

    floor_q = np.zeros((3, 5)) if p.info["converged"] else spectral_floor(p, "q")
    Aq = harmonic_table([p], "q")[1][0]
    return {"A": harmonic_table([p], "v")[1][0],
            "floor": np.zeros((3, 5)) if p.info["converged"] else spectral_floor(p, "v"),
            "orbit": orbit_radius_ratios(p),
            "orbit_noise": np.array([amplitude_noise({"noise_rel": floor_q}, k, (1, 2, 3, 4, 5), Aq) for k in range(3)])}


def rig_verdicts(points) -> list[tuple]:
    """``[(scene, key, rpm, verdict, effect, threshold, text)]``: :func:`rotor.studies.section6.judge_rig` of the
    scene's points, and of the fitted rig's pair (δ0 0.01 / 0.05 mm at one speed, δ 2 mm): Fig. 27's clearance
    statement, and the orbit and harmonics statements at δ0 0.01 mm."""
    from rotor.studies.section6 import clearance_raises, harmonics_near_support, judge_rig, noncircular

    out = [("paper-table5-testrig", *v) for v in judge_rig({_key(p): rig_inputs(p) for p in points if _is_base_scene(p)})]
    fitted = {_key(p): p for p in points if not _is_base_scene(p)}
    for rpm in sorted({k[0] for k in fitted}):
        a, b = fitted.get((rpm, 0.01, 2.0)), fitted.get((rpm, 0.05, 2.0))
        if a is None or b is None:
            continue
        name = Path(str(a.params["scene"])).stem
        ia = rig_inputs(a)
        out += [(name, "noncircular", rpm, *noncircular(ia)), (name, "harmonics", rpm, *harmonics_near_support(ia)),
                (name, "clearance", rpm, *clearance_raises(ia, rig_inputs(b)))]
    return out


def _points_lines(points) -> list[str]:
    lines = ["| scene | speed (rpm) | δ0 (mm) | δ (mm) | regime | contact % | faces stuck % | max r/δ0 | periodic | "
             "2X–5X disk 2 (mm/s) | 2X–5X support (mm/s) |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for p in sorted(points, key=lambda p: (not _is_base_scene(p), _key(p))):
        _, V = harmonic_table([p], "v")
        rpm, c, d = _key(p)
        lines.append(f"| `{Path(str(p.params['scene'])).stem}` | {rpm:.0f} | {c:g} | {d:g} | {p.info['label']} | "
                     f"{100 * p.info['contact_fraction']:.0f} | {100 * p.info['stick_fraction']:.0f} | "
                     f"{p.info['max_r_over_clearance']:.3g} | "
                     f"{'yes' if p.info['converged'] else 'no'} | {V[0, 1, 1:].sum() * 1e3:.4g} | "
                     f"{V[0, 2, 1:].sum() * 1e3:.4g} |")
    return lines


def _verdict_lines(verdicts) -> list[str]:
    from rotor.studies.section6 import STATEMENTS
    words = {k: (w, fig) for k, w, fig in STATEMENTS}
    lines = ["| statement of the paper | figure | scene | speed (rpm) | verdict | effect | threshold | our numbers |",
             "|---|---|---|---|---|---|---|---|"]
    for scene, key, rpm, v, e, t, text in verdicts:
        w, fig = words[key]
        lines.append(f"| {w} | {fig} | `{scene}` | {rpm:.0f} | {v} | {e:+.3g} | {t:.2g} | {text} |")
    return lines


def _scan_lines(scan) -> list[str]:
    head, rows = _summary_table(scan)
    by = {}
    for r in rows:
        by.setdefault(r[0], []).append(r)
    lines = ["| reading of what Table 5 leaves out | largest demand / μN (speed) | speeds where a face slips | "
             "demand / μN at 3 600 rpm | at 5 500 rpm |", "|---|---|---|---|---|"]
    for v, rs in by.items():
        top = max(rs, key=lambda r: r[4])
        slip = [r for r in rs if r[6] != ""]
        band = (f"{min(r[6] for r in slip):.0f}–{max(r[7] for r in slip):.0f} rpm in {len(slip)} of {len(rs)} cases"
                if slip else "none")
        lines.append(f"| {v} | {top[4]:.3g} ({top[5]:.0f} rpm: {top[1]}, {top[2]}, δ {top[3]:g} mm) | {band} | "
                     f"{min(r[8] for r in rs):.3g}–{max(r[8] for r in rs):.3g} | "
                     f"{min(r[9] for r in rs):.3g}–{max(r[9] for r in rs):.3g} |")
    return lines


def testrig_note(points, scan=None) -> str:
    """reports/published/study-testrig.md: the points, the Section 6 statements judged, and the stick-margin scan
    (``scan``: :func:`read_scan` of the run, None or [] leaves that section out)."""
    from collections import Counter
    verdicts = rig_verdicts(points)
    count = Counter(v[3] for v in verdicts)
    lines = ["# Test rig (Table 5 scene): Section 6 judged, and whether its loose support can slip", "",
             "`ringcontact study testrig`: steady states of the `paper-table5-testrig` scene (shaft geometry, disk "
             "positions, frame tilt and damping assumed: scene comments; Eq. 34 as `opposed-at-joint`, the placement "
             "section5-readings chose, with the rig's 0.5 kg / 30 mm sleeve) at the paper's speed steps 3 600 and 5 500 "
             "rpm (Figs. 25–26): Table 5's δ0 0.05 mm and δ 2 mm, δ0 0.01 mm (Fig. 27) and δ 1 and 3 mm (Fig. 28); "
             "preload 10 000 N (Table 5), μ 0.3 (Table 4's; Table 5 gives none). Spectra are y velocity. Each "
             "statement of §6.2 is judged as Section 5's (rotor.studies.section6): the effect in the paper's sense, "
             "the threshold the model's numerical noise, the verdict agrees / disagrees / no effect.", "",
             *_points_lines(points), "",
             f"Verdicts: {count.get('agrees', 0)} agree, {count.get('no effect', 0)} no effect, "
             f"{count.get('disagrees', 0)} disagree.", "", *_verdict_lines(verdicts), "",
             "Fig. 24 (cascades over the whole test, \"the amplitudes ... higher at these two speed steps\") is not "
             "judged: Fig. 22 states no other step. The model's own critical speeds are not at the paper's (scene: "
             "2 596 and 7 405 rpm against 3 319 and 5 184 rpm, rotor-testrig.md), so its 3 600 and 5 500 rpm are not "
             "near resonance; the scan below follows the demand through the readings whose critical speeds are the "
             "paper's.", ""]
    if scan:
        lines += ["## Can the rig's loose support slip within the paper's stated rig data?", "",
                  "The ring meets the bore only after an end face slips: while both stick, bearing and frame move as "
                  "one (relative motion zero, r = 0), whatever δ0. The stuck steady state is linear (the transition "
                  "shaft's cubic remainder aside), so its end-face demand is computed exactly from the locked harmonic "
                  "response (rotor.studies.stick_margin; at 3 600 rpm 174.5 N against 177.4 N peak in the nonlinear "
                  "stuck record of `simulate`) and scanned (rotor.studies.testrig_scan) over 300–8 000 rpm in 10 rpm "
                  "steps, δ 1, 2 and 3 mm, the three Eq. 34 placements, the rig's sleeve and one with Table 4's "
                  "×21.95 moment factor, and three readings of what Table 5 leaves out (A: the scene, the 15 kg frame "
                  "moving on k3; B: the frame still, k3 to ground, which puts the disk-2 mode at the paper's "
                  "3 319 rpm; C: B with the front shaft fitted to the paper's 5 184 rpm, rotor-testrig.md). A face "
                  "slips where the demand reaches μN = 3 000 N. Near a critical speed the demand grows about inversely with the "
                  "damping, which Table 5 does not give (the scene's assumed 200 N s/m at each bearing and the frame): the "
                  "slip bands below are that damping's. At the paper's steps, off resonance, it matters little: with half or "
                  "twice that damping the largest demand there is 0.385 or 0.379 of μN (rotor.studies.testrig_scan, "
                  "damping_factor).", "",
                  *_scan_lines(scan), "",
                  *_fitted_lines(points, scan)]
    return "\n".join(lines)


def _fitted_lines(points, scan) -> list[str]:
    """What the scan and the fitted rig's nonlinear points say, from their numbers."""
    from rotor.studies.testrig_scan import PRELOAD_N
    steps = [r for r in scan if r["speed_rpm"] in (3600.0, 5500.0)]
    top = max(steps, key=lambda r: r["peak_face_force_N"] / r["limit_N"])
    ratio = top["peak_face_force_N"] / top["limit_N"]
    out = [f"At the paper's steps no reading slips: the largest demand there is {ratio:.3g} of μN ({top['variant']}, "
           f"{top['placement']}, {top['sleeve']}, δ {top['misalignment_mm']:g} mm, {top['speed_rpm']:.0f} rpm), so a face "
           f"would slip there only below a preload of {ratio * PRELOAD_N:.0f} N (Table 5: 10 000 N; Table 4: "
           "5 000 N). The rig then stays stuck with r = 0 whatever δ0, and Fig. 27's clearance effect cannot "
           "appear in this model at those steps."]
    fitted = sorted((p for p in points if not _is_base_scene(p)), key=_key)
    if fitted:
        out += ["", "The fitted rig (case C) at the speed of its largest demand, in the nonlinear steady state: " + "; ".join(
            f"δ0 {_key(p)[1]:g} mm: {p.info['label']}, faces stuck {100 * p.info['stick_fraction']:.0f} %, contact "
            f"{100 * p.info['contact_fraction']:.0f} %, max r/δ0 {p.info['max_r_over_clearance']:.3g}"
            for p in fitted) + f" ({_key(fitted[0])[0]:.0f} rpm, δ 2 mm)."]
    return out + [""]
