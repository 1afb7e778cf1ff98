"""The comparison protocol of section5-readings: rows, effects, noise, weights (reports/protocols/section5-readings.toml).

The protocol file was committed before the run it scores; this module reads it and applies it. Each row of
Dai et al. (2025)'s text of Figs. 13–15 gets, per case (a reading of Eq. 34 or the no-excitation control, on
one mesh), an **effect**: the signed margin of the measured number to the row's threshold (positive: the row
holds; relative to the threshold unless the protocol says absolute), and a **noise**: the model's numerical
noise of that margin. The noise of an amplitude is :func:`rotor.studies.section5.amplitude_noise` (the time
step's amplitude error :data:`rotor.studies.section5.STEP_NOISE`, or at a point that is not periodic its
spectral floor, the larger); a ratio's relative noise is the sum of its amplitudes', and the margin's noise is
that times ``ratio / threshold``. A row is *meets* (effect > noise), *fails* (effect < −noise) or *within noise*;
the stick-share rows (B4, A2) count recorded samples and are judged exactly. A case's score under a weighting
(:class:`Weighting`) is the sum over scored rows and meshes of weight × the verdict's score
(:class:`Protocol`); rows every case meets on both meshes are left unscored (:func:`unscored_rows`).
"""
from __future__ import annotations

import tomllib
from dataclasses import dataclass, field

import numpy as np

MEETS, WITHIN, FAILS = "meets", "within noise", "fails"
#: rows judged exactly (a count of recorded samples): B4 holds when the faces slip at all, A2 only when never
STATE_ROWS = ("B4", "A2")


@dataclass(frozen=True)
class Row:
    """One statement of the paper as the protocol words it (every field a sentence of the file)."""
    id: str
    point: str
    statement: str
    measure: str
    threshold: str
    effect: str
    noise: str


@dataclass(frozen=True)
class Weighting:
    """A weight per row id (``default`` for the rest), the meshes counted (``None``: both) and whether only rows the
    control fails on that mesh are scored."""
    name: str
    why: str
    default: float = 1.0
    weights: dict = field(default_factory=dict)
    meshes: tuple | None = None
    control_fails_only: bool = False

    def weight(self, row_id: str) -> float:
        return float(self.weights.get(row_id, self.default))


@dataclass(frozen=True)
class Protocol:
    """The protocol file: rows, weightings, the primary weighting's name and the score of each verdict."""
    rows: tuple
    weightings: tuple
    primary: str
    scores: dict

    def weighting(self, name: str) -> Weighting:
        return next(w for w in self.weightings if w.name == name)


def load_protocol(text: str | None = None) -> Protocol:
    """The protocol from ``text`` (TOML) or the shipped reports/protocols/section5-readings.toml."""
    if text is None:
        from contact.package_data import shipped
        text = shipped("reports", "protocols", "section5-readings.toml").read_text(encoding="utf-8")
    d = tomllib.loads(text)
    rows = tuple(Row(**r) for r in d["rows"])
    ws = tuple(Weighting(w["name"], w["why"], float(w.get("default", 1.0)), dict(w.get("weights", {})),
                         tuple(w["meshes"]) if "meshes" in w else None, bool(w.get("control_fails_only", False)))
               for w in d["weightings"])
    sc = d["scoring"]
    return Protocol(rows, ws, sc["primary"], {MEETS: sc["meets"], WITHIN: sc["within_noise"], FAILS: sc["fails"]})


def _noise(m: dict, qty: str, loc: int, orders) -> float:
    from rotor.studies.section5 import amplitude_noise
    return amplitude_noise({"noise_rel": m[f"floor_{qty}"]}, loc, orders, m[f"amps_{qty}"])


def _verdict(e: float, n: float) -> str:
    return MEETS if e > n else FAILS if e < -n else WITHIN


def _worst(terms) -> tuple[str, float, float]:
    """``(verdict, effect, noise)`` of the deciding term of ``[(effect, noise)]``: the lowest verdict (fails <
    within noise < meets), then the smallest ``effect − noise``."""
    order = (FAILS, WITHIN, MEETS)
    e, n = min(terms, key=lambda t: (order.index(_verdict(*t)), t[0] - t[1]))
    return _verdict(e, n), float(e), float(n)


def _ratio_term(r: float, thr: float, rel_noise: float) -> tuple[float, float]:
    """Margin ``r/thr − 1`` of a ratio to its threshold and its noise (the ratio's relative noise × ``r/thr``)."""
    return r / thr - 1.0, rel_noise * r / thr


