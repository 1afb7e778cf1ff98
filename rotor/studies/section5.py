"""The paper's Section 5 findings judged per speed band, one speed at a time.

Dai et al. (2025), §5.1–5.3, state their findings over speed ranges ("low speed range (0~9000 rpm)",
"high (9000~18,000 rpm)"); a median over a range can hide a band where a finding fails. Here each
finding (:data:`FINDINGS`) is judged at *every* speed of a band (:data:`BANDS`, edges stated) by
:meth:`Finding.judge`: an **effect** in the paper's sense (a relative change of an amplitude between the
compared cases or stations, positive where the paper is right), a **threshold** tied to the model's numerical
noise (the time step's error of the amplitudes, :data:`STEP_NOISE`, and at a non-periodic speed the spectral
floor around each harmonic of its record, whichever is larger; summed over the two points compared), and a
verdict from :data:`VERDICTS`: *agrees* (the effect beyond the threshold in the paper's sense), *disagrees*
(beyond it against the paper's sense), *no effect* (within it). A statement of "at most x %" agrees where the
change is at most x % plus the threshold. A speed where a compared case is not periodic is judged on the
harmonics of its record of the last 32 revolutions (exact bins of that record: each harmonic averaged over the
32 revolutions), said so per speed. A band's verdict is the most frequent one of its speeds, a tie going
against the paper (:class:`BandVerdict`). The report (reports/studies/findings.py, study-findings.md) and the
tests (tests/rotor/studies/test_study_paper.py) judge with the same code, on the same points
(:func:`rotor.studies.steady_state.run_point`). The boolean predicates (``near_support`` …) are the
statements' plain readings, used for the text of each speed.

Inputs of a judge (one speed): ``amps`` maps a case to ``(A, info)`` with ``A`` the (3, 5)
amplitudes of 1X–5X at disk 1, disk 2 and the 3# bearing support (y velocity for the cascades,
m/s; y displacement for Figs. 18–19, m) and ``info`` the point's info (``stick_fraction``,
``contact_fraction``, ``converged``, optionally ``noise_rel``). Cases: ``base`` (δ0 = 0.05 mm, δ = 1 mm,
tilt on), ``notilt``, ``c0.03``/``c0.08`` (clearance, mm), ``d0.5``/``d2`` (misalignment, mm).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: speed bands (rpm, both edges included): the paper's low range split at point A, its high range in thirds
BANDS = {"L1": (300.0, 4500.0), "L2": (4800.0, 8700.0), "H1": (9000.0, 12000.0), "H2": (12300.0, 15000.0),
         "H3": (15300.0, 18000.0)}
LOW, HIGH = ("L1", "L2"), ("H1", "H2", "H3")

#: "markedly reduced" (§5.2) read as at least 30 % lower
MARKED = 0.7
#: "minimal impact" (§5.3.1 (1)) read as within 5 %
MINIMAL = 0.05
#: "essentially unchanged" (§5.3.2) read as within 10 % while 2X changes fourfold (δ 0.5 → 2 mm)
UNCHANGED = 0.10


def _ratio(x) -> float:
    x = np.asarray(x, float)
    return float(x.max() / max(x.min(), 1e-300) - 1.0)


def near_support(amps) -> tuple[bool, str]:
    """§5.1, Fig. 12: 3X–5X at high speed larger at disk 2 and the 3# bearing than at disk 1 (y velocity)."""
    s = amps["base"][0][:, 2:5].sum(axis=1)
    return bool(s[1] > s[0] and s[2] > s[0]), f"3X–5X {s[0] * 1e3:.3g} / {s[1] * 1e3:.3g} / {s[2] * 1e3:.3g} mm/s"


def tilt_reduces(amps) -> tuple[bool, str]:
    """§5.2, Fig. 16 vs 12: with the tilt ignored 3X–5X are markedly (≥ 30 %) lower at disk 2 and the support."""
    on = amps["base"][0][:, 2:5].sum(axis=1)
    off = amps["notilt"][0][:, 2:5].sum(axis=1)
    r = off / np.maximum(on, 1e-300)
    return bool(r[1] < MARKED and r[2] < MARKED), f"off/on {r[0]:.2f} / {r[1]:.2f} / {r[2]:.2f}"


