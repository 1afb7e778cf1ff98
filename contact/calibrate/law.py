"""The stored object: a calibrated law as held in ``contact/calibrated/<name>.json``.

:class:`CalibratedLaw` evaluates the fitted family (straight and tilted ring), gives the slots of
the compiled loose-support kernel and (de)serialises itself; :class:`CalibratedSupportParams` is
the rotor's loose support with that law.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from contact import laws
import contact.calibrate.spline as spline
from contact.calibrate.families import KERNEL_LAW_CODE, SceneGeometry, family_force
from contact.calibrate.validate import check_behaviour, check_document
from contact.dataset import check_document_sha256, document_sha256
from contact.errors import DatasetError, InputError
from contact.calibrate.tilt_correction import TiltCorrection
from contact.loose_support import N_SPLINE_SLOTS, N_TILT_SLOTS, SPLINE_SLOT, TILT_SLOT, LooseSupportParams

SCHEMA = "ringcontact/calibrated-law"
VERSION = 1


@dataclass(frozen=True)
class CalibratedLaw:
    """A calibrated law as stored in ``contact/calibrated/<name>.json`` (SI).

    Attributes
    ----------
    name : str
        ``<scene>-<family>``, e.g. ``"clamped-foundation"``.
    scene : str
        FEM boundary-condition scene the law was fitted to.
    family : str
        One of :data:`FAMILIES`.
    parameters, parameter_std, parameter_units : dict
        Fitted values, 1σ standard deviations, units.
    geometry : SceneGeometry
        Clearance, width, radius, materials and plane of the scene.
    validity_penetration_m : tuple(float, float)
        Range of penetrations (m) of the fitted points; zero tilt.
    dataset : dict
        ``path`` (repo-relative), ``points_sha256``, ``created_utc``, ``code_revision`` of the source.
    fit : dict
        Per-point penetration, FEM force, fit and leave-one-out errors; the family comparison.
    validity_tilt_max_rad : float
        Largest tilt (rad) the law was checked at against a 3D reference (0: straight ring only).
    provenance : dict
        Optional: where the law came from beyond its dataset (a ring-pair file's name and sha256,
        the code version, the checks made; written by ``ringcontact bearing``, reports/bearing/).
    """

    name: str
    scene: str
    family: str
    parameters: dict
    parameter_std: dict
    parameter_units: dict
    geometry: SceneGeometry
    validity_penetration_m: tuple
    dataset: dict
    fit: dict = field(default_factory=dict)
    validity_tilt_max_rad: float = 0.0
    provenance: dict = field(default_factory=dict)

    def force(self, penetration_m, *, strict: bool = False) -> laws.LawResult:
        """Line-contact force (N) at penetrations Δr (m).

        Points above the validity range are flagged (``in_domain`` False, force NaN) or, with
        ``strict``, raise :class:`~contact.errors.OutsideDomainError`. Δr <= 0 gives 0.
        """
        check = np.asarray(penetration_m, dtype=float)
        laws._penetration(check)
        ok = check <= self.validity_penetration_m[1] * (1 + 1e-12)
        f = family_force(self.family, self.parameters, check, self.geometry)
        res = laws.LawResult(np.where(ok, f, np.nan), np.asarray(ok), f"calibrated:{self.name}")
        if strict:
            res.require_in_domain(check)
        return res

    def force_per_length(self, penetration_m) -> np.ndarray:
        """Force per unit axial length (N/m) at penetration Δr (m), no validity check (0 for Δr <= 0)."""
        return family_force(self.family, self.parameters, penetration_m, self.geometry) / self.geometry.width_m

    def tilted(self, penetration_m: float, tilt_rad: float, *, n_gauss: int = 48) -> tuple[float, float, float]:
        """Slice-integrated force of a tilted ring: each axial slice carries the 2D law of its own penetration.

        The ring centre is at ``y = δ0 + Δr`` and the tilt ``θ`` is about z, so the slice at axial
        position x has ``Δr(x) = Δr + θx`` on the +y side and ``−2δ0 − Δr − θx`` on the −y side
        (small angles, docs/reference/contact-laws.md §1, §8). ``P = ∫ h(Δr(x)) dx`` and ``M_z = Σ x F_y`` over the
        contact, by Gauss–Legendre quadrature on each contact interval (exact for a Winkler bed,
        whose slices are independent; Johnson 1985 §4.3). This is the calibrated law's tilt
        model; the paper's edge/patch model (Eqs. 8–19) is the compiled kernel's.

        Returns
        -------
        load_N : float
            ``−F_y`` on the bearing (N), positive when the +y side carries the load.
        moment_z_Nm : float
            ``M_z`` of the contact force about the ring centre (N·m), ``Σ x F_y``.
        width_m : float
            Axial length of the contact on the +y side (m).
        """
        laws._penetration(penetration_m)
        check = np.asarray(tilt_rad, dtype=float)
        laws.check_finite("tilt_rad", check, "rad")
        g = self.geometry
        half = 0.5 * g.width_m
        pen, th = float(penetration_m), float(tilt_rad)
        xg, wg = np.polynomial.legendre.leggauss(n_gauss)

        def side(depth0: float, slope: float, sign: float):
            # contact where depth0 + slope*x > 0 on [-half, half]; returns (∫h, ∫x h, length)
            if slope == 0.0:
                return (g.width_m * float(self.force_per_length(depth0)), 0.0, g.width_m) if depth0 > 0 else (0.0, 0.0, 0.0)
            x0 = -depth0 / slope
            a, b = (max(-half, x0), half) if slope > 0 else (-half, min(half, x0))
            if b <= a:
                return 0.0, 0.0, 0.0
            x = 0.5 * (b - a) * xg + 0.5 * (a + b)
            h = self.force_per_length(depth0 + slope * x)
            w = 0.5 * (b - a) * wg
            return float(w @ h), float(w @ (x * h)), b - a

        f_plus, m_plus, width = side(pen, th, 1.0)
        f_minus, m_minus, _ = side(-2.0 * g.clearance_m - pen, -th, -1.0)
        fy = -f_plus + f_minus                  # force on the bearing
        mz = -m_plus + m_minus                  # M_z = Σ x F_y
        return -fy, mz, width

    def kernel_law(self) -> tuple:
        """Kernel law slots ``(code, slot 3, slot 6, slot 7)`` of ``contact._kernel`` for this law, followed for
        ``foundation-spline`` (code 3) by its knots (the kernel's slots 15 on, :func:`contact.calibrate.spline.
        kernel_slots`), and for a law with a tilt correction by the spline slots (zeros for code 2) and the
        correction's (slots 88 on, :meth:`contact.calibrate.tilt_correction.TiltCorrection.kernel_slots`).

        Raises
        ------
        InputError
            for the ``conformal-compliance`` family (implicit in Δr; not in the compiled kernel).
        """
        g = self.geometry
        if self.family not in KERNEL_LAW_CODE:
            raise InputError(f"calibrated law {self.name!r}: family {self.family!r} is implicit in the penetration "
                             "and not available in the compiled loose-support kernel (families usable by the rotor: "
                             f"{', '.join(KERNEL_LAW_CODE)})")
        if self.family == "conformal-scaled":
            return (0.0, self.parameters["stiffness_factor"] * 2.0 * math.pi * g.e_star_Pa * g.clearance_m, 0.0, 1.0)
        if self.family == "power":
            return (1.0, 0.0, self.parameters["coefficient_N_per_m_pow_n_plus_1"], self.parameters["exponent"])
        tilt = TiltCorrection.from_parameters(self.parameters)
        if self.family == spline.FAMILY:
            out = (3.0, 0.0, g.radius_m, 0.0, *spline.kernel_slots(self.parameters))
        else:
            out = (2.0, 0.0, self.parameters["foundation_modulus_Pa_per_m"] * g.radius_m, 0.0)
        if tilt is None:
            return out
        return out + (0.0,) * (4 + N_SPLINE_SLOTS - len(out)) + tilt.kernel_slots()

    def loose_support_params(self, **overrides) -> "CalibratedSupportParams":
        """The loose support of the rotor with this law (other fields as in ``LooseSupportParams``).

        Clearance, width and materials come from the calibration; passing a different
        ``clearance_m`` or ``width_m`` raises :class:`InputError` (the law holds for its scene only).
        """
        g = self.geometry
        kernel_law = self.kernel_law()
        for key, val in (("clearance_m", g.clearance_m), ("width_m", g.width_m)):
            if key in overrides and not math.isclose(overrides[key], val, rel_tol=1e-9):
                raise InputError(f"{key} = {overrides[key]:g} m: calibrated law {self.name!r} holds for "
                                 f"{key} = {val:g} m only (refit it for another geometry)")
        values = dict(clearance_m=g.clearance_m, width_m=g.width_m, bearing_E_Pa=g.bearing_E_Pa,
                      bearing_nu=g.bearing_nu, support_E_Pa=g.support_E_Pa, support_nu=g.support_nu,
                      law="pereira" if self.family == "power" else "conformal",
                      modulus=g.modulus if self.family != "power" else None,
                      calibration_name=self.name, calibrated_kernel_law=kernel_law)
        values.update(overrides)
        return CalibratedSupportParams(**values)

    # ---- (de)serialisation -------------------------------------------------------------
    def to_json(self) -> str:
        doc = {"schema": SCHEMA, "version": VERSION, "name": self.name, "scene": self.scene,
               "family": self.family, "parameters": self.parameters, "parameter_std": self.parameter_std,
               "parameter_units": self.parameter_units, "geometry": self.geometry.to_dict(),
               "validity": {"penetration_min_m": self.validity_penetration_m[0],
                            "penetration_max_m": self.validity_penetration_m[1], "tilt_rad": 0.0},
               "dataset": self.dataset, "fit": self.fit}
        if self.validity_tilt_max_rad:
            doc["validity"]["tilt_max_rad"] = self.validity_tilt_max_rad
        if self.provenance:
            doc["provenance"] = self.provenance
        doc = _round_floats(doc)
        doc["sha256"] = document_sha256(doc)      # whole-file checksum: an edited modulus is refused on load
        return json.dumps(doc, indent=1, allow_nan=False) + "\n"

    @classmethod
    def from_json(cls, text: str, source: str = "<string>") -> "CalibratedLaw":
        try:
            doc = json.loads(text)
        except (json.JSONDecodeError, RecursionError) as exc:     # RecursionError: nested beyond any law file
            raise DatasetError(f"{source}: not valid JSON (or nested too deeply): {str(exc)[:120]}") from None
        if not isinstance(doc, dict) or doc.get("schema") != SCHEMA or doc.get("version") != VERSION:
            raise DatasetError(f"{source}: not a {SCHEMA} v{VERSION} file")
        check_document_sha256(doc, source)      # accidents only: the content is checked as any input
        fields = check_document(doc, source)      # every field's type and range, one-line DatasetError
        law = cls(**{**fields, "geometry": SceneGeometry(**fields["geometry"])})
        check_behaviour(law, source)              # finite, > 0 and rising over its validity range
        return law


def _round_floats(obj, digits: int = 12):
    """Floats to ``digits`` significant digits so that a refit writes byte-identical files."""
    if isinstance(obj, float):
        return float(f"{obj:.{digits}g}")
    if isinstance(obj, dict):
        return {k: _round_floats(v, digits) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_round_floats(v, digits) for v in obj]
    if isinstance(obj, np.ndarray):
        return _round_floats(obj.tolist(), digits)
    if isinstance(obj, np.floating):
        return _round_floats(float(obj), digits)
    return obj


@dataclass(frozen=True)
class CalibratedSupportParams(LooseSupportParams):
    """:class:`~contact.loose_support.LooseSupportParams` whose radial law is a calibrated one.

    Identical to its base for damping, friction, tilt geometry and validation; only the law
    slots of the compiled kernel (``kernel_args`` 2, 3, 6, 7, 15 on for a spline, 88 on for a tilt correction) come
    from ``calibrated_kernel_law``
    (see :meth:`CalibratedLaw.kernel_law`). ``law`` keeps the base family for validation
    ("pereira" for a power law, "conformal" otherwise); ``calibration_name`` says which law is used.
    """

    calibration_name: str = ""
    calibrated_kernel_law: tuple = ()

    def __post_init__(self):
        super().__post_init__()
        k = tuple(self.calibrated_kernel_law)
        size = 4 + (N_SPLINE_SLOTS if k and k[0] == 3.0 else 0)
        tilted = bool(k) and k[0] in (2.0, 3.0) and len(k) == 4 + N_SPLINE_SLOTS + N_TILT_SLOTS
        if (len(k) != size and not tilted) or k[0] not in (0.0, 1.0, 2.0, 3.0) or not all(math.isfinite(v) for v in k):
            raise InputError(f"calibrated_kernel_law = {str(self.calibrated_kernel_law)[:80]}: need (code 0/1/2/3, "
                             f"slot 3, slot 6, slot 7, and for code 3 the {N_SPLINE_SLOTS} spline slots, for codes 2 "
                             f"and 3 with a tilt correction the spline slots and its {N_TILT_SLOTS}), finite")
        if not self.calibration_name:
            raise InputError("calibration_name = '': name the calibrated law")

    @cached_property
    def kernel_args(self) -> tuple:
        args = list(LooseSupportParams.kernel_args.func(self))
        code, s3, s6, s7 = (float(v) for v in self.calibrated_kernel_law[:4])
        args[2] = code
        if code == 0.0:
            args[3] = s3
        else:
            args[6], args[7] = s6, s7
        if code == 3.0:
            args[SPLINE_SLOT:SPLINE_SLOT + N_SPLINE_SLOTS] = [float(v) for v in
                                                              self.calibrated_kernel_law[4:4 + N_SPLINE_SLOTS]]
        if len(self.calibrated_kernel_law) > 4 + N_SPLINE_SLOTS:        # a tilt correction (contact._kernel_tilt)
            assert len(args) == TILT_SLOT
            args += [float(v) for v in self.calibrated_kernel_law[4 + N_SPLINE_SLOTS:]]
        return tuple(args)

    @cached_property
    def neat_fit_limit_m(self) -> float:
        if float(self.calibrated_kernel_law[0]) != 0.0:
            return math.inf
        return LooseSupportParams.neat_fit_limit_m.func(self)
