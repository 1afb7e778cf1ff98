"""Contact laws from Python: evaluate a law (force and moment against penetration and tilt), and calibrate one
from a ring-pair file (``ringcontact bearing``).

:func:`law` evaluates as ``ringcontact law`` does (:func:`reports.cli.law.evaluate`: the analytic laws of
Dai et al. 2025 with the tilt geometry of their Eqs. 8-19, or a calibrated law's slice-integrated tilt model);
:func:`bearing` runs the stages of :mod:`reports.bearing.pipeline` (2D FEM sweep, 3D tilt sweep where the
ring-pair file asks for tilt, calibration with held-out points, accuracy report, law file).
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from contact.errors import InputError
import ringcontact._checks as _checks
from ringcontact.results import ResultMethods, internal

MM, GPA = 1e-3, 1e9
ARCMIN = math.pi / 10800.0


@dataclass(frozen=True)
class LawResult(ResultMethods):
    """A contact law at points (penetration, tilt): ``force_N`` and ``moment_Nm`` (NaN outside the law's
    domain, ``in_domain`` False there), the contact's axial ``contact_width_m``, its ``state`` (``line``,
    ``edge1``, ``two_point``, ``none`` …), and the geometry the law was evaluated for."""

    law: str
    penetration_m: np.ndarray
    tilt_rad: np.ndarray
    force_N: np.ndarray
    moment_Nm: np.ndarray
    contact_width_m: np.ndarray
    in_domain: np.ndarray
    state: tuple
    clearance_m: float
    width_m: float
    _dim = "point"

    def _rows(self) -> list[dict]:
        return [{"penetration_m": p, "tilt_rad": self.tilt_rad[i], "force_N": self.force_N[i],
                 "moment_Nm": self.moment_Nm[i], "contact_width_m": self.contact_width_m[i],
                 "in_domain": bool(self.in_domain[i]), "state": self.state[i]} for i, p in enumerate(self.penetration_m)]

    def _draw(self, ax) -> None:
        for tilt in np.unique(self.tilt_rad):
            pick = self.tilt_rad == tilt
            order = np.argsort(self.penetration_m[pick])
            ax.plot(self.penetration_m[pick][order] / MM, self.force_N[pick][order] / 1e3, "-o", ms=3,
                    label=f"tilt {tilt / ARCMIN:g} arcmin")
        ax.set_xlabel("penetration Δr (mm)")
        ax.set_ylabel("radial contact force (kN)")
        ax.set_title(f"Contact law {self.law}: clearance {self.clearance_m / MM:g} mm, width {self.width_m / MM:g} mm",
                     fontsize=10)
        ax.legend(fontsize=8)


def law(name: str = "conformal", penetration_m=1e-5, tilt_rad=0.0, *, clearance_m: float | None = None,
        width_m: float | None = None, bearing_modulus_pa: float | None = None, bearing_poisson: float | None = None,
        support_modulus_pa: float | None = None, support_poisson: float | None = None, modulus: str | None = None,
        penetration_at: str = "centre") -> LawResult:
    """Evaluate a contact law at ``penetration_m`` (m) and ``tilt_rad`` (rad), broadcast against each other.

    Parameters
    ----------
    name : str
        An analytic law (``conformal`` … as ``ringcontact law --law``), ``calibrated:<name>`` or a law file's path.
    penetration_m, tilt_rad : float or array
        Penetration ``Δr = |r| − δ0`` (m) at the ring's centre plane (``penetration_at="edge"``: at the leading
        edge) and relative tilt (rad).
    clearance_m, width_m, bearing_modulus_pa, bearing_poisson, support_modulus_pa, support_poisson : float
        Geometry and materials of an analytic law (None: Dai et al. 2025, Table 1); a calibrated law has its
        own (a different value is refused).
    modulus : str or None
        The 2D idealisation of an analytic law (``plane_stress`` …; None: the law's default).
    """
    from reports.cli.law import MAX_POINTS, evaluate
    if not isinstance(name, (str, os.PathLike)):
        raise InputError(f"name = {name!r}: must name a law (conformal …, calibrated:<name> or a law file's path)")
    pen_m = _checks.numbers_in("penetration_m", penetration_m, "--penetration-mm", "penetration_mm", MM, "m")
    tilt = _checks.numbers_in("tilt_rad", tilt_rad, "--tilt-arcmin", "tilt_arcmin", ARCMIN, "rad")
    try:
        pen, tilt = (np.asarray(a, dtype=float).ravel() for a in np.broadcast_arrays(pen_m, tilt))
    except ValueError:
        raise InputError(f"penetration_m {np.shape(pen_m)} and tilt_rad {np.shape(tilt)}: shapes that do not "
                         "broadcast against each other") from None
    if pen.size > MAX_POINTS:
        raise InputError(f"penetration_m x tilt_rad: {pen.size} points, more than the {MAX_POINTS} of ringcontact law "
                         "(call contact.tilt.aligned_tilt_contact for a batch)")
    given = {"clearance_mm": clearance_m, "width_mm": width_m, "bearing_E_GPa": bearing_modulus_pa,
             "bearing_nu": bearing_poisson, "support_E_GPa": support_modulus_pa, "support_nu": support_poisson}
    scale = {"clearance_mm": MM, "width_mm": MM, "bearing_E_GPa": GPA, "support_E_GPa": GPA}
    for (key, v), kw in zip(given.items(), ("clearance_m", "width_m", "bearing_modulus_pa", "bearing_poisson",
                                            "support_modulus_pa", "support_poisson")):
        if v is not None:
            row = "E_GPa" if key.endswith("GPa") else "nu" if key.endswith("nu") else key
            _checks.number(kw, v, "--" + key.replace("_", "-"), row, scale.get(key, 1.0),
                           {"clearance_mm": "m", "width_mm": "m"}.get(key, "Pa" if row == "E_GPa" else ""))
    args = SimpleNamespace(law=str(name), modulus=modulus, beta_reading="zero", penetration_at=penetration_at,
                           **{k: None if v is None else float(v) / scale.get(k, 1.0) for k, v in given.items()})
    points = evaluate(args, pen / MM, tilt / ARCMIN)

    def col(key):
        return np.array([np.nan if p[key] is None else float(p[key]) for p in points])

    return LawResult(str(name), pen, tilt, col("force_N"), col("moment_Nm"), col("contact_width_m"),
                     np.array([not p["outside_domain"] for p in points]), tuple(p["state"] for p in points),
                     args.clearance_mm * MM, args.width_mm * MM)


@dataclass(frozen=True)
class BearingResult(ResultMethods):
    """A ring-pair file calibrated to a contact law (``ringcontact bearing``): the law file written
    (``law_file``, what a rotor scene names in ``[loose_support] law``), its family and parameters, the
    penetration range it was fitted on (m), the tilt it was checked at against the 3D reference (rad),
    the checks and warnings. :meth:`evaluate` evaluates the law (:func:`law`)."""

    ring_scene: str
    law_file: str
    law_name: str
    family: str
    parameters: dict
    validity_penetration_m: tuple
    validity_tilt_max_rad: float
    warnings: tuple
    summary: dict
    calibrated: object = internal()
    _dim = "parameter"

    def evaluate(self, penetration_m, tilt_rad=0.0) -> LawResult:
        """The law at ``penetration_m`` (m) and ``tilt_rad`` (rad), see :func:`law`."""
        return law(self.law_file, penetration_m, tilt_rad)

    def _rows(self) -> list[dict]:
        return [{"parameter": k, "value": v} for k, v in self.parameters.items()]

    def _draw(self, ax) -> None:
        lo, hi = self.validity_penetration_m
        self.evaluate(np.linspace(max(lo, 0.0), hi, 40))._draw(ax)


def _widened(rs, range_from):
    """``(rs, note)``: ``rs`` widened to the run ``range_from`` visited (a path or a result), or as it is."""
    import hashlib
    import json

    from reports.bearing.range_from import read_visited, visited_from_record, widened
    if range_from is None:
        return rs, None
    if isinstance(range_from, (str, os.PathLike)):
        return widened(rs, read_visited(os.fspath(range_from)))
    rec = getattr(range_from, "law_validity", None)
    if not isinstance(rec, dict):
        raise InputError(f"range_from = {type(range_from).__name__}: must be a run folder or JSON file, or a result of "
                         "simulate, orbit, branch or cascade (with its law_validity)")
    text = json.dumps(rec, sort_keys=True, allow_nan=False)
    where = f"range_from = {type(range_from).__name__}"
    return widened(rs, visited_from_record(rec, where, hashlib.sha256(text.encode()).hexdigest(), where))


def bearing(ring_scene: str | os.PathLike, out: str | os.PathLike | None = None, *, workers: int = 1,
            fresh: bool = False, progress: bool | None = None, log=print, range_from=None,
            plane_check: bool | None = None) -> BearingResult:
    """Calibrate the contact law of a ring-pair file (schema ``ringcontact.ring-scene/1``) or a bundled one by
    name (``clamped``, ``steel-in-aluminium`` …), as ``ringcontact bearing``: FEM reference points, law
    families fitted with held-out points, report and law file in ``out`` (default ``bearing-<name>``). An
    interrupted run resumes where it stopped (``fresh`` starts over). Minutes of FEM on ``workers`` processes.

    ``range_from``: as ``--range-from``, the file's range widened to what a rotor run visited in contact
    (:mod:`reports.bearing.range_from`): a run folder or JSON file, or a result of :func:`simulate`, :func:`orbit`,
    :func:`branch` or :func:`cascade` (its ``law_validity``). ``plane_check``: as ``--plane-check`` (True) or
    ``--no-plane-check`` (False); None: the 3D check of the plane runs for a file left at ``plane = "auto"`` and for
    a tilt range (the summary's ``plane``: the plane used, why, and the 3D numbers).
    """
    from contact.calibrate.store import load_law_file
    from fem_reference.ring_scene import load
    from reports.bearing.pipeline import run

    if int(workers) != workers or not 1 <= workers <= 64:
        raise InputError(f"workers = {workers}: must be a whole number of processes, 1 to 64")
    rs = load(ring_scene)
    rs, note = _widened(rs, range_from)
    folder = Path(out) if out is not None else Path(f"bearing-{rs.name}")
    summary = run(rs, folder, workers=int(workers), fresh=fresh, progress=progress, log=log, range_from=note,
                  plane_check=plane_check)
    path = folder / summary["law_file"]
    cal = load_law_file(path)
    return BearingResult(rs.name, str(path.resolve()), cal.name, cal.family, dict(cal.parameters),
                         tuple(float(v) for v in cal.validity_penetration_m), float(cal.validity_tilt_max_rad),
                         tuple(summary["warnings"]), summary, cal)
