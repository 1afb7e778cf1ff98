"""The five Section 5 findings of Dai et al. (2025), judged on finished study directories.

Each judge takes the points of the studies it needs (``reports.studies.common.load_points``) and
returns ``(our numbers as text, verdict)``; :func:`findings_rows` puts them in the order of the
paper. Velocities are y velocities (the paper's spectra, Figs. 12–16); "high speed" is ≥ 9 000 rpm
(§5.3.1). Verdicts: "yes", "partly" (part of the statement holds, said which), "no", or "n/a"
when the studies needed are missing.
"""
from __future__ import annotations

import numpy as np

from reports.studies.common import harmonic_table

HIGH_RPM = 9000.0
POINT_A_RPM = 4500.0


def point_a(points) -> tuple[str, str]:
    """§5.1, Fig. 13: at 4 500 rpm 2X accompanies 1X, relatively highest at the 3# bearing, and the
    support moves with the rotor (no relative movement)."""
    p = next((q for q in points if abs(q.params["speed_rpm"] - POINT_A_RPM) < 1), None)
    if p is None:
        return "no 4 500 rpm point", "n/a"
    _, V = harmonic_table([p], "v")
    r = V[0, :, 1] / V[0, :, 0]
    stuck = p.info["stick_fraction"]
    text = (f"2X/1X disk 1 {r[0]:.3f}, disk 2 {r[1]:.3f}, support {r[2]:.3f}; end faces stuck {100 * stuck:.0f} % "
            f"of the time ({p.info['label']}, max r/δ0 {p.info['max_r_over_clearance']:.3f}, "
            f"{'periodic' if p.info['converged'] else 'not periodic'} after {p.info['transient_revs']} revolutions)")
    ok2 = r[2] >= 0.05 and r[2] > r[0]
    verdict = "yes" if ok2 and stuck == 1.0 else "partly (2X yes; the faces slip)" if ok2 else "no"
    return text, verdict


def harmonics_near_support(cascade) -> tuple[str, str]:
    """§5.1, Fig. 12: at high speed 3X–5X are significant at disk 2 and the 3# bearing, more than at disk 1."""
    rpm, V = harmonic_table(cascade, "v")
    hi = rpm >= HIGH_RPM
    if not hi.any():
        return "no high-speed points", "n/a"
    s = V[hi][:, :, 2:5].sum(axis=2)
    r = s / np.maximum(s[:, [0]], 1e-30)
    text = (f"sum 3X–5X over disk 1, median over {int(hi.sum())} speeds ≥ 9 000 rpm: disk 2 {np.median(r[:, 1]):.3g}, "
            f"support {np.median(r[:, 2]):.3g}; largest at the support {s[:, 2].max() * 1e3:.3g} mm/s "
            f"({rpm[hi][np.argmax(s[:, 2])]:.0f} rpm)")
    return text, "yes" if np.median(r[:, 1]) > 1 and np.median(r[:, 2]) > 1 else "no"


def tilt_ignored(cascade, notilt) -> tuple[str, str]:
    """§5.2, Fig. 16 vs 12: ignoring the angular deflections markedly reduces the harmonics."""
    if not notilt:
        return "no tilt-ignored cascade", "n/a"
    rpm, V = harmonic_table(cascade, "v")
    rpm0, V0 = harmonic_table(notilt, "v")
    common = [s for s in rpm[rpm >= HIGH_RPM] if s in set(rpm0)]
    if not common:
        return "no common high-speed points", "n/a"
    a = np.array([V[rpm == s][0, :, 2:5].sum(axis=1) for s in common])
    b = np.array([V0[rpm0 == s][0, :, 2:5].sum(axis=1) for s in common])
    ratio = b / np.maximum(a, 1e-30)
    med = np.median(ratio, axis=0)
    text = (f"sum 3X–5X tilt ignored / with tilt, median over {len(common)} speeds ≥ 9 000 rpm: disk 1 "
            f"{med[0]:.3g}, disk 2 {med[1]:.3g}, support {med[2]:.3g}")
    return text, "yes" if med[1] < 0.7 and med[2] < 0.7 else "partly (lower, not markedly)" if med[1:].max() < 1 else "no"