def stuck(amps) -> tuple[bool, str]:
    """§5.3.1 (1): below 9 000 rpm "there is no relative displacement between the bearing and support":
    both end faces stuck over the whole record (contact share given beside)."""
    i = amps["base"][1]
    return bool(i["stick_fraction"] >= 1.0), (f"stuck {100 * i['stick_fraction']:.0f} %, contact "
                                              f"{100 * i['contact_fraction']:.0f} %")


def clearance_minimal(amps) -> tuple[bool, str]:
    """§5.3.1 (1): at low speed δ0 (0.03 / 0.05 / 0.08 mm) changes 1X and 2X by less than 5 % at every station."""
    A = np.array([amps[c][0][:, :2] for c in ("c0.03", "base", "c0.08")])   # (3 δ0, 3 loc, 2 orders)
    ch = A.max(axis=0) / np.maximum(A.min(axis=0), 1e-300) - 1
    return bool(ch.max() < MINIMAL), f"largest change 1X {100 * ch[:, 0].max():.1f} %, 2X {100 * ch[:, 1].max():.1f} %"


def _monotone(amps, cases, order, sign) -> tuple[bool, str]:
    a = np.array([amps[c][0][:, order - 1] for c in cases])                 # (3 values, 3 loc)
    d = np.diff(a[:, 1:], axis=0) * sign
    text = "; ".join(f"{n} " + "/".join(f"{x * 1e6:.3g}" for x in a[:, j]) for j, n in ((1, "disk 2"), (2, "support")))
    return bool(np.all(d > 0)), f"{order}X {text} µm"


def clearance_2x(amps):
    """§5.3.1 (2): at high speed 2X falls as δ0 grows (0.03 → 0.05 → 0.08 mm) at disk 2 and the support."""
    return _monotone(amps, ("c0.03", "base", "c0.08"), 2, -1)


def clearance_3x(amps):
    """§5.3.1 (2): at high speed 3X falls as δ0 grows at disk 2 and the support."""
    return _monotone(amps, ("c0.03", "base", "c0.08"), 3, -1)


def misalignment_2x(amps):
    """§5.3.2: 2X rises with δ (0.5 → 1 → 2 mm) at disk 2 and the support."""
    return _monotone(amps, ("d0.5", "base", "d2"), 2, +1)


def misalignment_3x(amps):
    """§5.3.2: 3X rises with δ at disk 2 and the support."""
    return _monotone(amps, ("d0.5", "base", "d2"), 3, +1)


def misalignment_1x(amps) -> tuple[bool, str]:
    """§5.3.2: 1X "remain[s] essentially unchanged" as δ grows (within 10 % at every station)."""
    A = np.array([amps[c][0][:, 0] for c in ("d0.5", "base", "d2")])
    ch = A.max(axis=0) / np.maximum(A.min(axis=0), 1e-300) - 1
    return bool(ch.max() <= UNCHANGED), f"1X change {100 * ch[0]:.1f} / {100 * ch[1]:.1f} / {100 * ch[2]:.1f} %"


# ---------------------------------------------------------------------------------------------
# verdicts: agrees / disagrees / no effect, with the effect size and the noise threshold
# ---------------------------------------------------------------------------------------------

AGREES, DISAGREES, NO_EFFECT = "agrees", "disagrees", "no effect"
VERDICTS = (AGREES, NO_EFFECT, DISAGREES)
#: relative error of a periodic point's harmonic amplitudes from the time step, 1X to 5X (–): 256 against 512
#: steps per revolution moved 1X–3X by at most 0.4 % and 4X–5X by 2 % (rotor.studies.steady_state.SteadyStateOptions,
#: measured at 4 500 and 10 500 rpm). A non-periodic point adds its spectral floor (``info["noise_rel"]``).
STEP_NOISE = np.array([0.004, 0.004, 0.004, 0.02, 0.02])


