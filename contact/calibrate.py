"""Calibrated contact laws: fitted to a named FEM scene, stored as data, loaded by name.

The conformal law (Dai et al. 2025 Eq. 5; Persson 1964; Ciavarella & Decuzzi 2001) is exact
for a pin in an infinite plate. Real rings between a shaft and a housing are stiffer or softer:
the reference FEM (``fem_reference``, scenes ``clamped``, ``clamped-stress``, ``persson-*``)
measures how much, per boundary-condition scene. This module fits, per scene, the law with the
**fewest parameters the data justify**, each parameter with a physical meaning:

``conformal-scaled`` (1 parameter)
    ``P = s · P_conformal(Δr)``: a stiffness (modulus) factor ``s`` on the conformal law with
    the scene's own composite modulus (plane strain or plane stress).
``foundation`` (1 parameter)
    Winkler elastic foundation (Johnson 1985, *Contact Mechanics*, §4.3 "elastic foundation
    model"): the two rings act as a bed of independent springs of modulus ``k_f`` (Pa/m)
    between a rigid shaft and a rigid housing. The overlap of the rigid circles at polar angle
    φ is ``e cos φ − δ0`` (``e = δ0 + Δr``), so the pressure is ``k_f (e cos φ − δ0)`` on
    ``|φ| < ε``, ``cos ε = δ0/e``, and the resultant is
    ``P = k_f R l e (ε − sin ε cos ε)``, ``R`` the contact radius, ``l`` the width. For thin
    rings clamped on their far faces ``k_f`` should be the constrained (oedometric) modulus
    over the total ring thickness, ``M/(h_b + h_s)``; the fit is compared with that.
``conformal-compliance`` (1 parameter)
    The conformal law's force–angle relation (exact for a pin in an infinite plate) with the
    penetration of a finite body: the rigid overlap ``δ0(sec ε − 1)`` plus the elastic approach
    of the contact in series, ``P/(π E* l) · (2 ln(1/sin ε) + C)``. The ``2 ln`` term is the
    logarithm of 2D contact mechanics (the approach of a line contact of half-width ``R sin ε``,
    Johnson 1985 §5.6); the dimensionless ``C`` lumps the far field (support size and how it is
    held). ``P(Δr)`` is the root of a monotone equation in ``b² = tan²(ε/2)`` (bisection), so
    this family is not available in the compiled kernel.
``power`` (2 parameters)
    ``P = C · l · Δr^n``: the form of Pereira et al. (2015) with its constants refitted.

Fitting is linear least squares in log force (every family is ``log P = base(Δr) + Xθ``), so
each fit is exact and the parameter covariance is the classical ``s²(XᵀX)⁻¹`` with ``s²`` the
residual variance: the uncertainty reflects how well the family describes the FEM, not only
the FEM's own (much smaller) discretisation error. Hold-out validation is leave-one-out: each
point is predicted by a fit that never saw it. Selection: the 1-parameter family with the
smallest leave-one-out RMS error is kept unless a 2-parameter family at least halves that
error (:data:`SELECTION_GAIN`).

A calibration is stored as JSON in ``contact/calibrated/<name>.json`` (parameters with their
standard deviations and units, the scene and its geometry, the range of validity, the dataset
file, its checksum and code revision, the fit and hold-out errors, the family comparison) and
loaded with :func:`load_calibrated`. :meth:`CalibratedLaw.loose_support_params` turns it into
:class:`CalibratedSupportParams`, a :class:`~contact.loose_support.LooseSupportParams` that the
rotor solver uses like any other (same compiled kernel; the ``foundation`` family is the
kernel's law code 2, see ``contact._kernel``). Under tilt, a calibrated law is evaluated slice by
slice along the ring width (:meth:`CalibratedLaw.tilted`; the kernel does the same for code 2),
not with the paper's edge-penetration × patch-length rule: for a Winkler bed every axial slice
carries the load of its own penetration. The ``power`` family goes through the kernel's Pereira
branch and keeps the paper's tilt rule.

Example::

    from contact.calibrate import load_calibrated
    from rotor.dynamics.kernels import support_law_from_params
    law = load_calibrated("clamped")                  # -> "clamped-foundation"
    params = law.loose_support_params(c_c_s_per_m=100.0, mu=0.3, preload_N=5000.0)
    support_law = support_law_from_params(params)     # pass as system_from_model(..., law=support_law)

``ringcontact calibrate`` (``main``) refits every scene of the committed 2D dataset and writes
the files; ``--check`` only compares the stored files with a fresh fit.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from contact import laws
from contact.dataset import ReferenceDataset, read_dataset
from contact.errors import DatasetError, InputError, RingContactError
from contact.files import atomic_write_text
from contact.loose_support import LooseSupportParams

SCHEMA = "ringcontact/calibrated-law"
VERSION = 1
REPO_ROOT = Path(__file__).resolve().parents[1]
DATASET_2D = REPO_ROOT / "fem_reference" / "data" / "fem2d-reference.json"
DATA_3D_DIR = REPO_ROOT / "fem_reference" / "data" / "3d"
CALIBRATED_DIR = Path(__file__).resolve().parent / "calibrated"
SELECTION_GAIN = 2.0          # a k+1-parameter family must at least halve the held-out RMS error
FAMILIES = ("conformal-scaled", "foundation", "conformal-compliance", "power")
LINEAR_FAMILIES = ("conformal-scaled", "foundation", "power")       # log P linear in the fit coordinates
KERNEL_LAW_CODE = {"conformal-scaled": 0.0, "power": 1.0, "foundation": 2.0}


# --------------------------------------------------------------------------------------------
# the families: log P = base(Δr) + X θ
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class SceneGeometry:
    """What a calibrated law needs to know about its scene (SI).

    clearance_m, width_m : float
        Radial clearance δ0 and ring width l0 (m).
    radius_m : float
        Contact radius R (m): the bearing ring's outer radius.
    bearing_thickness_m, support_thickness_m : float
        Radial thickness of the two rings (m); only for the foundation modulus estimate.
    bearing_E_Pa, bearing_nu, support_E_Pa, support_nu : float
        Elastic constants (Pa, –).
    plane : {"strain", "stress", "3d"}
        Idealisation of the FEM scene ("3d": a full 3D ring with free end faces; its conformal
        baseline uses the paper's plane-stress modulus, its foundation yardstick plane strain).
    """

    clearance_m: float
    width_m: float
    radius_m: float
    bearing_thickness_m: float
    support_thickness_m: float
    bearing_E_Pa: float
    bearing_nu: float
    support_E_Pa: float
    support_nu: float
    plane: str

    @property
    def modulus(self) -> str:
        return "plane_strain" if self.plane == "strain" else "plane_stress"   # "3d": the paper's plane stress

    @property
    def e_star_Pa(self) -> float:
        """Composite modulus of the scene's plane idealisation (Pa)."""
        return laws.composite_modulus(self.bearing_E_Pa, self.bearing_nu, self.support_E_Pa, self.support_nu,
                                      self.modulus)

    def foundation_modulus_estimate_Pa_per_m(self) -> float:
        """``M/(h_b + h_s)``: constrained modulus of the layer over the total ring thickness (Pa/m).

        Plane strain ``M = E(1−ν)/((1+ν)(1−2ν))``; plane stress ``M = E/(1−ν²)``; the two rings
        in series. A physical yardstick for the fitted ``k_f`` (Johnson 1985 §4.3).
        """
        def m(E, nu):
            return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) if self.plane != "stress" else E / (1 - nu ** 2)
        compliance = self.bearing_thickness_m / m(self.bearing_E_Pa, self.bearing_nu) \
            + self.support_thickness_m / m(self.support_E_Pa, self.support_nu)
        return 1.0 / compliance

    def to_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def foundation_shape(penetration_m, clearance_m: float):
    """``e (ε − sin ε cos ε)`` (m) of the Winkler law, with ``e = δ0 + Δr``, ``cos ε = δ0/e``; 0 for Δr <= 0."""
    pen = np.maximum(np.asarray(penetration_m, dtype=float), 0.0)
    e = clearance_m + pen
    sin_eps = np.sqrt(pen * (2.0 * clearance_m + pen)) / e
    cos_eps = clearance_m / e
    eps = np.arctan2(sin_eps, cos_eps)
    return e * (eps - sin_eps * cos_eps)


