"""The validity record of a run: which contact law drove the loose support, whether its own checks passed, and
how much of the time in contact the rotor spent inside the range the law was fitted and checked over.

One record per run, the same dict under the JSON key ``law_validity`` in every rotor job's output
(``simulate``, ``orbit``, ``branch``, ``study``) and in the API's result objects (:mod:`ringcontact.nonlinear`):

``law``
    the law as the scene names it (``conformal``, ``calibrated:<name>``, a law file's path as typed);
``law_name``, ``law_file``, ``law_sha256``
    a calibrated law's name, the file it was read from and the file's checksum (None for an analytic law);
``verdict``
    ``verified`` (the law file's own checks passed), ``flagged`` (they did not: ``verdict_reasons`` quotes the
    file's warnings) or ``analytic`` (a closed-form law with no fitted range: nothing to check the run against);
``penetration_range_m``, ``tilt_range_rad``
    the fitted penetration range ``[min, max]`` (m) and the tilt range ``[0, max]`` (rad) the law was checked at
    against a 3D reference (``[0, 0]``: a straight ring only); None for an analytic law;
``contact_time_share``
    the share of the recorded time the ring touches its support (an edge past the clearance);
``contact_time_share_below``, ``contact_time_share_inside``, ``contact_time_share_above``
    shares of that contact time whose deepest edge penetration lies below, inside or above the fitted range
    (they sum to 1; None without contact or without a fitted range);
``visited_penetration_range_m``
    the smallest and largest edge penetration while in contact (m; None without contact);
``largest_tilt_rad``
    the largest relative tilt of the ring while in contact (rad; 0 without contact);
``beyond_tilt_range``
    True when that tilt passes the checked tilt of a law checked against a 3D reference; None when the law's
    tilt was never checked (a straight-ring law) or for an analytic law;
``warnings``
    the sentences every job prints on the terminal (:func:`warning_lines`).

The penetration of a sample is the deeper edge's, ``max(r1, r2) − δ0`` (:func:`rotor.dynamics.constraints.
edge_offsets`, the quantity of ``simulate``'s ``max_edge_penetration_mm``); samples are uniform in time, so a
share of samples is a share of time. The verdict is the one ``ringcontact bearing`` writes into a law file
(``provenance.warnings``: empty for a verified law, reports/bearing/pipeline.py) and ``ringcontact calibrate``
into a shipped one (``fit.warning``, contact/calibrate/fit.py).
"""
from __future__ import annotations

import numpy as np

from contact.errors import InputError
from contact.units import ARCMIN

VERIFIED, FLAGGED, ANALYTIC = "verified", "flagged", "analytic"
#: the option (command line) and keyword (API) that let a flagged law run
ALLOW_OPTION, ALLOW_KEYWORD = "--allow-flagged-law", "allow_flagged_law"
_REL = 1e-9       # a value equal to a range end (rounded in the law file) is inside


def verdict(calibrated) -> tuple[str, list[str]]:
    """``(verdict, reasons)`` of a calibrated law (:class:`contact.calibrate.law.CalibratedLaw`; None: analytic)."""
    if calibrated is None:
        return ANALYTIC, []
    reasons = [str(w) for w in (calibrated.provenance or {}).get("warnings") or []]
    if (calibrated.fit or {}).get("warning"):
        reasons.append(str(calibrated.fit["warning"]))
    return (FLAGGED if reasons else VERIFIED), reasons


def check_allowed(loose, allowed: bool, where: str) -> None:
    """Refuse a flagged law (one :class:`~contact.errors.InputError` line) unless ``allowed``.

    ``loose``: the scene's :class:`rotor.model.loose_support_scene.LooseSupport` (None: nothing to check);
    ``where``: how the message names the option that lets it run (``--allow-flagged-law`` or the API keyword).
    """
    if loose is None or allowed:
        return
    kind, reasons = verdict(loose.calibrated)
    if kind == FLAGGED:
        raise InputError(f"law = {loose.law}: {loose.calibrated.name} is FLAGGED in its file ({reasons[0]}); "
                         f"refit it (ringcontact bearing) or give {where} to run on it anyway")