def amplitude_noise(info, loc: int, orders, A) -> float:
    """Relative noise (–) of the amplitude of ``orders`` (1-based, summed when several) at location ``loc``: the
    step error :data:`STEP_NOISE`, or where larger the point's spectral floor ``info["noise_rel"]`` ((3, 5):
    the largest spectral amplitude within a quarter order of each harmonic over the harmonic's own, zero on a
    periodic record's exact bins), weighted by the amplitudes of the orders summed."""
    j = np.asarray(orders, int) - 1
    n = np.maximum(STEP_NOISE, np.asarray(info.get("noise_rel", np.zeros((3, 5))), float)[loc])[j]
    a = np.asarray(A, float)[loc, j]
    return float((n * a).sum() / max(a.sum(), 1e-300))


#: how a finding's effect reads (:func:`verdict_of`): 'directed' (a change in the paper's sense), 'limit' ("within
#: x %": effect x minus the change), 'marked' (a reduction of at least 30 %), 'state' (minus the share slipping)
KINDS = {"near_support": "directed", "low_harmonics": "limit", "tilt": "marked", "stuck_low": "state", "clearance_low": "limit",
         "clearance_1x": "directed", "clearance_2x": "directed", "clearance_3x": "directed",
         "misalignment_2x": "directed", "misalignment_3x": "directed", "misalignment_1x": "limit"}


def verdict_of(name: str, effect: float, threshold: float) -> str:
    """The verdict of finding ``name`` from its effect and threshold (relative, –): *directed*: agrees above the
    threshold, disagrees below minus it, no effect between; *marked*: the same, agreeing only from a 30 %
    reduction on (``1 − MARKED``); *limit*: agrees unless the change exceeds the limit by more than the threshold
    (effect below minus it); *state*: agrees only at zero (faces stuck the whole record)."""
    kind = KINDS[name]
    if kind == "state":
        return AGREES if effect == 0.0 else DISAGREES
    if kind == "limit":
        return AGREES if effect >= -threshold else DISAGREES
    if abs(effect) <= threshold:
        return NO_EFFECT
    if effect < 0 or (kind == "marked" and effect < 1 - MARKED):
        return DISAGREES
    return AGREES


def _decide(name: str, e, t) -> tuple[str, float, float]:
    """Per-location effects ``e`` and thresholds ``t``: the verdict of the deciding location (the lowest verdict,
    disagrees < no effect < agrees, then the smallest ``e − t``) with its effect and threshold."""
    v = [verdict_of(name, float(a), float(b)) for a, b in zip(e, t)]
    k = min(range(len(v)), key=lambda i: (VERDICTS[::-1].index(v[i]), e[i] - t[i]))
    return v[k], float(e[k]), float(t[k])


def _near_support_v(amps):
    A, i = amps["base"]
    s = A[:, 2:5].sum(axis=1)
    e = [s[k] / max(s[0], 1e-300) - 1 for k in (1, 2)]
    t = [amplitude_noise(i, 0, (3, 4, 5), A) + amplitude_noise(i, k, (3, 4, 5), A) for k in (1, 2)]
    return (*_decide("near_support", e, t), near_support(amps)[1])


def _tilt_v(amps):
    (A, i), (B, j) = amps["base"], amps["notilt"]
    e = [1 - B[k, 2:5].sum() / max(A[k, 2:5].sum(), 1e-300) for k in (1, 2)]
    t = [amplitude_noise(i, k, (3, 4, 5), A) + amplitude_noise(j, k, (3, 4, 5), B) for k in (1, 2)]
    return (*_decide("tilt", e, t), tilt_reduces(amps)[1])


def _stuck_v(amps):
    i = amps["base"][1]
    e = float(i["stick_fraction"]) - 1.0         # minus the share of the record with a face slipping: exact
    return (verdict_of("stuck_low", e, 0.0), e, 0.0, stuck(amps)[1])


def _limit_v(name, amps, cases, orders, limit, text):
    """"Changes by less than ``limit``": the largest relative change over the cases, every location and order."""
    A = np.array([amps[c][0][:, [h - 1 for h in orders]] for c in cases])
    ch = A.max(axis=0) / np.maximum(A.min(axis=0), 1e-300) - 1
    t = max(amplitude_noise(amps[c][1], k, (h,), amps[c][0]) for c in cases for k in range(3) for h in orders) * 2
    e = limit - float(ch.max())
    return (verdict_of(name, e, t), e, t, text(amps)[1])