def _base_and_design(family: str, pen: np.ndarray, geo: SceneGeometry) -> tuple[np.ndarray, np.ndarray]:
    """``base(Δr)`` (log N) and design matrix ``X`` of a family, for Δr > 0."""
    if family == "conformal-scaled":
        p = laws.conformal_force(pen, clearance_m=geo.clearance_m, width_m=geo.width_m,
                                 bearing_E_Pa=geo.bearing_E_Pa, bearing_nu=geo.bearing_nu,
                                 support_E_Pa=geo.support_E_Pa, support_nu=geo.support_nu,
                                 modulus=geo.modulus).force_N
        return np.log(p), np.ones((pen.size, 1))
    if family == "foundation":
        return np.log(geo.radius_m * geo.width_m * foundation_shape(pen, geo.clearance_m)), np.ones((pen.size, 1))
    if family == "power":
        return np.full(pen.size, math.log(geo.width_m)), np.column_stack([np.ones(pen.size), np.log(pen)])
    raise InputError(f"family = {family!r}: must be one of {', '.join(FAMILIES)}")


def conformal_compliance_force(penetration_m, constant: float, geo: SceneGeometry) -> np.ndarray:
    """Force (N) of the ``conformal-compliance`` family at penetrations Δr (m) (module docstring).

    With ``s = b²``: ``Δr/δ0 = 2s/(1−s) + 2 s(1+s)/D(s) · (2 ln((1+s)/(2√s)) + C)`` and
    ``P = 2π E* δ0 l s(1+s)/D(s)``; solved for s by bisection on ``(0, s_max)``, ``D(s_max) = 0``.
    """
    pen = np.asarray(penetration_m, dtype=float)
    flat = np.maximum(pen.ravel(), 0.0)
    alpha, _ = laws.dundurs_constants(geo.bearing_E_Pa, geo.bearing_nu, geo.support_E_Pa, geo.support_nu, geo.modulus)
    s_max_pen = laws.conformal_neat_fit_limit_m(geo.clearance_m, alpha)
    s_max = 1.0 if math.isinf(s_max_pen) else s_max_pen / (2 * geo.clearance_m + s_max_pen)
    target = flat / geo.clearance_m

    def rhs(sv):
        D = laws.conformal_denominator(sv, alpha)
        g = sv * (1 + sv) / D
        return 2 * sv / (1 - sv) + 2 * g * (2 * np.log((1 + sv) / (2 * np.sqrt(sv))) + constant), g

    lo = np.full(flat.shape, 1e-300)
    hi = np.full(flat.shape, s_max * (1 - 1e-12))
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        big = rhs(mid)[0] > target
        hi = np.where(big, mid, hi)
        lo = np.where(big, lo, mid)
        if np.all(hi - lo <= 1e-15 * hi):
            break
    sv = 0.5 * (lo + hi)
    force = 2 * math.pi * geo.e_star_Pa * geo.clearance_m * geo.width_m * rhs(sv)[1]
    return np.where(flat > 0, force, 0.0).reshape(pen.shape)


