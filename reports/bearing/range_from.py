"""The law follows the rotor: a ring-pair file's ``[range]`` widened to what a rotor run visited.

``ringcontact bearing FILE --range-from RUN`` reads the validity record of a rotor run (``law_validity``,
:mod:`rotor.model.law_validity`: the smallest and largest edge penetration while in contact and the largest tilt)
from ``RUN``, which is

- a ``simulate --out`` folder (its ``simulate-summary.json``) or that file,
- a ``study --out`` folder (its ``law-validity.json``) or that file,
- an ``orbit --out`` or ``branch --out`` JSON file;

and widens the file's range to hold it: the visited penetrations divided and multiplied by :data:`MARGIN` (the rotor
moves when its law changes: the rerun on the new law must stay inside), rounded outward to two significant digits,
the tilt likewise, each end only ever moved outward. The file's reference points are kept (an earlier run's FEM
points in the same output folder are read back, not recomputed) and the default grid's points beyond the old range
added (:func:`fem_reference.ring_scene.default_grid`). What the references cannot hold is not asked of them but
said: penetrations below the smallest the FEM resolves for this ring, above the small-strain limit, tilts past the
small-rotation limit or on a hold the 3D reference does not model (``not_reached``).

The widened file is validated as any ring-pair file (:func:`fem_reference.ring_scene.from_document`); its content,
and so its sha256 in the law's provenance, is the widened one.
"""
from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path

from contact.errors import InputError
from contact.plausible import MAX_TILT_ARCMIN
from contact.units import ARCMIN, MM
from fem_reference import ring_scene
from fem_reference.ring_scene import RingScene

#: the visited range widened by this factor at each end (penetration and tilt) before rounding outward
MARGIN = 1.25
#: the files a run folder's record is read from, in this order (simulate, then study)
RECORD_FILES = ("simulate-summary.json", "law-validity.json")
OPTION = "--range-from"


@dataclass(frozen=True)
class Visited:
    """What a rotor run visited in contact, from its ``law_validity`` record.

    Attributes
    ----------
    source : str
        The file read (as found from the option's value).
    sha256 : str
        SHA-256 of that file's bytes.
    law_name : str
        The law the run was made with.
    penetration_m : tuple of float
        Smallest and largest edge penetration while in contact (m).
    tilt_max_rad : float
        Largest relative tilt of the ring while in contact (rad).
    """

    source: str
    sha256: str
    law_name: str
    penetration_m: tuple
    tilt_max_rad: float


def _record_file(text: str) -> Path:
    if not text.strip():
        raise InputError(f"{OPTION} = '': must name a run (a `simulate --out` or `study --out` folder, or a run's "
                         "JSON file)")
    p = Path(text)
    if p.is_dir():
        for name in RECORD_FILES:
            if (p / name).is_file():
                return p / name
        raise InputError(f"{OPTION} = {text}: the folder holds no {' or '.join(RECORD_FILES)} (a `simulate --out` "
                         "or `study --out` folder, or an `orbit`/`branch --out` JSON file)")
    if not p.is_file():
        raise InputError(f"{OPTION} = {text}: {'does not exist' if not p.exists() else 'is not a file or folder'} "
                         "(a `simulate --out` or `study --out` folder, or a run's JSON file)")
    return p


def read_visited(text: str) -> Visited:
    """The visited range of the run ``text`` names (see the module docstring); one-line :class:`InputError` else."""
    path = _record_file(text)
    try:
        data = path.read_bytes()
        doc = json.loads(data.decode("utf-8"))
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise InputError(f"{OPTION} = {text}: {path.name} is not a readable JSON file ({type(exc).__name__})") from None
    rec = doc.get("law_validity") if isinstance(doc, dict) else None
    if not isinstance(rec, dict):
        raise InputError(f"{OPTION} = {text}: {path.name} has no law_validity record (the output of a rotor job: "
                         "simulate, orbit, branch or study)")
    return visited_from_record(rec, str(path), hashlib.sha256(data).hexdigest(), f"{OPTION} = {text}")