def _trend_v(name, amps, cases, order, signs, text):
    """Relative change of ``order`` from the first to the last case at disk 2 and the support, times ``signs`` (the
    paper's sense per location: +1 rises, −1 falls); the threshold is the two points' noise."""
    (A0, i0), (A1, i1) = amps[cases[0]], amps[cases[-1]]
    e = [s * (A1[k, order - 1] / max(A0[k, order - 1], 1e-300) - 1) for k, s in zip((1, 2), signs)]
    t = [amplitude_noise(i0, k, (order,), A0) + amplitude_noise(i1, k, (order,), A1) for k in (1, 2)]
    return (*_decide(name, e, t), text(amps)[1])


_C, _D = ("c0.03", "base", "c0.08"), ("d0.5", "base", "d2")


#: "significant" 3X–5X (§5.1): their sum at least this share of 1X (as reports/studies/readings.py VISIBLE)
SIGNIFICANT = 0.05


def low_harmonics(amps) -> tuple[bool, str]:
    """§5.1 (Fig. 12): 3X–5X appear "when the rotational speed is high": below 9 000 rpm their sum stays under
    :data:`SIGNIFICANT` of 1X at disk 2 and the support (y velocity)."""
    A = amps["base"][0]
    r = A[:, 2:5].sum(axis=1) / np.maximum(A[:, 0], 1e-300)
    return bool(r[1:].max() < SIGNIFICANT), f"(3X+4X+5X)/1X {r[0]:.3g} / {r[1]:.3g} / {r[2]:.3g}"


def _low_harmonics_v(amps):
    A, i = amps["base"]
    r = A[:, 2:5].sum(axis=1) / np.maximum(A[:, 0], 1e-300)
    k = 1 + int(np.argmax(r[1:]))
    t = float(r[k]) * (amplitude_noise(i, k, (3, 4, 5), A) + amplitude_noise(i, k, (1,), A))
    e = SIGNIFICANT - float(r[k])
    return (verdict_of("low_harmonics", e, t), e, t, low_harmonics(amps)[1])


def clearance_1x(amps):
    """§5.3.1 (2): at high speed, as δ0 grows, 1X "increases at disk 2 but decreases at 3# bearing"."""
    a = np.array([amps[c][0][:, 0] for c in _C])
    return bool(a[-1, 1] > a[0, 1] and a[-1, 2] < a[0, 2]), ("1X disk 2 " + "/".join(f"{x * 1e6:.3g}" for x in a[:, 1])
                                                          + "; support " + "/".join(f"{x * 1e6:.3g}" for x in a[:, 2]) + " µm")


JUDGES = {
    "near_support": _near_support_v, "low_harmonics": _low_harmonics_v, "tilt": _tilt_v, "stuck_low": _stuck_v,
    "clearance_low": lambda a: _limit_v("clearance_low", a, _C, (1, 2), MINIMAL, clearance_minimal),
    "clearance_1x": lambda a: _trend_v("clearance_1x", a, _C, 1, (+1, -1), clearance_1x),
    "clearance_2x": lambda a: _trend_v("clearance_2x", a, _C, 2, (-1, -1), clearance_2x),
    "clearance_3x": lambda a: _trend_v("clearance_3x", a, _C, 3, (-1, -1), clearance_3x),
    "misalignment_2x": lambda a: _trend_v("misalignment_2x", a, _D, 2, (+1, +1), misalignment_2x),
    "misalignment_3x": lambda a: _trend_v("misalignment_3x", a, _D, 3, (+1, +1), misalignment_3x),
    "misalignment_1x": lambda a: _limit_v("misalignment_1x", a, _D, (1,), UNCHANGED, misalignment_1x),
}


@dataclass(frozen=True)
class Finding:
    """A finding: its predicate, the cases and quantity it needs, the bands it speaks of, the paper's words."""
    name: str
    predicate: object
    cases: tuple
    quantity: str          # 'v' (cascade, y velocity) or 'q' (Figs. 18-19, y displacement)
    bands: tuple
    claim: str

    def judge(self, amps) -> tuple[str, float, float, str]:
        """``(verdict, effect, threshold, text)`` at one speed: the effect (relative, –) in the paper's sense
        (positive agrees; for a "within x %" statement x minus the change), the noise threshold (relative, –)."""
        return JUDGES[self.name](amps)


