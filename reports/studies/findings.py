"""The Section 5 findings of Dai et al. (2025) judged on finished study directories, per speed band.

:func:`point_a` judges the paper's point A (Fig. 13); :func:`band_verdicts` every finding of
:data:`rotor.studies.section5.FINDINGS` at every speed of its bands, with the verdicts agrees / disagrees / no
effect, the effect size and the noise threshold (rotor/studies/section5.py). Velocities are y velocities (the
paper's spectra, Figs. 12–16), displacements y displacements (Figs. 18–19).
"""
from __future__ import annotations

import numpy as np

from reports.studies.common import harmonic_table

POINT_A_RPM = 4500.0
#: half-width (orders) of the neighbourhood of a harmonic whose largest spectral amplitude is the point's floor there
FLOOR_ORDERS = 0.25


def point_a(points) -> tuple[str, str]:
    """§5.1, Fig. 13: at 4 500 rpm 2X accompanies 1X, relatively highest at the 3# bearing (2X/1X at least 0.05
    there and above disk 1's), and the support moves with the rotor (faces stuck): agrees or disagrees."""
    p = next((q for q in points if abs(q.params["speed_rpm"] - POINT_A_RPM) < 1), None)
    if p is None:
        return "no 4 500 rpm point", "no data"
    _, V = harmonic_table([p], "v")
    r = V[0, :, 1] / V[0, :, 0]
    stuck = p.info["stick_fraction"]
    text = (f"2X/1X disk 1 {r[0]:.3f}, disk 2 {r[1]:.3f}, support {r[2]:.3f}; end faces stuck {100 * stuck:.0f} % "
            f"of the time ({p.info['label']}, max r/δ0 {p.info['max_r_over_clearance']:.3f}, "
            f"{'periodic' if p.info['converged'] else 'not periodic'} after {p.info['transient_revs']} revolutions)")
    ok2 = r[2] >= 0.05 and r[2] > r[0]
    verdict = "agrees" if ok2 and stuck == 1.0 else "disagrees (the faces slip)" if ok2 else "disagrees"
    return text, verdict


_PARAM_CASES = {"base-rpm": "base", "c0.03mm-rpm": "c0.03", "c0.08mm-rpm": "c0.08", "d0.5mm-rpm": "d0.5",
                "d2mm-rpm": "d2"}
_LOC = ("disk1.y", "disk2.y", "s.y")


def spectral_floor(p, quantity: str) -> np.ndarray:
    """``(3, 5)``: at disk 1, disk 2 and the support, the largest amplitude of the point's spectrum within
    :data:`FLOOR_ORDERS` of each of 1X–5X (the harmonic's own bin excluded) over the harmonic's amplitude (–).
    Zero on a periodic record (its spectrum is on exact bins); at a non-periodic point the content the record
    does not repeat, which its averaged harmonics carry as uncertainty."""
    from reports.studies.common import channel_column

    o = np.asarray(p.arrays.get("spec_orders", ()), float)
    out = np.zeros((3, 5))
    if o.size == 0:
        return out
    S = np.asarray(p.arrays[f"spec_{quantity}"], float)
    H = np.abs(p.arrays[f"harm_{quantity}"])
    for k, ch in enumerate(_LOC):
        j = channel_column(p, ch)
        for h in range(1, 6):
            near = (np.abs(o - h) <= FLOOR_ORDERS) & (np.abs(o - h) > 1e-9)
            if near.any():
                out[k, h - 1] = S[near, j].max() / max(H[h - 1, j], 1e-300)
    return out


def _amps(p, quantity: str):
    from reports.studies.common import channel_column
    h = np.abs(p.arrays[f"harm_{quantity}"])
    info = dict(p.info)
    if not info.get("converged"):
        info["noise_rel"] = spectral_floor(p, quantity)
    return h[:, [channel_column(p, c) for c in _LOC]].T, info


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
    """Markdown rows: one per finding and mesh, one column per band: the band's verdict and its speeds' counts."""
    from rotor.studies.section5 import BANDS, FINDINGS

    heads = [f"{b} {BANDS[b][0]:.0f}–{BANDS[b][1]:.0f}" for b in BANDS]
    lines = ["| finding (Dai et al. 2025) | mesh | " + " | ".join(heads) + " |", "|---|---|" + "---|" * len(BANDS)]
    for f in FINDINGS:
        for tag, bv in (("paper", paper), (f"{elements}/segment", converged)):
            cells = []
            for b in BANDS:
                x = bv.get(f.name, {}).get(b)
                cells.append("—" if x is None else x.summary())
            lines.append(f"| {f.claim} | {tag} | " + " | ".join(cells) + " |")
    return lines


def _speed_text(s) -> str:
    how = "" if s.periodic else ", averaged spectrum"
    return (f"{s.rpm:.0f} {s.verdict}: effect {100 * s.effect:+.1f} % (threshold {100 * s.threshold:.1f} %{how}); "
            f"{s.text}")


def band_details(verdicts: dict, tag: str) -> list[str]:
    """Per finding and band: every speed's verdict, effect, threshold and numbers, and the speeds without a record."""
    from rotor.studies.section5 import finding

    out = [f"### {tag}", ""]
    for name, bands in verdicts.items():
        for b, x in bands.items():
            pts = "; ".join(_speed_text(s) for s in x.speeds)
            none = (" No record (beyond the contact law's domain): " + ", ".join(f"{r:.0f}" for r in x.no_record_rpm)
                    + " rpm.") if x.no_record_rpm else ""
            out.append(f"- **{finding(name).claim}**, {b}: {x.summary()}. {pts or 'no speed'}.{none}")
    return out + [""]


FINDINGS_CSV_HEADER = ["mesh", "finding", "band", "speed_rpm", "periodic", "verdict", "effect", "threshold"]


def findings_csv_rows(paper: dict, converged: dict, elements: int) -> list[list]:
    """Rows of ``study-findings.csv``: one per mesh, finding, band and speed (effect and threshold relative, –)."""
    rows = []
    for tag, bv in (("paper", paper), (f"{elements}/segment", converged)):
        for name, bands in bv.items():
            for b, x in bands.items():
                rows += [[tag, name, b, s.rpm, int(s.periodic), s.verdict, s.effect, s.threshold] for s in x.speeds]
    return rows