def visited_from_record(rec: dict, source: str, sha256: str, where: str) -> Visited:
    """The visited range of a ``law_validity`` record (``source`` and its ``sha256`` name it; ``where`` starts a
    refusal's one line: the option or keyword with the value as given)."""
    if not rec:
        raise InputError(f"{where}: the run has no loose support, so no contact to take a range from")
    seen, tilt = rec.get("visited_penetration_range_m"), rec.get("largest_tilt_rad")
    if seen is None:
        raise InputError(f"{where}: the ring never touched its support in this run (contact_time_share "
                         f"{rec.get('contact_time_share')}): no visited range to take")
    try:
        lo, hi, tilt = float(seen[0]), float(seen[1]), float(tilt or 0.0)
    except (TypeError, ValueError, IndexError):
        raise InputError(f"{where}: visited_penetration_range_m = {seen!r} m, largest_tilt_rad = {tilt!r} "
                         "rad: must be numbers [low, high] and one number") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and math.isfinite(tilt) and 0 < lo <= hi and tilt >= 0):
        raise InputError(f"{where}: visited_penetration_range_m = [{lo:g}, {hi:g}] m, largest_tilt_rad = "
                         f"{tilt:g} rad: must be 0 < low <= high and a tilt >= 0")
    return Visited(source, sha256, str(rec.get("law_name")), (lo, hi), tilt)


def _round(v: float, up: bool) -> float:
    """``v`` > 0 rounded outward (``up``: towards +inf) to two significant digits."""
    e = 10.0 ** (math.floor(math.log10(v)) - 1)
    k = v / e
    k = math.ceil(k - 1e-9) if up else math.floor(k + 1e-9)
    return float(f"{k * e:.3g}")


def _grown(old: list, grid: list, lo: float, hi: float) -> list:
    """The points ``old`` and those of ``grid`` outside ``[lo, hi]`` (sorted, no repeats)."""
    return sorted(set(old) | {v for v in grid if v < lo * (1 - 1e-12) or v > hi * (1 + 1e-12)})


def _tilt_range(rs: RingScene, t_lo: float, t_hi: float, want: float, notes: list) -> float:
    """The new largest tilt (arcmin) for a visited tilt ``want`` (arcmin, margin included), notes of what is not."""
    if want <= t_hi:
        return t_hi
    if (rs.scene.support_hold, rs.scene.bearing_drive) not in ring_scene.HOLDS_3D:
        notes.append(f"tilts 0-{want:.3g} arcmin: the 3D reference models only rings held the same all round, not "
                     f"hold {rs.scene.support_hold!r} with drive {rs.scene.bearing_drive!r}: no tilt reference")
        return t_hi
    if want > MAX_TILT_ARCMIN:
        notes.append(f"tilts {MAX_TILT_ARCMIN:g}-{want:.3g} arcmin: past the small-rotation model's "
                     f"{MAX_TILT_ARCMIN:g} arcmin: no reference")
    return min(want, MAX_TILT_ARCMIN)


def _penetration_range(rs: RingScene, lo: float, hi: float, want: tuple, tilt: bool, notes: list) -> tuple:
    """The new penetration range (mm) for the visited one ``want`` (mm, margin included), notes of what is not."""
    doc = rs.document
    c_mm, ro_mm = doc["housing"]["radial_clearance_mm"], doc["bearing_ring"]["outer_radius_mm"]
    least = ring_scene.smallest_penetration_mm(c_mm, ro_mm, tilt)
    floor, ceil = _round(least, up=True), ring_scene.largest_penetration_mm(ro_mm)
    new_lo, new_hi = min(lo, want[0]), max(hi, want[1])
    if new_lo < least:
        notes.append(f"penetrations {new_lo:.3g}-{floor:.3g} mm: below the smallest the FEM references resolve for "
                     f"this ring ({floor:.3g} mm{', with tilt' if tilt else ''}): no reference")
        new_lo = min(lo, floor) if lo >= least else floor
    if new_hi > ceil:
        notes.append(f"penetrations {ceil:.3g}-{new_hi:.3g} mm: past the small-strain limit ({ceil:.3g} mm): "
                     "no reference")
        new_hi = ceil
    return new_lo, new_hi


