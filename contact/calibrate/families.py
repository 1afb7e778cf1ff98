"""The law families of a calibration and their closed forms: ``log P = base(Δr) + X θ``.

Each family (``conformal-scaled``, ``foundation``, ``conformal-compliance``, ``power``, and the flexible
``foundation-spline`` of :mod:`contact.calibrate.spline`; see the package docstring of
:mod:`contact.calibrate`) gives the force of a straight ring (N) at
penetrations Δr (m) from its physical parameters (:data:`PARAMETERS`) and the scene's geometry
(:class:`SceneGeometry`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact import laws
import contact.calibrate.spline as spline
from contact.errors import InputError

ANALYTIC_FAMILIES = ("conformal-scaled", "foundation", "conformal-compliance", "power")
FAMILIES = ANALYTIC_FAMILIES + (spline.FAMILY,)
LINEAR_FAMILIES = ("conformal-scaled", "foundation", "power")       # log P linear in the fit coordinates
KERNEL_LAW_CODE = {"conformal-scaled": 0.0, "power": 1.0, "foundation": 2.0, spline.FAMILY: 3.0}


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


def foundation_force(penetration_m, geo: SceneGeometry) -> np.ndarray:
    """``R l e (ε − sin ε cos ε)`` (N per Pa/m of foundation modulus): the base of ``foundation-spline``."""
    return geo.radius_m * geo.width_m * foundation_shape(penetration_m, geo.clearance_m)


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
    """Force (N) of the ``conformal-compliance`` family at penetrations Δr (m) (package docstring).

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
    spline.FAMILY: (("knot_count", "-"),),      # and the knots' log_penetration_NN, log_correction_NN, log_slope_NN
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
    if family == spline.FAMILY:
        flat = np.maximum(pen.ravel(), 0.0)
        out = np.zeros(flat.size)
        pos = flat > 0
        out[pos] = foundation_force(flat[pos], geo) * spline.correction(params, flat[pos])
        return out.reshape(pen.shape)
    flat = pen.ravel()
    out = np.zeros(flat.size)
    pos = flat > 0
    if np.any(pos):
        base, X = _base_and_design(family, flat[pos], geo)
        out[pos] = np.exp(base + X @ _theta_from_parameters(family, params))
    return out.reshape(pen.shape)