def effects_b(m: dict) -> dict:
    """``{row id: (verdict, effect, noise)}`` of the point-B rows from :func:`reports.studies.readings.point_measures`."""
    c, spr = m["contact_share"], max(m["samples_per_rev"], 1)
    rmax = max(m["r1_max_over_d0"], m["r2_max_over_d0"])
    b2 = [(min(1 - m[f"{r}_min_over_d0"], m[f"{r}_max_over_d0"] - 1), _noise(m, "q", 2, (1,)) * rmax) for r in ("r1", "r2")]
    o, v2, v35 = m["orbit_ratio"], m["v2_over_v1"], m["v35_over_v1"]
    n1 = [_noise(m, "v", k, (1,)) for k in range(3)]
    n35 = [_noise(m, "v", k, (3, 4, 5)) for k in range(3)]
    b6 = [_ratio_term(v35[2], 0.05, n35[2] + n1[2]),
          _ratio_term(v35[1], max(v35[0], 1e-300), n35[0] + n1[0] + n35[1] + n1[1]),
          _ratio_term(v35[2], max(v35[1], 1e-300), n35[1] + n1[1] + n35[2] + n1[2])]
    slip = 1.0 - m["stick_share"]
    return {"B1": _worst([(min(c, 1 - c) / 0.05 - 1, (1 / spr) / 0.05)]),
            "B2": _worst(b2),
            "B3": _worst([_ratio_term(o[k], 1.2, 2 * _noise(m, "q", k, (1, 2, 3, 4, 5))) for k in range(3)]),
            "B4": (MEETS if slip > 0 else FAILS, slip, 0.0),
            "B5": _worst([_ratio_term(v2[2], 0.05, n1[2] + _noise(m, "v", 2, (2,)))]),
            "B6": _worst(b6)}


def effects_a(m: dict) -> dict:
    """``{row id: (verdict, effect, noise)}`` of the point-A rows."""
    o, v2, A = m["orbit_ratio"], m["v2_over_v1"], m["amps_v"]
    a1 = [(1 - o[k] / 1.2, 2 * _noise(m, "q", k, (1, 2, 3, 4, 5)) * o[k] / 1.2) for k in (0, 1)]
    a3 = []
    for k in range(3):
        h = 2 + int(np.argmax(A[k, 1:]))
        a3.append(_ratio_term(A[k, 0], max(A[k, h - 1], 1e-300), _noise(m, "v", k, (1,)) + _noise(m, "v", k, (h,))))
    n = [_noise(m, "v", k, (1,)) + _noise(m, "v", k, (2,)) for k in range(3)]
    d = int(np.argmax(v2[:2]))
    a4 = [_ratio_term(v2[2], 0.05, n[2]), _ratio_term(v2[2], max(v2[d], 1e-300), n[2] + n[d])]
    stuck = m["stick_share"] - 1.0
    return {"A1": _worst(a1), "A2": (MEETS if stuck >= 0 else FAILS, stuck, 0.0), "A3": _worst(a3),
            "A4": _worst(a4)}


def judged_rows(mb: dict | None, ma: dict | None) -> dict:
    """Every row of one case: ``{id: (verdict, effect, noise)}``; a point without a record (beyond the contact
    law's domain, ``None``) fails its rows with no effect to show (NaN)."""
    nan = (FAILS, float("nan"), float("nan"))
    ids = [r.id for r in load_protocol().rows]
    out = effects_b(mb) if mb is not None else {i: nan for i in ids if i.startswith("B")}
    out.update(effects_a(ma) if ma is not None else {i: nan for i in ids if i.startswith("A")})
    return out


def unscored_rows(judged: dict) -> tuple:
    """Row ids every case (readings and the control, every mesh) meets: they do not tell the cases apart."""
    ids = dict.fromkeys(i for rows in judged.values() for i in rows)
    return tuple(i for i in ids if all(rows.get(i, (FAILS,))[0] == MEETS for rows in judged.values()))


def score(protocol: Protocol, judged: dict, weighting: Weighting, control: str) -> dict:
    """``{case name: score}`` under ``weighting``: ``judged`` maps ``(name, mesh tag)`` (mesh tag ``paper`` or
    ``converged``) to :func:`judged_rows`; ``control``: the control's name (for ``control_fails_only``)."""
    skip = set(unscored_rows(judged))
    out: dict = {}
    for (name, mesh), rows in judged.items():
        if weighting.meshes is not None and mesh not in weighting.meshes:
            out.setdefault(name, 0.0)
            continue
        ctrl = judged.get((control, mesh), {})
        s = 0.0
        for rid, (v, _, _) in rows.items():
            if rid in skip or (weighting.control_fails_only and ctrl.get(rid, (FAILS,))[0] == MEETS):
                continue
            s += weighting.weight(rid) * protocol.scores[v]
        out[name] = out.get(name, 0.0) + s
    return out


def winner(scores: dict, candidates, current: str) -> str:
    """The candidate with the highest score; a tie keeps ``current`` when it is among the tied."""
    top = max(scores[c] for c in candidates)
    tied = [c for c in candidates if abs(scores[c] - top) < 1e-9]
    return current if current in tied else tied[0]