PARAMETERS = {
    # family: ((name, unit, from fit coordinate θ_i), ...)
    "conformal-scaled": (("stiffness_factor", "-"),),
    "foundation": (("foundation_modulus_Pa_per_m", "Pa/m"),),
    "power": (("coefficient_N_per_m_pow_n_plus_1", "N/m^(n+1)"), ("exponent", "-")),
    "conformal-compliance": (("far_field_constant", "-"),),
}


def _to_parameters(family: str, theta: np.ndarray, cov: np.ndarray) -> tuple[dict, dict]:
    """Physical parameter values and standard deviations from fit coordinates (log or linear)."""
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    names = [n for n, _ in PARAMETERS[family]]
    if family in ("conformal-scaled", "foundation"):
        v = math.exp(theta[0])
        return {names[0]: v}, {names[0]: v * sd[0]}
    c = math.exp(theta[0])
    return {names[0]: c, names[1]: float(theta[1])}, {names[0]: c * sd[0], names[1]: float(sd[1])}


def _theta_from_parameters(family: str, params: dict) -> np.ndarray:
    names = [n for n, _ in PARAMETERS[family]]
    if family == "power":
        return np.array([math.log(params[names[0]]), params[names[1]]])
    return np.array([math.log(params[names[0]])])


def family_force(family: str, params: dict, penetration_m, geo: SceneGeometry) -> np.ndarray:
    """Force (N) of a family with given physical parameters; 0 for Δr <= 0."""
    if family == "conformal-compliance":
        return conformal_compliance_force(penetration_m, params["far_field_constant"], geo)
    pen = np.asarray(penetration_m, dtype=float)
    flat = pen.ravel()
    out = np.zeros(flat.size)
    pos = flat > 0
    if np.any(pos):
        base, X = _base_and_design(family, flat[pos], geo)
        out[pos] = np.exp(base + X @ _theta_from_parameters(family, params))
    return out.reshape(pen.shape)