def _groups(params, key):
    base = [p for p in params if "clearance_m" not in p.params and "misalignment_m" not in p.params]
    out: dict = {}
    for p in [q for q in params if key in q.params] + base:
        out.setdefault(round(p.info[key], 9), {})[p.params["speed_rpm"]] = p
    return out


def _trend(params, key, sign):
    """Per order (1X, 2X, 3X): fraction of high speeds (periodic at every value) where disk 2 and the
    support change monotonically with the parameter in direction ``sign`` (+1 rising), and the largest
    1X change (%)."""
    groups = _groups(params, key)
    vals = sorted(groups)
    speeds = sorted(set.intersection(*(set(g) for g in groups.values())))
    use = [s for s in speeds if s >= HIGH_RPM and all(groups[v][s].info["converged"] for v in vals)]
    mono = np.zeros(3)
    one = 0.0
    for s in use:
        A = np.array([harmonic_table([groups[v][s]], "q", orders=(1, 2, 3))[1][0] for v in vals])  # (V, loc, 3)
        d = np.diff(A[:, 1:, :], axis=0) * sign
        mono += np.all(d > 0, axis=(0, 1))
        one = max(one, float((A[:, :, 0].max(axis=0) / A[:, :, 0].min(axis=0) - 1).max() * 100))
    return vals, len(use), mono / max(len(use), 1), one


def clearance(params) -> tuple[str, str]:
    """§5.3.1, Fig. 18: at high speed 2X and 3X decrease as the clearance grows."""
    if not params or len(_groups(params, "clearance_m")) < 2:
        return "no clearance study", "n/a"
    vals, n, mono, _ = _trend(params, "clearance_m", -1)
    text = (f"δ0 = {' / '.join(f'{v * 1e3:g}' for v in vals)} mm: at {n} periodic speeds ≥ 9 000 rpm, 2X falls "
            f"monotonically with δ0 at disk 2 and the support at {100 * mono[1]:.0f} % of them, 3X at {100 * mono[2]:.0f} %")
    return text, "yes" if min(mono[1:]) >= 0.5 and n else "partly (3X)" if mono[2] >= 0.5 else \
        "partly (2X)" if mono[1] >= 0.5 else "no"


def misalignment(params) -> tuple[str, str]:
    """§5.3.2, Fig. 19: as δ grows, 1X stays essentially unchanged while 2X and 3X increase."""
    if not params or len(_groups(params, "misalignment_m")) < 2:
        return "no misalignment study", "n/a"
    vals, n, mono, one = _trend(params, "misalignment_m", +1)
    text = (f"δ = {' / '.join(f'{v * 1e3:g}' for v in vals)} mm: at {n} periodic speeds ≥ 9 000 rpm, 2X rises "
            f"monotonically at disk 2 and the support at {100 * mono[1]:.0f} % of them, 3X at {100 * mono[2]:.0f} %; "
            f"1X changes by up to {one:.1f} %")
    ok = mono[1] >= 0.5 and mono[2] >= 0.5
    return text, "yes" if ok and one <= 5 else "partly (2X, 3X rise; 1X moves more than a few %)" if ok else \
        "partly (2X)" if mono[1] >= 0.5 else "no"


def findings_rows(cascade=None, notilt=None, params=None, point=None) -> list[tuple[str, str, str]]:
    """``[(finding, our numbers, verdict)]`` for the five Section 5 findings."""
    rows = [("Point A (Fig. 13): 2X with 1X, highest at the 3# bearing; support moves with the rotor",
             *(point_a(point) if point else ("no point study", "n/a"))),
            ("High speed (Fig. 12): 3X–5X at disk 2 and the 3# bearing, more than at disk 1",
             *(harmonics_near_support(cascade) if cascade else ("no cascade", "n/a"))),
            ("§5.2 (Fig. 16): ignoring the tilt markedly reduces the harmonics",
             *(tilt_ignored(cascade, notilt) if cascade else ("no cascade", "n/a"))),
            ("§5.3.1 (Fig. 18): smaller clearance, larger 2X and 3X at high speed", *clearance(params)),
            ("§5.3.2 (Fig. 19): larger misalignment, larger 2X and 3X, 1X unchanged", *misalignment(params))]
    return rows