def law_header(loose) -> dict:
    """The record's fields that depend on the law only (no run): name, file, checksum, verdict and ranges."""
    if loose is None:
        return {}
    cal = loose.calibrated
    kind, reasons = verdict(cal)
    head = {"law": loose.law, "law_name": cal.name if cal is not None else loose.law,
            "law_file": loose.law_file or None, "law_sha256": loose.law_sha256 or None,
            "verdict": kind, "verdict_reasons": reasons, "penetration_range_m": None, "tilt_range_rad": None}
    if cal is not None:
        head["penetration_range_m"] = [float(v) for v in cal.validity_penetration_m]
        head["tilt_range_rad"] = [0.0, float(cal.validity_tilt_max_rad)]
    return head


def record(loose, penetration_m, tilt_rad) -> dict:
    """The ``law_validity`` record of a run (see the module docstring); empty without a loose support.

    Parameters
    ----------
    loose : rotor.model.loose_support_scene.LooseSupport or None
        The scene's loose support, with its law.
    penetration_m : array_like
        Deeper edge's penetration past the clearance per recorded sample (m; <= 0: no contact).
    tilt_rad : array_like
        Relative tilt magnitude of the ring per sample (rad).
    """
    if loose is None:
        return {}
    pen = np.asarray(penetration_m, dtype=float).ravel()
    tilt = np.abs(np.asarray(tilt_rad, dtype=float).ravel())
    hit = pen > 0.0
    out = law_header(loose)
    seen = pen[hit]
    out.update(contact_samples=int(hit.sum()), samples=int(pen.size),
               contact_time_share=float(hit.mean()) if pen.size else 0.0,
               contact_time_share_below=None, contact_time_share_inside=None, contact_time_share_above=None,
               visited_penetration_range_m=[float(seen.min()), float(seen.max())] if seen.size else None,
               largest_tilt_rad=float(tilt[hit].max()) if seen.size else 0.0, beyond_tilt_range=None)
    rng = out["penetration_range_m"]
    if rng is not None and seen.size:
        below = float(np.mean(seen < rng[0] * (1 - _REL)))
        above = float(np.mean(seen > rng[1] * (1 + _REL)))
        out.update(contact_time_share_below=below, contact_time_share_above=above,
                   contact_time_share_inside=1.0 - below - above)
    if out["tilt_range_rad"] is not None and out["tilt_range_rad"][1] > 0:
        out["beyond_tilt_range"] = bool(out["largest_tilt_rad"] > out["tilt_range_rad"][1] * (1 + _REL))
    out["warnings"] = warning_lines(out)
    return out


def warning_lines(rec: dict) -> list[str]:
    """The sentences of a record a job prints (each after its name and ``warning:``): contact time outside the fitted
    penetration range, a tilt past the checked one, a flagged law that ran."""
    lines = []
    if rec.get("verdict") == FLAGGED:
        lines.append(f"the law {rec['law_name']} is FLAGGED in its file ({rec['verdict_reasons'][0]}) and ran because "
                     f"{ALLOW_OPTION} ({ALLOW_KEYWORD}=True) was given")
    rng = rec.get("penetration_range_m")
    for side, word in (("below", "below"), ("above", "above")):
        share = rec.get(f"contact_time_share_{side}")
        if share:
            end = rng[0] if side == "below" else rng[1]
            lines.append(f"{100 * share:.3g} % of the contact time the edge penetration was {word} the law's fitted "
                         f"range ({rng[0] * 1e3:.4g}-{rng[1] * 1e3:.4g} mm; visited "
                         f"{rec['visited_penetration_range_m'][0] * 1e3:.4g}-"
                         f"{rec['visited_penetration_range_m'][1] * 1e3:.4g} mm): the law was extrapolated "
                         f"{'down' if side == 'below' else 'up'} from {end * 1e3:.4g} mm")
    if rec.get("beyond_tilt_range"):
        lines.append(f"the largest tilt in contact {rec['largest_tilt_rad'] / ARCMIN:.4g} arcmin exceeds the tilt the "
                     f"law was checked at ({rec['tilt_range_rad'][1] / ARCMIN:.4g} arcmin): the law was extrapolated")
    return lines