FINDINGS = (
    Finding("near_support", near_support, ("base",), "v", HIGH,
            "§5.1 (Fig. 12): at high speed 3X–5X at disk 2 and the 3# bearing, more than at disk 1"),
    Finding("low_harmonics", low_harmonics, ("base",), "v", LOW,
            "§5.1 (Fig. 12): 3X–5X appear at high speed: below 9 000 rpm their sum under 5 % of 1X (disk 2, support)"),
    Finding("tilt", tilt_reduces, ("base", "notilt"), "v", HIGH,
            "§5.2 (Fig. 16): ignoring the tilt markedly (≥ 30 %) reduces 3X–5X at disk 2 and the support"),
    Finding("stuck_low", stuck, ("base",), "v", LOW,
            "§5.3.1 (1): below 9 000 rpm no relative displacement between bearing and support (faces stuck)"),
    Finding("clearance_low", clearance_minimal, ("base", "c0.03", "c0.08"), "q", LOW,
            "§5.3.1 (1): below 9 000 rpm δ0 has minimal impact (1X, 2X within 5 %)"),
    Finding("clearance_1x", clearance_1x, ("base", "c0.03", "c0.08"), "q", HIGH,
            "§5.3.1 (2, Fig. 18): at high speed, as δ0 grows, 1X rises at disk 2 and falls at the support"),
    Finding("clearance_2x", clearance_2x, ("base", "c0.03", "c0.08"), "q", HIGH,
            "§5.3.1 (2, Fig. 18): at high speed 2X falls as δ0 grows (disk 2, support)"),
    Finding("clearance_3x", clearance_3x, ("base", "c0.03", "c0.08"), "q", HIGH,
            "§5.3.1 (2, Fig. 18): at high speed 3X falls as δ0 grows (disk 2, support)"),
    Finding("misalignment_2x", misalignment_2x, ("base", "d0.5", "d2"), "q", LOW + HIGH,
            "§5.3.2 (Fig. 19): 2X rises with δ (disk 2, support)"),
    Finding("misalignment_3x", misalignment_3x, ("base", "d0.5", "d2"), "q", HIGH,
            "§5.3.2 (Fig. 19): 3X rises with δ (disk 2, support)"),
    Finding("misalignment_1x", misalignment_1x, ("base", "d0.5", "d2"), "q", LOW + HIGH,
            "§5.3.2 (Fig. 19): 1X essentially unchanged as δ grows (within 10 %)"),
)
FINDING_NAMES = tuple(f.name for f in FINDINGS)


def finding(name: str) -> Finding:
    return FINDINGS[FINDING_NAMES.index(name)]


def in_band(speed_rpm: float, band: str) -> bool:
    lo, hi = BANDS[band]
    return lo - 1e-6 <= speed_rpm <= hi + 1e-6


@dataclass(frozen=True)
class SpeedVerdict:
    """One finding at one speed: ``verdict`` (:data:`VERDICTS`), ``effect`` and ``threshold`` (relative, –;
    :meth:`Finding.judge`), ``periodic`` (every compared case periodic; otherwise judged on the harmonics of the
    last 32 revolutions' record, their average over those revolutions), ``text`` (the numbers)."""
    rpm: float
    verdict: str
    effect: float
    threshold: float
    periodic: bool
    text: str


@dataclass(frozen=True)
class BandVerdict:
    """One finding in one band: the verdict at every speed of the band (``speeds``: :class:`SpeedVerdict`), and the
    speeds without a record (``no_record_rpm``: a case beyond the contact law's domain)."""
    finding: str
    band: str
    speeds: tuple
    no_record_rpm: tuple = ()

    def counts(self) -> dict:
        return {v: sum(s.verdict == v for s in self.speeds) for v in VERDICTS}

    @property
    def verdict(self) -> str:
        """The most frequent verdict of the band's speeds; a tie goes against the paper (disagrees, then no
        effect, then agrees)."""
        if not self.speeds:
            return "no data"
        c = self.counts()
        return max((DISAGREES, NO_EFFECT, AGREES), key=lambda v: (c[v], VERDICTS.index(v)))

    def summary(self) -> str:
        c, n = self.counts(), len(self.speeds)
        per = sum(s.periodic for s in self.speeds)
        return (f"{self.verdict} ({c[AGREES]} agree, {c[NO_EFFECT]} no effect, {c[DISAGREES]} disagree; "
                f"{per} of {n} periodic)") if n else "no data"