def findings_table(rows) -> list[str]:
    return ["| finding (Dai et al. 2025) | ours | holds? |", "|---|---|---|"] + \
        [f"| {a} | {b} | {c} |" for a, b, c in rows]


# ---------------------------------------------------------------------------------------------
# per speed band (rotor.studies.section5): the verdicts of study-findings.md
# ---------------------------------------------------------------------------------------------

_PARAM_CASES = {"base-rpm": "base", "c0.03mm-rpm": "c0.03", "c0.08mm-rpm": "c0.08", "d0.5mm-rpm": "d0.5",
                "d2mm-rpm": "d2"}


def _amps(p, quantity: str):
    from reports.studies.common import channel_column
    h = np.abs(p.arrays[f"harm_{quantity}"])
    return h[:, [channel_column(p, c) for c in ("disk1.y", "disk2.y", "s.y")]].T, p.info


def by_speed(cascade=None, notilt=None, params=None) -> tuple[dict, dict]:
    """``({rpm: {case: (A, info)}}`` of y velocities from the cascades, the same of y displacements from
    the params study)``: the inputs of :func:`rotor.studies.section5.band_verdict`."""
    v: dict = {}
    for pts, case in ((cascade or [], "base"), (notilt or [], "notilt")):
        for p in pts:
            v.setdefault(round(p.params["speed_rpm"], 1), {})[case] = _amps(p, "v")
    q: dict = {}
    for p in params or []:
        prefix = p.key.rsplit("rpm", 1)[0] + "rpm"
        if prefix in _PARAM_CASES:
            q.setdefault(round(p.params["speed_rpm"], 1), {})[_PARAM_CASES[prefix]] = _amps(p, "q")
    return v, q


def band_verdicts(cascade=None, notilt=None, params=None) -> dict:
    """``{finding name: {band: BandVerdict}}`` of every finding of :data:`rotor.studies.section5.FINDINGS`."""
    from rotor.studies.section5 import FINDINGS, band_verdict

    v, q = by_speed(cascade, notilt, params)
    return {f.name: {b: band_verdict(f, b, v if f.quantity == "v" else q) for b in f.bands} for f in FINDINGS}


def band_table(paper: dict, converged: dict, elements: int) -> list[str]:
    """Markdown rows: one per finding, one column per band and mesh, the verdict and where it holds."""
    from rotor.studies.section5 import BANDS, FINDINGS

    heads = [f"{b} {BANDS[b][0]:.0f}–{BANDS[b][1]:.0f}" for b in BANDS]
    lines = ["| finding (Dai et al. 2025) | mesh | " + " | ".join(heads) + " |", "|---|---|" + "---|" * len(BANDS)]
    for f in FINDINGS:
        for tag, bv in (("paper", paper), (f"{elements}/segment", converged)):
            cells = []
            for b in BANDS:
                x = bv.get(f.name, {}).get(b)
                cells.append("—" if x is None else x.verdict)
            lines.append(f"| {f.claim} | {tag} | " + " | ".join(cells) + " |")
    return lines


def band_details(verdicts: dict, tag: str) -> list[str]:
    """Per finding and band: the speeds judged, where it holds, the numbers at each, the speeds left out."""
    from rotor.studies.section5 import finding

    out = [f"### {tag}", ""]
    for name, bands in verdicts.items():
        for b, x in bands.items():
            pts = "; ".join(f"{s:.0f} {'✔' if ok else '✘'} {t}" for s, ok, t in zip(x.speeds_rpm, x.holds, x.texts))
            skip = (" Not periodic (not judged; the predicate there: " + "; ".join(
                f"{s:.0f} {'✔' if ok else '✘'} {t}" for s, ok, t in x.loose) + ").") if x.loose else ""
            out.append(f"- **{finding(name).claim}**, {b}: {x.verdict}. {pts or 'no periodic speed'}.{skip}")
    return out + [""]