def merged(records) -> dict:
    """One record of several runs of the same law (a branch's orbits, a study's points): the shares weighted by
    each run's contact samples, the visited range and the largest tilt over all of them."""
    recs = [r for r in records if r]
    if not recs:
        return {}
    out = {k: recs[0][k] for k in ("law", "law_name", "law_file", "law_sha256", "verdict", "verdict_reasons",
                                   "penetration_range_m", "tilt_range_rad")}
    n = sum(r["contact_samples"] for r in recs)
    total = sum(r["samples"] for r in recs)
    seen = [r["visited_penetration_range_m"] for r in recs if r["visited_penetration_range_m"]]
    out.update(contact_samples=n, samples=total, contact_time_share=n / total if total else 0.0,
               visited_penetration_range_m=[min(s[0] for s in seen), max(s[1] for s in seen)] if seen else None,
               largest_tilt_rad=max(r["largest_tilt_rad"] for r in recs))
    for side in ("below", "inside", "above"):
        parts = [(r[f"contact_time_share_{side}"], r["contact_samples"]) for r in recs
                 if r[f"contact_time_share_{side}"] is not None]
        out[f"contact_time_share_{side}"] = sum(s * w for s, w in parts) / n if parts and n else None
    flags = [r["beyond_tilt_range"] for r in recs if r["beyond_tilt_range"] is not None]
    out["beyond_tilt_range"] = any(flags) if flags else None
    out["warnings"] = warning_lines(out)
    return out


def law_line(loose, overrides: dict | None = None) -> str:
    """One line naming the loose support's geometry and the law a job runs on, with its verdict and ranges (every
    rotor job prints it once at the start, so a law file that supplied the geometry is seen to have done so).

    ``overrides``: the jobs' overrides as keywords of :func:`rotor.studies.steady_state.point_system`
    (``clearance_m``, ``mu``, ``preload_n``, SI; None or missing: the scene's value)."""
    head = law_header(loose)
    if not head:
        return "no loose support: no contact law"
    ov = {k: v for k, v in (overrides or {}).items() if v is not None}
    c, w = ov.get("clearance_m", loose.clearance_m), loose.ring_width_m
    mu, pre = ov.get("mu", loose.friction_coefficient), ov.get("preload_n", loose.preload_n)
    geo = (f"loose support: clearance {c * 1e3:.4g} mm, ring width {w * 1e3:.4g} mm, bearing E "
           f"{loose.bearing_modulus_pa / 1e9:.4g} GPa nu {loose.bearing_poisson:.3g}, support E "
           f"{loose.support_modulus_pa / 1e9:.4g} GPa nu {loose.support_poisson:.3g}, mu {mu:.3g}, preload {pre:.4g} N; "
           f"law {head['law']}")
    if head["law_file"]:
        geo += f" ({head['law_file']}, sha256 {head['law_sha256'][:12]}...)"
    geo += f": {head['verdict']}"
    if head["penetration_range_m"] is not None:
        lo, hi = head["penetration_range_m"]
        tilt = head["tilt_range_rad"][1]
        geo += (f", fitted for edge penetrations {lo * 1e3:.4g}-{hi * 1e3:.4g} mm, "
                + (f"tilt checked to {tilt / ARCMIN:.4g} arcmin" if tilt > 0 else "tilt never checked (straight ring)"))
    return geo


def stored_point_record(loose, arrays, clearance_m: float) -> dict:
    """The record of a steady-state study point from its stored arrays (``r1``, ``r2``: the ring edges' offsets,
    m; ``u``: the relative support motion with the tilts in columns 2 and 3, rad; the last revolutions of
    :func:`rotor.studies.steady_state.run_point`) and its clearance (m); empty where the point kept no history."""
    if loose is None or any(k not in arrays for k in ("r1", "r2", "u")) or not len(arrays["r1"]):
        return {}
    u = np.asarray(arrays["u"], dtype=float)
    return record(loose, np.maximum(arrays["r1"], arrays["r2"]) - clearance_m, np.hypot(u[:, 2], u[:, 3]))