def band_verdict(f: Finding, band: str, by_speed: dict) -> BandVerdict:
    """Judge ``f`` at every speed of ``band`` in ``by_speed`` (``{rpm: {case: (A, info)}}``), periodic or not."""
    out, none = [], []
    for rpm in sorted(s for s in by_speed if in_band(s, band)):
        amps = by_speed[rpm]
        if any(c not in amps for c in f.cases):
            continue
        if any(not np.all(np.isfinite(amps[c][0][:, 0])) for c in f.cases):      # no 1X: no record
            none.append(rpm)
            continue
        v, e, t, text = f.judge(amps)
        out.append(SpeedVerdict(float(rpm), v, e, t, all(amps[c][1]["converged"] for c in f.cases), text))
    return BandVerdict(f.name, band, tuple(out), tuple(none))


# ---------------------------------------------------------------------------------------------
# mechanisms behind the failures, measured
# ---------------------------------------------------------------------------------------------

def law_secant_stiffness(scene, clearances_m, penetrations_m) -> np.ndarray:
    """Secant radial stiffness ``P(Δr)/Δr`` (N/m) of the scene's contact law, ``(len(clearances), len(penetrations))``.

    The conformal law (Dai et al. 2025 Eq. 5; contact/laws.py) is ``P = 2π E* δ0 l b²(1+b²)/D(b)`` with
    ``b² = Δr/(2δ0+Δr)``: for ``Δr ≪ δ0`` it tends to ``(π/2) E* l Δr``, in which δ0 has cancelled. At the
    sub-micrometre penetrations of the high-speed contact the law is thus nearly the same spring for every
    clearance; δ0 only moves where contact starts."""
    from contact.laws import conformal_force

    ls = scene.loose_support
    out = np.zeros((len(clearances_m), len(penetrations_m)))
    for i, d0 in enumerate(clearances_m):
        P = conformal_force(np.asarray(penetrations_m, float), clearance_m=float(d0), width_m=ls.ring_width_m,
                            bearing_E_Pa=ls.bearing_modulus_pa, bearing_nu=ls.bearing_poisson,
                            support_E_Pa=ls.support_modulus_pa, support_nu=ls.support_poisson).force_N
        out[i] = P / np.asarray(penetrations_m, float)
    return out


def first_slip(points) -> tuple[float | None, float]:
    """Lowest speed (rpm) of ``points`` whose end faces slip (stuck < 100 % of the record), and its contact share;
    points without a record (beyond the contact law's domain) are passed over."""
    for p in sorted(points, key=lambda p: p.params["speed_rpm"]):
        if p.info.get("stick_fraction", 1.0) < 1.0:
            return float(p.params["speed_rpm"]), float(p.info["contact_fraction"])
    return None, 0.0


def contact_pattern(arrays, info) -> dict:
    """How the ring meets the support over a point's recorded revolutions (the last ones of
    :func:`rotor.studies.steady_state.run_point`): ``impacts_per_rev`` (contact onsets, r1 or r2 crossing δ0
    outwards, per revolution; the record of whole revolutions counted as a loop), ``contact_share`` (of the record), ``period_revs`` and the amplitudes (N) of the
    radial contact force's 1X, 2X, 3X (``force_1x_N`` …; the magnitude of each harmonic of (Fy, Fz), zero without contact).

    Where the finding on 1X or 3X with δ fails (§5.3.2), these show whether the contact changes its pattern
    between the δ values (a regime switch) and how its force's harmonics move."""
    from rotor.studies.steady_state import harmonic_amplitudes

    d0 = float(info["clearance_m"])
    r1, r2 = np.asarray(arrays["r1"], float), np.asarray(arrays["r2"], float)
    spr = int(info["samples_per_rev"])
    revs = len(r1) // spr
    on = (r1 > d0) | (r2 > d0)
    f = np.asarray(arrays["f_contact"], float)[: revs * spr, :2]
    F = np.abs(harmonic_amplitudes(f - f.mean(axis=0), revs, (1, 2, 3))) if revs else np.zeros((3, 2))
    Fr = np.hypot(F[:, 0], F[:, 1])
    onsets = int(np.sum(on & ~np.roll(on, 1)))          # whole revolutions of a periodic record: wrap around
    return {"impacts_per_rev": onsets / max(revs, 1), "contact_share": float(on.mean()),
            "period_revs": int(info.get("period_revs", 0)), "force_1x_N": float(Fr[0]), "force_2x_N": float(Fr[1]),
            "force_3x_N": float(Fr[2])}