# --------------------------------------------------------------------------------------------
# fitting, hold-out, selection
# --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class FamilyFit:
    """Least-squares fit of one family to one scene.

    parameters, parameter_std : dict
        Physical values and 1σ standard deviations (units in :data:`PARAMETERS`).
    fit_rel_err : ndarray
        ``P_fit/P_FEM − 1`` at the fitted points (fit on all of them).
    holdout_rel_err : ndarray
        Leave-one-out ``P/P_FEM − 1``: each point predicted by a fit without it.
    """

    family: str
    n_parameters: int
    parameters: dict
    parameter_std: dict
    penetration_m: np.ndarray
    force_fem_N: np.ndarray
    fit_rel_err: np.ndarray
    holdout_rel_err: np.ndarray

    @property
    def holdout_rms(self) -> float:
        return float(np.sqrt(np.mean(self.holdout_rel_err ** 2)))

    @property
    def holdout_max(self) -> float:
        return float(np.max(np.abs(self.holdout_rel_err)))


def _lstsq(y: np.ndarray, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    theta, *_ = np.linalg.lstsq(X, y, rcond=None)
    n, k = X.shape
    resid = y - X @ theta
    s2 = float(resid @ resid) / (n - k) if n > k else 0.0
    cov = s2 * np.linalg.inv(X.T @ X)
    return theta, cov


def fit_family(family: str, penetration_m, force_N, geo: SceneGeometry) -> FamilyFit:
    """Fit ``family`` to FEM points (Δr > 0, force > 0) by linear least squares in log force.

    Raises
    ------
    InputError
        if fewer points than parameters + 2 (no hold-out possible) or a value is not positive.
    """
    if family not in PARAMETERS:
        raise InputError(f"family = {family!r}: must be one of {', '.join(FAMILIES)}")
    pen = np.asarray(penetration_m, dtype=float).ravel()
    f = np.asarray(force_N, dtype=float).ravel()
    k = len(PARAMETERS[family])
    if pen.size != f.size or pen.size < k + 2:
        raise InputError(f"fit_family({family}): need >= {k + 2} points of penetration and force, got {pen.size}")
    laws.check_clearance(geo.clearance_m)
    if np.any(pen <= 0) or np.any(f <= 0) or not np.all(np.isfinite(pen)) or not np.all(np.isfinite(f)):
        raise InputError(f"fit_family({family}): penetration_m and force_N must be finite and > 0")
    if family not in LINEAR_FAMILIES:
        return _fit_nonlinear(family, pen, f, geo)
    base, X = _base_and_design(family, pen, geo)
    y = np.log(f) - base
    theta, cov = _lstsq(y, X)
    fit = np.exp(X @ theta - y) - 1.0
    loo = np.empty(pen.size)
    for i in range(pen.size):
        keep = np.arange(pen.size) != i
        th_i, _ = _lstsq(y[keep], X[keep])
        loo[i] = math.exp(float(X[i] @ th_i - y[i])) - 1.0
    values, std = _to_parameters(family, theta, cov)
    return FamilyFit(family, k, values, std, pen, f, fit, loo)


def _fit_nonlinear(family: str, pen: np.ndarray, f: np.ndarray, geo: SceneGeometry) -> FamilyFit:
    """One-parameter nonlinear least squares in log force (``conformal-compliance``), same outputs as the linear path."""
    from scipy.optimize import least_squares

    name = PARAMETERS[family][0][0]
    bounds = (0.0, 100.0)     # C >= 0: a finite body only adds compliance; keeps Δr(s) monotone

    def resid(c, idx):
        return np.log(family_force(family, {name: float(c[0])}, pen[idx], geo)) - np.log(f[idx])

    def solve(idx, c0=None):
        if c0 is None:     # coarse scan for the start (the residual is smooth and monotone in C per point)
            grid = np.concatenate([[0.0], np.geomspace(0.01, bounds[1], 15)])
            c0 = grid[int(np.argmin([np.sum(resid([g], idx) ** 2) for g in grid]))]
        return least_squares(resid, [c0], args=(idx,), bounds=bounds, x_scale=[1.0], xtol=1e-12, ftol=1e-14, gtol=1e-14)

    allidx = np.arange(pen.size)
    r = solve(allidx)
    n = pen.size
    s2 = float(r.fun @ r.fun) / (n - 1)
    J = r.jac
    var = s2 / float(J[:, 0] @ J[:, 0]) if float(J[:, 0] @ J[:, 0]) > 0 else math.inf
    c = float(r.x[0])
    fit = np.exp(r.fun) - 1.0
    loo = np.empty(n)
    for i in range(n):
        ri = solve(allidx[allidx != i], float(r.x[0]))
        loo[i] = math.exp(float(resid(ri.x, np.array([i]))[0])) - 1.0
    return FamilyFit(family, 1, {name: c}, {name: math.sqrt(var)}, pen, f, fit, loo)


def select_family(fits: list[FamilyFit]) -> FamilyFit:
    """Fewest parameters the data justify (module docstring): returns the chosen fit."""
    best = None
    for k in sorted({f.n_parameters for f in fits}):
        cand = min((f for f in fits if f.n_parameters == k), key=lambda f: f.holdout_rms)
        if best is None or cand.holdout_rms * SELECTION_GAIN <= best.holdout_rms:
            best = cand
    return best


# --------------------------------------------------------------------------------------------
# the stored object
# --------------------------------------------------------------------------------------------

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
        (small angles, contact-laws.md §1, §8). ``P = ∫ h(Δr(x)) dx`` and ``M_z = Σ x F_y`` over the
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

    def kernel_law(self) -> tuple[float, float, float, float]:
        """Kernel law slots ``(code, slot 3, slot 6, slot 7)`` of ``contact._kernel`` for this law.

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
        return (2.0, 0.0, self.parameters["foundation_modulus_Pa_per_m"] * g.radius_m, 0.0)

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
        return json.dumps(_round_floats(doc), indent=1, allow_nan=False) + "\n"

    @classmethod
    def from_json(cls, text: str, source: str = "<string>") -> "CalibratedLaw":
        try:
            doc = json.loads(text)
        except json.JSONDecodeError as exc:
            raise DatasetError(f"{source}: not valid JSON: {exc}") from exc
        if not isinstance(doc, dict) or doc.get("schema") != SCHEMA or doc.get("version") != VERSION:
            raise DatasetError(f"{source}: not a {SCHEMA} v{VERSION} file")
        try:
            fam = doc["family"]
            if fam not in FAMILIES:
                raise DatasetError(f"{source}: family {fam!r} unknown (have {', '.join(FAMILIES)})")
            params = {k: float(doc["parameters"][k]) for k, _ in PARAMETERS[fam]}
            if not all(math.isfinite(v) for v in params.values()):
                raise DatasetError(f"{source}: non-finite parameter")
            return cls(name=doc["name"], scene=doc["scene"], family=fam, parameters=params,
                       parameter_std={k: float(v) for k, v in doc["parameter_std"].items()},
                       parameter_units=dict(doc["parameter_units"]), geometry=SceneGeometry(**doc["geometry"]),
                       validity_penetration_m=(float(doc["validity"]["penetration_min_m"]),
                                               float(doc["validity"]["penetration_max_m"])),
                       dataset=dict(doc["dataset"]), fit=dict(doc.get("fit", {})))
        except (KeyError, TypeError, ValueError) as exc:
            raise DatasetError(f"{source}: malformed calibrated law ({exc!r})") from exc


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
    slots of the compiled kernel (``kernel_args`` 2, 3, 6, 7) come from ``calibrated_kernel_law``
    (see :meth:`CalibratedLaw.kernel_law`). ``law`` keeps the base family for validation
    ("pereira" for a power law, "conformal" otherwise); ``calibration_name`` says which law is used.
    """

    calibration_name: str = ""
    calibrated_kernel_law: tuple = ()

    def __post_init__(self):
        super().__post_init__()
        k = tuple(self.calibrated_kernel_law)
        if len(k) != 4 or k[0] not in (0.0, 1.0, 2.0) or not all(math.isfinite(v) for v in k):
            raise InputError(f"calibrated_kernel_law = {self.calibrated_kernel_law!r}: need (code 0/1/2, "
                             "slot 3, slot 6, slot 7), finite")
        if not self.calibration_name:
            raise InputError("calibration_name = '': name the calibrated law")

    @cached_property
    def kernel_args(self) -> tuple:
        args = list(LooseSupportParams.kernel_args.func(self))
        code, s3, s6, s7 = (float(v) for v in self.calibrated_kernel_law)
        args[2] = code
        if code == 0.0:
            args[3] = s3
        else:
            args[6], args[7] = s6, s7
        return tuple(args)

    @cached_property
    def neat_fit_limit_m(self) -> float:
        if float(self.calibrated_kernel_law[0]) != 0.0:
            return math.inf
        return LooseSupportParams.neat_fit_limit_m.func(self)


# --------------------------------------------------------------------------------------------
# from the dataset to stored files
# --------------------------------------------------------------------------------------------

def scene_geometry(dataset: ReferenceDataset, scene: str) -> SceneGeometry:
    """Geometry of ``scene`` from the dataset metadata.

    2D datasets (``fem_reference.plane.sweep``) hold ``metadata.scenes[scene].rings``; 3D datasets
    (``fem_reference.solid.sweep``) one ``metadata.geometry`` for all scenes (then ``plane = "3d"``).
    """
    g = dataset.metadata.get("geometry")
    if isinstance(g, dict) and "bearing_outer_radius_m" in g:
        try:
            return SceneGeometry(
                clearance_m=float(g["clearance_m"]), width_m=float(g["width_m"]), radius_m=float(g["bearing_outer_radius_m"]),
                bearing_thickness_m=float(g["bearing_outer_radius_m"]) - float(g["bearing_inner_radius_m"]),
                support_thickness_m=float(g["support_thickness_m"]),
                bearing_E_Pa=float(g["young_bearing_pa"]), bearing_nu=float(g["poisson_bearing"]),
                support_E_Pa=float(g["young_support_pa"]), support_nu=float(g["poisson_support"]), plane="3d")
        except (KeyError, TypeError, ValueError) as exc:
            raise DatasetError(f"3D dataset metadata 'geometry' is not usable ({exc!r})") from exc
    try:
        s = dataset.metadata["scenes"][scene]
        r = s["rings"]
        return SceneGeometry(
            clearance_m=float(r["clearance_m"]), width_m=float(r["width_m"]), radius_m=float(r["outer_radius_m"]),
            bearing_thickness_m=float(r["outer_radius_m"]) - float(r["inner_radius_m"]),
            support_thickness_m=float(r["support_outer_radius_m"]) - float(r["outer_radius_m"]) - float(r["clearance_m"]),
            bearing_E_Pa=float(r["bearing"]["youngs_modulus_pa"]), bearing_nu=float(r["bearing"]["poisson_ratio"]),
            support_E_Pa=float(r["support"]["youngs_modulus_pa"]), support_nu=float(r["support"]["poisson_ratio"]),
            plane=str(s["plane"]))
    except (KeyError, TypeError, ValueError) as exc:
        raise DatasetError(f"dataset metadata has no usable ring geometry for scene {scene!r} ({exc!r})") from exc


def scene_points(dataset: ReferenceDataset, scene: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Penetration (m), force (N) and relative FEM error (–) of the zero-tilt points of a scene, sorted."""
    pts = [p for p in dataset.select(scene=scene) if float(p.get("tilt_rad", 0.0)) == 0.0 and p["penetration_m"] > 0]
    if not pts:
        raise DatasetError(f"dataset has no zero-tilt points with penetration > 0 for scene {scene!r}")
    pts.sort(key=lambda p: p["penetration_m"])
    return (np.array([p["penetration_m"] for p in pts], dtype=float),
            np.array([p["force_n"] for p in pts], dtype=float),
            np.array([p.get("force_error_rel", 0.0) for p in pts], dtype=float))


def _dataset_info(path: Path, ds: ReferenceDataset) -> dict:
    doc = json.loads(Path(path).read_text(encoding="utf-8"))
    try:
        rel = str(Path(path).resolve().relative_to(REPO_ROOT))
    except ValueError:
        rel = str(path)
    return {"path": rel, "points_sha256": doc["points_sha256"], "created_utc": ds.metadata.get("created_utc"),
            "code_revision": ds.metadata.get("code_revision")}


def calibrate_scene(dataset: ReferenceDataset, scene: str, dataset_info: dict | None = None) -> tuple[CalibratedLaw, list[FamilyFit]]:
    """Fit every family to a scene's zero-tilt points, select one, return it as a :class:`CalibratedLaw` and all fits.

    The law's name is ``<scene>-<family>`` for 2D datasets and ``<scene>-3d-<family>`` for 3D ones.
    """
    geo = scene_geometry(dataset, scene)
    pen, force, fem_err = scene_points(dataset, scene)
    usable = [fam for fam in FAMILIES if len(PARAMETERS[fam]) + 2 <= pen.size]   # room for a hold-out
    if not usable:
        raise InputError(f"scene {scene!r}: {pen.size} zero-tilt points, need >= 3 to fit and hold out")
    fits = [fit_family(fam, pen, force, geo) for fam in usable]
    best = select_family(fits)
    fit_doc = {
        "method": "linear least squares in log force; 1-sigma from residual variance; hold-out = leave-one-out",
        "selection_rule": f"fewest parameters; a k+1-parameter family replaces the best k-parameter one only if "
                          f"it divides the leave-one-out RMS error by >= {SELECTION_GAIN:g}",
        "penetration_m": pen.tolist(), "force_fem_n": force.tolist(), "fem_error_rel": fem_err.tolist(),
        "fit_rel_err": best.fit_rel_err.tolist(), "holdout_rel_err": best.holdout_rel_err.tolist(),
        "holdout_rms_rel": best.holdout_rms, "holdout_max_rel": best.holdout_max,
        "families": [{"family": f.family, "n_parameters": f.n_parameters, "parameters": f.parameters,
                      "holdout_rms_rel": f.holdout_rms, "holdout_max_rel": f.holdout_max} for f in fits],
    }
    if best.family == "foundation":
        fit_doc["foundation_modulus_estimate_Pa_per_m"] = geo.foundation_modulus_estimate_Pa_per_m()
    law = CalibratedLaw(
        name=f"{scene}{'-3d' if geo.plane == '3d' else ''}-{best.family}", scene=scene, family=best.family, parameters=best.parameters,
        parameter_std=best.parameter_std, parameter_units=dict(PARAMETERS[best.family]), geometry=geo,
        validity_penetration_m=(float(pen.min()), float(pen.max())), dataset=dataset_info or {}, fit=fit_doc)
    return law, fits


def committed_datasets() -> list[Path]:
    """The committed reference datasets to calibrate on: the 2D one and every 3D one present."""
    return [DATASET_2D] + sorted(DATA_3D_DIR.glob("*.json")) if DATA_3D_DIR.is_dir() else [DATASET_2D]


def calibrate_dataset(path=DATASET_2D) -> list[CalibratedLaw]:
    """One calibrated law per scene (with zero-tilt points) of a dataset file."""
    ds = read_dataset(path)
    info = _dataset_info(Path(path), ds)
    out = []
    for scene in ds.scenes():
        pts = [p for p in ds.select(scene=scene) if float(p.get("tilt_rad", 0.0)) == 0.0 and p["penetration_m"] > 0]
        if len(pts) >= 3:
            out.append(calibrate_scene(ds, scene, info)[0])
    return out


def available(directory=CALIBRATED_DIR) -> list[str]:
    """Names of the stored calibrated laws."""
    return sorted(p.stem for p in Path(directory).glob("*.json"))


def load_calibrated(name: str, directory=CALIBRATED_DIR) -> CalibratedLaw:
    """Load a stored calibrated law by name, e.g. ``load_calibrated("clamped-foundation")``.

    A bare scene name (``"clamped"``) is accepted when exactly one law is stored for it.

    Raises
    ------
    DatasetError
        unknown name (listing the available ones) or an unreadable/malformed file.
    """
    directory = Path(directory)
    path = directory / f"{name}.json"
    if not path.exists():
        matches = [n for n in available(directory) if any(n == f"{name}-{fam}" for fam in FAMILIES)]
        if len(matches) != 1:
            raise DatasetError(f"calibrated law {name!r} not found in {directory} (available: "
                               f"{', '.join(available(directory)) or 'none'})")
        path = directory / f"{matches[0]}.json"
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise DatasetError(f"{path}: cannot read calibrated law ({exc})") from exc
    return CalibratedLaw.from_json(text, str(path))


def _calibrate_all(paths) -> list[CalibratedLaw]:
    paths = committed_datasets() if paths is None else [paths] if isinstance(paths, (str, Path)) else list(paths)
    return [law for p in paths for law in calibrate_dataset(p)]


def write_calibrations(paths=None, directory=CALIBRATED_DIR) -> list[Path]:
    """Refit every scene of the datasets (default: all committed) and write ``<directory>/<name>.json``.

    A stored file of the same scene and dataset kind but another family is removed.
    """
    directory = Path(directory)
    out = []
    for law in _calibrate_all(paths):
        stem = law.name[: -len(law.family) - 1]
        for fam in FAMILIES:
            old = directory / f"{stem}-{fam}.json"
            if fam != law.family and old.exists():
                old.unlink()
        out.append(atomic_write_text(directory / f"{law.name}.json", law.to_json()))
    return out


def _first_difference(a, b, where: str = "", rel: float = 1e-6) -> str | None:
    """Path of the first difference between two JSON trees (floats compared to ``rel``), or None."""
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            return f"{where or '/'} keys {sorted(set(a) ^ set(b))}"
        for k in a:
            d = _first_difference(a[k], b[k], f"{where}/{k}", rel)
            if d:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{where} length {len(a)} != {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            d = _first_difference(x, y, f"{where}/{i}", rel)
            if d:
                return d
        return None
    if isinstance(a, float) or isinstance(b, float):
        if isinstance(a, (int, float)) and isinstance(b, (int, float)) and math.isclose(a, b, rel_tol=rel, abs_tol=1e-12):
            return None
        return f"{where}: {a!r} != {b!r}"
    return None if a == b else f"{where}: {a!r} != {b!r}"


def check_calibrations(paths=None, directory=CALIBRATED_DIR) -> list[str]:
    """Differences between the stored calibrations and a fresh fit of the datasets (empty list = up to date)."""
    problems = []
    for law in _calibrate_all(paths):
        try:
            stored = load_calibrated(law.name, directory)
        except DatasetError as exc:
            problems.append(str(exc))
            continue
        diff = _first_difference(json.loads(stored.to_json()), json.loads(law.to_json()))
        if diff is not None:
            problems.append(f"{law.name}: stored file differs from a refit of {law.dataset.get('path')} at {diff} "
                            f"(dataset {law.dataset.get('points_sha256', '')[:12]}…, stored from "
                            f"{stored.dataset.get('points_sha256', '')[:12]}…)")
    return problems


def main(argv: list[str] | None = None) -> int:
    """``ringcontact calibrate``: fit and store the calibrated laws of the committed 2D dataset."""
    p = argparse.ArgumentParser(prog="ringcontact calibrate",
                                description="Fit one calibrated contact law per FEM scene and store it in contact/calibrated/.")
    p.add_argument("--dataset", type=Path, action="append",
                   help="reference dataset (repeatable; default: the committed 2D dataset and every 3D one)")
    p.add_argument("--out", type=Path, default=CALIBRATED_DIR, help=f"directory of the JSON files (default {CALIBRATED_DIR})")
    p.add_argument("--check", action="store_true", help="only compare the stored files with a fresh fit; exit 1 on drift")
    args = p.parse_args(argv)
    try:
        if args.check:
            problems = check_calibrations(args.dataset, args.out)
            for msg in problems:
                print(msg)
            print("calibrations up to date" if not problems else f"{len(problems)} calibration(s) out of date")
            return 1 if problems else 0
        for f in write_calibrations(args.dataset, args.out):
            law = load_calibrated(f.stem, args.out)
            pars = ", ".join(f"{k} = {v:.6g} ± {law.parameter_std[k]:.2g} {law.parameter_units[k]}"
                             for k, v in law.parameters.items())
            print(f"{law.name}: {pars}; hold-out max {100 * law.fit['holdout_max_rel']:.3f} % -> {f}")
    except RingContactError as exc:
        print(f"ringcontact calibrate: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":   # pragma: no cover
    sys.exit(main())