def widened(rs: RingScene, seen: Visited) -> tuple[RingScene, dict]:
    """``rs`` with its range widened to hold ``seen`` (see the module docstring) and a note of what was done.

    Returns
    -------
    scene : RingScene
        The widened ring pair (validated; ``source`` names the run it was widened by).
    note : dict
        ``source``, ``source_sha256``, ``run_law``, ``visited_penetration_mm``, ``visited_tilt_max_arcmin``, ``margin``,
        ``penetration_mm`` and ``tilt_arcmin`` (before → after, ``[low, high]`` each), ``not_reached`` (sentences).
    """
    rng = rs.document["range"]
    lo, hi = rng["penetration_mm"]
    t_lo, t_hi = rng["tilt_arcmin"]
    notes: list[str] = []
    want_t = _round(seen.tilt_max_rad * MARGIN / ARCMIN, up=True) if seen.tilt_max_rad > 0 else 0.0
    new_t = _tilt_range(rs, t_lo, t_hi, want_t, notes)
    want_p = (_round(seen.penetration_m[0] / MARGIN / MM, up=False), _round(seen.penetration_m[1] * MARGIN / MM, up=True))
    new_lo, new_hi = _penetration_range(rs, lo, hi, want_p, new_t > 0, notes)
    new_rng = {"penetration_mm": [new_lo, new_hi], "tilt_arcmin": [t_lo, new_t],
               "penetration_points_mm": _grown(rng["penetration_points_mm"], ring_scene.default_grid(new_lo, new_hi, 10),
                                               lo, hi)}
    if new_t > 0:
        old3 = rng.get("penetration_points_3d_mm") or []
        new_rng["penetration_points_3d_mm"] = _grown(old3, ring_scene.default_grid(new_lo, new_hi, 6),
                                                     *((lo, hi) if old3 else (math.inf, -math.inf)))
        tilts = sorted({0.0, t_lo, new_t / 4, new_t / 2, new_t} - ({0.0} if t_lo > 0 else set()))
        old_t = rng.get("tilt_points_arcmin") or []
        new_rng["tilt_points_arcmin"] = _grown(old_t, [float(f"{v:.3g}") for v in tilts],
                                               *((t_lo, t_hi) if old_t else (math.inf, -math.inf)))
    doc = {**rs.document, "range": new_rng}
    out = ring_scene.from_document(doc, f"{rs.source} (range from {seen.source})")
    note = {"source": seen.source, "source_sha256": seen.sha256, "run_law": seen.law_name,
            "visited_penetration_mm": [v / MM for v in seen.penetration_m],
            "visited_tilt_max_arcmin": seen.tilt_max_rad / ARCMIN, "margin": MARGIN,
            "penetration_mm": {"before": [lo, hi], "after": [new_lo, new_hi]},
            "tilt_arcmin": {"before": [t_lo, t_hi], "after": [t_lo, new_t]}, "not_reached": notes}
    return out, note


def note_lines(note: dict) -> list[str]:
    """The note of :func:`widened` as sentences (terminal and report)."""
    p, t = note["penetration_mm"], note["tilt_arcmin"]
    vis = note["visited_penetration_mm"]
    lines = [f"range from {note['source']} (law {note['run_law']}): visited penetrations {vis[0]:.4g}-{vis[1]:.4g} mm, "
             f"tilt up to {note['visited_tilt_max_arcmin']:.4g} arcmin; with a margin of x{note['margin']:g}: "
             f"penetration {p['before'][0]:g}-{p['before'][1]:g} -> {p['after'][0]:g}-{p['after'][1]:g} mm, "
             f"tilt {t['before'][0]:g}-{t['before'][1]:g} -> {t['after'][0]:g}-{t['after'][1]:g} arcmin"]
    lines += [f"not reached: {n}" for n in note["not_reached"]]
    return lines