def misalignment_mechanism(points: dict) -> tuple[dict, str]:
    """The contact behind §5.3.2 at one speed: ``points`` maps ``d0.5``, ``base``, ``d2`` to ``(arrays, info)``.

    Returns ``({case: contact_pattern}, text)``: impacts per revolution, contact share, contact-force 1X and 3X
    (N) and the support's y 1X and 3X (µm) for δ = 0.5 / 1 / 2 mm."""
    cases = ("d0.5", "base", "d2")
    pat = {c: contact_pattern(*points[c]) for c in cases}

    def amp(c, h):
        a, i = points[c]
        return abs(a["harm_q"][h - 1, list(a["channels"]).index("s.y")]) * 1e6

    def per(c):
        p = pat[c]["period_revs"]
        return f"{pat[c]['impacts_per_rev']:.3g}" + (f" (period {p})" if p > 1 else "")

    text = ("impacts/rev " + " / ".join(per(c) for c in cases)
            + "; contact " + " / ".join(f"{100 * pat[c]['contact_share']:.0f}" for c in cases) + " %"
            + "; contact-force 1X " + " / ".join(f"{pat[c]['force_1x_N']:.0f}" for c in cases)
            + " N, 3X " + " / ".join(f"{pat[c]['force_3x_N']:.0f}" for c in cases) + " N"
            + "; support 1X " + " / ".join(f"{amp(c, 1):.3g}" for c in cases)
            + " µm, 3X " + " / ".join(f"{amp(c, 3):.3g}" for c in cases) + " µm")
    return pat, text


#: the clearance mechanism's tolerance, as a share of the clearance change compared (–): the ring's mean offset
#: follows δ0 where it moves by 1 ± this of δ0's change and its swings differ by less than this of it
FOLLOW_TOL = 0.1


def ring_offset(arrays) -> tuple[float, float]:
    """Where the ring rides in its support over a point's record: ``(mean, swing)`` (m) of the mean of its two
    edges' radial offsets ``r1``, ``r2`` (:func:`rotor.studies.steady_state.run_point`'s arrays); swing = peak to
    peak. In contact the ring sits near δ0; stuck, wherever it was held."""
    r = 0.5 * (np.asarray(arrays["r1"], float) + np.asarray(arrays["r2"], float))
    return float(r.mean()), float(np.ptp(r))


def offset_follows(clearances_m, means_m, swings_m) -> dict:
    """The geometric reading of the clearance study at one speed (§5.3.1 (2)): between the smallest and the largest
    clearance, ``slope`` (the mean offset's change over δ0's change, –), ``swing_change`` (largest minus smallest
    swing over δ0's change, –), ``inside_m`` (δ0 minus the mean offset at each clearance, m) and ``holds``: the
    mean offset follows δ0 with the same swing (slope within 1 ± :data:`FOLLOW_TOL`, swing change below it)."""
    d0, m, s = (np.asarray(x, float) for x in (clearances_m, means_m, swings_m))
    i, j = int(np.argmin(d0)), int(np.argmax(d0))
    slope = (m[j] - m[i]) / (d0[j] - d0[i])
    swing_change = (s.max() - s.min()) / (d0[j] - d0[i])
    return {"slope": float(slope), "swing_change": float(swing_change), "inside_m": d0 - m,
            "holds": bool(abs(slope - 1.0) <= FOLLOW_TOL and swing_change < FOLLOW_TOL)}
