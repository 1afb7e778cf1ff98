"""Analytic force laws of a bearing outer ring pressed into its support through a clearance.

Three laws, each a plain vectorized function of the **penetration** ``Δr = |r| − δ0``
(radial overlap of the undeformed circles, metres) returning a :class:`LawResult`:

* :func:`conformal_force` — the pin-in-hole law of Persson (1964) as generalised by
  Ciavarella & Decuzzi (2001, Int. J. Solids Struct. 38, parts I and II), used by
  Yang et al. (2024) and Dai et al. (2025, Actuators 14:422, Eq. 5);
* :func:`johnson_force` — Johnson's conformal-cylinder law (Johnson, *Contact Mechanics*;
  Dai et al. 2025 Eqs. 26–27), in closed form with the Lambert W function;
* :func:`pereira_force` — the fit of Pereira, Ramalho & Ambrósio (2015, Multibody Syst.
  Dyn. 35:277; Dai et al. 2025 Eqs. 28–29).

and :func:`damping_factor`, the Lankarani & Nikravesh (1990) impact-damping factor
``(1 + c_c v_n)`` of Dai et al. (2025) Eq. 1.

Units: SI everywhere (m, N, Pa, s). Only :func:`pereira_force` converts internally, to the
mm / MPa in which its exponent was fitted, and back to N at its edge.

Validity domains are explicit. A point where a law has no (physical) value is returned with
``in_domain = False`` and ``force_N = nan`` in a :class:`LawResult`; pass ``strict=True``
to get :class:`~contact.errors.OutsideDomainError` instead. A zero or negative penetration
is *inside* the domain and gives zero force.

Open questions resolved here (see ``docs/reference/contact-laws.md`` Q1, Q3, Q6):

* ``beta_reading`` (Q1): the β term of Eq. 5 is garbled in the paper. ``"zero"`` (default)
  drops it; this is the exact plane-elasticity solution whenever the Dundurs β vanishes,
  in particular for identical ring and support materials (the paper's Tables 1 and 4).
  ``"minus_4b2_1pb2"`` / ``"plus_4b2_1pb2"`` subtract / add ``4 β b²(1+b²)`` in the
  denominator (reading (a) of the note), for comparison against the FEM only.
* ``modulus`` (Q3): ``"plane_stress"`` (default for the conformal law, reproduces the
  paper's Table 2) or ``"plane_strain"``; Johnson and Pereira default to plane strain
  as in the paper's Eq. 27.
* ``c_c`` (Q6): the collision factor is taken in **s/m** (the paper's "s/N" cannot be
  right: ``c_c v_n`` must be dimensionless). The factor ``1 + c_c v_n`` is clipped at 0 by
  default (``clip_at_zero=True``): a contact cannot pull the ring back during fast
  separation. The paper does not say; pass ``clip_at_zero=False`` for the raw product.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.special import lambertw

from contact.errors import InputError, OutsideDomainError
from contact.units import check_finite, check_positive

MODULI = ("plane_stress", "plane_strain")
BETA_READINGS = ("zero", "minus_4b2_1pb2", "plus_4b2_1pb2")

# Plausibility bounds that catch values typed in mm/GPa where SI is expected.
MAX_CLEARANCE_M = 1e-2      # 10 mm radial clearance: also the upper edge of Pereira's fit
MAX_WIDTH_M = 1.0
MAX_RADIUS_M = 10.0
MIN_MODULUS_PA = 1e5        # below this, a modulus was probably given in GPa or MPa
MAX_MODULUS_PA = 2e12
MAX_CLEARANCE_TO_RADIUS = 0.05

PEREIRA_A = 0.965           # Pereira et al. (2015) as quoted by Dai et al. (2025) Eq. 28
PEREIRA_B = 0.0965
PEREIRA_CLEARANCE_RANGE_MM = (0.005, 10.0)
PEREIRA_BRANCH_MM = 0.34954


@dataclass(frozen=True)
class LawResult:
    """Force of a law at an array of points, with its validity mask.

    Attributes
    ----------
    force_N : ndarray
        Magnitude of the normal contact force (N), ``>= 0``; ``nan`` where ``in_domain``
        is False.
    in_domain : ndarray of bool
        False where the law has no physical value (never silently a number).
    law : str
        Name of the law that produced the values.
    """

    force_N: np.ndarray
    in_domain: np.ndarray
    law: str

    def require_in_domain(self, penetration_m=None) -> np.ndarray:
        """Return ``force_N`` or raise :class:`OutsideDomainError` naming the first bad point."""
        if np.all(self.in_domain):
            return self.force_N
        idx = np.flatnonzero(~np.asarray(self.in_domain).ravel())[0]
        where = ""
        if penetration_m is not None:
            pen = np.broadcast_to(np.asarray(penetration_m, dtype=float), np.shape(self.in_domain)).ravel()
            where = f" at penetration_m = {pen[idx]:g} m"
        raise OutsideDomainError(f"{self.law} law has no solution{where} (point {idx}): outside its domain")


# --------------------------------------------------------------------------------------------
# parameter checks
# --------------------------------------------------------------------------------------------

def check_clearance(clearance_m: float, radius_m: float | None = None) -> float:
    """Validate a radial clearance (m); with ``radius_m`` also catch mm typed as m.

    Raises
    ------
    InputError
        naming ``clearance_m``, its value and unit, if it is not finite, not > 0, larger
        than 10 mm, or larger than 5 % of the ring radius.
    """
    check_positive("clearance_m", clearance_m, "m", upper=MAX_CLEARANCE_M)
    if radius_m is not None:
        check_positive("radius_m", radius_m, "m", upper=MAX_RADIUS_M)
        if clearance_m > MAX_CLEARANCE_TO_RADIUS * radius_m:
            raise InputError(
                f"clearance_m = {clearance_m:g} m: must be <= {MAX_CLEARANCE_TO_RADIUS:g} x radius_m "
                f"= {MAX_CLEARANCE_TO_RADIUS * radius_m:g} m (a radial clearance that large is not a "
                "bearing fit; value given in mm?)")
    return float(clearance_m)


def check_width(width_m: float) -> float:
    """Validate the axial ring width (m): finite, > 0, <= 1 m."""
    check_positive("width_m", width_m, "m", upper=MAX_WIDTH_M)
    return float(width_m)


def check_material(name: str, E_Pa: float, nu: float) -> None:
    """Validate a Young's modulus (Pa, 1e5..2e12) and Poisson's ratio (-1 < ν <= 0.5)."""
    check_finite(f"{name}_E_Pa", E_Pa, "Pa")
    if not E_Pa > 0:
        raise InputError(f"{name}_E_Pa = {E_Pa:g} Pa: must be > 0")
    if not MIN_MODULUS_PA <= E_Pa <= MAX_MODULUS_PA:
        raise InputError(f"{name}_E_Pa = {E_Pa:g} Pa: must be in [{MIN_MODULUS_PA:g}, {MAX_MODULUS_PA:g}] Pa "
                         "(given in GPa or MPa? SI expected)")
    check_finite(f"{name}_nu", nu, "-")
    if not -1.0 < nu <= 0.5:
        raise InputError(f"{name}_nu = {nu:g} (dimensionless): must be in (-1, 0.5]")


def _check_choice(name: str, value: str, allowed: tuple[str, ...]) -> str:
    if value not in allowed:
        raise InputError(f"{name} = {value!r}: must be one of {', '.join(allowed)}")
    return value


def _penetration(penetration_m) -> np.ndarray:
    check_finite("penetration_m", penetration_m, "m")
    return np.asarray(penetration_m, dtype=float)


# --------------------------------------------------------------------------------------------
# elastic constants
# --------------------------------------------------------------------------------------------

def composite_modulus(bearing_E_Pa: float, bearing_nu: float, support_E_Pa: float, support_nu: float,
                      modulus: str = "plane_stress") -> float:
    """Composite contact modulus E* (Pa) of ring and support.

    ``plane_stress``: ``1/E* = 1/E_b + 1/E_s`` (then ``E_b(1+α) = 2E*``, Dai et al. 2025 Eq. 5);
    ``plane_strain``: ``1/E* = (1−ν_b²)/E_b + (1−ν_s²)/E_s`` (Johnson; Dai et al. 2025 Eq. 27).
    """
    _check_choice("modulus", modulus, MODULI)
    check_material("bearing", bearing_E_Pa, bearing_nu)
    check_material("support", support_E_Pa, support_nu)
    if modulus == "plane_stress":
        return 1.0 / (1.0 / bearing_E_Pa + 1.0 / support_E_Pa)
    return 1.0 / ((1 - bearing_nu ** 2) / bearing_E_Pa + (1 - support_nu ** 2) / support_E_Pa)


def dundurs_constants(bearing_E_Pa: float, bearing_nu: float, support_E_Pa: float, support_nu: float,
                      modulus: str = "plane_stress") -> tuple[float, float]:
    """Dundurs' (1969) bimaterial constants (α, β), body 1 = support (hole), body 2 = bearing (pin).

    Plane stress gives exactly the paper's ``α = (E_s − E_b)/(E_s + E_b)`` and
    ``β = [E_s(1−ν_b) − E_b(1−ν_s)] / [2(E_s + E_b)]`` (Dai et al. 2025, after Eq. 5).
    Both vanish for identical materials.
    """
    _check_choice("modulus", modulus, MODULI)
    check_material("bearing", bearing_E_Pa, bearing_nu)
    check_material("support", support_E_Pa, support_nu)
    E1, n1, E2, n2 = support_E_Pa, support_nu, bearing_E_Pa, bearing_nu
    if modulus == "plane_stress":
        return (E1 - E2) / (E1 + E2), (E1 * (1 - n2) - E2 * (1 - n1)) / (2 * (E1 + E2))
    A1, A2 = E1 * (1 - n2 ** 2), E2 * (1 - n1 ** 2)
    alpha = (A1 - A2) / (A1 + A2)
    beta = (E1 * (1 + n2) * (1 - 2 * n2) - E2 * (1 + n1) * (1 - 2 * n1)) / (2 * (A1 + A2))
    return alpha, beta


# --------------------------------------------------------------------------------------------
# conformal law (Persson 1964; Ciavarella & Decuzzi 2001; Dai et al. 2025 Eq. 5)
# --------------------------------------------------------------------------------------------

def contact_b_squared(penetration_m, clearance_m: float) -> np.ndarray:
    """``b² = tan²(ε/2) = Δr / (2δ0 + Δr)`` for ``Δr > 0`` (0 otherwise).

    ε is the rigid-overlap contact half-angle, ``cos ε = δ0/(δ0 + Δr)`` (Dai et al. 2025
    Eq. 7 read with ε the *half*-angle, docs/reference/contact-laws.md §2 / Q2).
    """
    pen = np.maximum(np.asarray(penetration_m, dtype=float), 0.0)
    return pen / (2.0 * clearance_m + pen)


def contact_half_angle_rad(penetration_m, clearance_m: float) -> np.ndarray:
    """Rigid-overlap contact half-angle ε (rad): ``cos ε = δ0/(δ0 + Δr)``, 0 without contact."""
    pen = np.maximum(np.asarray(penetration_m, dtype=float), 0.0)
    return np.arccos(clearance_m / (clearance_m + pen))


def beta_coefficient(beta: float, beta_reading: str = "zero") -> float:
    """Coefficient ``c_β`` such that the denominator is ``D = 2 − (1−α)(ln(1+b²)+2b⁴) + c_β b²(1+b²)``."""
    _check_choice("beta_reading", beta_reading, BETA_READINGS)
    return {"zero": 0.0, "minus_4b2_1pb2": -4.0 * beta, "plus_4b2_1pb2": 4.0 * beta}[beta_reading]


def conformal_denominator(b2, alpha: float, beta_coef: float = 0.0):
    """``D(b) = 2 − (1−α)[ln(1+b²) + 2b⁴] + c_β b²(1+b²)`` of Dai et al. (2025) Eq. 5.

    ``D > 0`` is the law's domain; ``D → 0`` is the neat-fit limit where the load diverges.
    """
    b2 = np.asarray(b2, dtype=float)
    return 2.0 - (1.0 - alpha) * (np.log1p(b2) + 2.0 * b2 * b2) + beta_coef * b2 * (1.0 + b2)


def conformal_neat_fit_limit_m(clearance_m: float, alpha: float = 0.0, beta_coef: float = 0.0) -> float:
    """Penetration (m) at which ``D(b) = 0`` and the conformal load diverges; ``inf`` if never.

    For α = β = 0 this is ``Δr_max = 10.09 δ0`` (ε_max = 84.83°, docs/reference/contact-laws.md §3.1).
    ``b²`` ranges over [0, 1) as Δr goes from 0 to ∞, so the root is sought on that interval.
    """
    f = lambda s: float(conformal_denominator(s, alpha, beta_coef))  # noqa: E731
    hi = 1.0 - 1e-15
    if f(hi) > 0:
        return math.inf
    s = brentq(f, 0.0, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
    return 2.0 * clearance_m * s / (1.0 - s)


def conformal_force(penetration_m, *, clearance_m: float, width_m: float,
                    bearing_E_Pa: float, bearing_nu: float, support_E_Pa: float, support_nu: float,
                    modulus: str = "plane_stress", beta_reading: str = "zero",
                    strict: bool = False) -> LawResult:
    """Conformal pin-in-hole contact force (Dai et al. 2025 Eq. 5; Persson 1964; Ciavarella & Decuzzi 2001).

    ``P = 2π E* δ0 l · b²(1+b²) / D(b)`` with ``b² = Δr/(2δ0+Δr)`` and
    ``D = 2 − (1−α)[ln(1+b²) + 2b⁴] (+ β term, see ``beta_reading``)``.
    In the paper's notation ``2E* = E_b(1+α)`` (plane stress). The load scales with the
    clearance δ0; the penetration enters only through b. Small-load limit:
    ``P ≈ (π/2) E* l Δr``, the Hertz line-contact limit (see tests).

    Parameters
    ----------
    penetration_m : array_like
        ``Δr = |r| − δ0`` (m). ``<= 0`` means no contact (force 0).
    clearance_m : float
        Radial clearance δ0 (m), > 0.
    width_m : float
        Axial contact length l (m): the ring width l0 for line contact.
    bearing_E_Pa, bearing_nu, support_E_Pa, support_nu : float
        Young's moduli (Pa) and Poisson's ratios of ring (pin) and support (hole).
    modulus : {"plane_stress", "plane_strain"}
        Which 2D idealisation sets E*, α and β (default reproduces the paper).
    beta_reading : {"zero", "minus_4b2_1pb2", "plus_4b2_1pb2"}
        Reading of the garbled β term (module docstring). Irrelevant when β = 0.
    strict : bool
        Raise :class:`OutsideDomainError` instead of flagging points beyond the neat fit.

    Returns
    -------
    LawResult
        ``force_N`` (N); ``in_domain`` False where ``D(b) <= 0``.
    """
    pen = _penetration(penetration_m)
    check_clearance(clearance_m)
    check_width(width_m)
    e_star = composite_modulus(bearing_E_Pa, bearing_nu, support_E_Pa, support_nu, modulus)
    alpha, beta = dundurs_constants(bearing_E_Pa, bearing_nu, support_E_Pa, support_nu, modulus)
    beta_coef = beta_coefficient(beta, beta_reading)
    force, ok = _conformal_per_width(pen, clearance_m, e_star, alpha, beta_coef)
    result = LawResult(force_N=force * width_m, in_domain=ok, law="conformal")
    if strict:
        result.require_in_domain(pen)
    return result


def _conformal_per_width(pen: np.ndarray, clearance_m: float, e_star: float, alpha: float,
                         beta_coef: float) -> tuple[np.ndarray, np.ndarray]:
    """Conformal load per unit contact length (N/m) and domain mask; inputs already validated."""
    b2 = contact_b_squared(pen, clearance_m)
    d = conformal_denominator(b2, alpha, beta_coef)
    ok = d > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.where(ok, 2.0 * np.pi * e_star * clearance_m * b2 * (1.0 + b2) / np.where(ok, d, 1.0), np.nan)
    return p, np.asarray(ok)


# --------------------------------------------------------------------------------------------
# Johnson (Dai et al. 2025 Eqs. 26-27)
# --------------------------------------------------------------------------------------------

JOHNSON_MAX_RATIO = 4.0 / math.e ** 2   # max of Δr/δ: no solution above (docs/reference/contact-laws.md §5)


def johnson_penetration(force_N, *, clearance_m: float, width_m: float, e_star_Pa: float) -> np.ndarray:
    """Johnson's implicit relation solved the easy way: ``Δr = P/(πE*l)·[ln(4πE*lδ/P) − 1]`` (m).

    Dai et al. (2025) Eq. 26 with δ = δ0; zero force gives zero penetration.
    """
    P = np.asarray(force_N, dtype=float)
    scale = np.pi * e_star_Pa * width_m
    with np.errstate(divide="ignore", invalid="ignore"):
        out = P / scale * (np.log(4.0 * scale * clearance_m / P) - 1.0)
    return np.where(P > 0, out, 0.0)


def johnson_force(penetration_m, *, clearance_m: float, width_m: float,
                  bearing_E_Pa: float, bearing_nu: float, support_E_Pa: float, support_nu: float,
                  modulus: str = "plane_strain", strict: bool = False) -> LawResult:
    """Johnson's conformal-cylinder law (Johnson, *Contact Mechanics*; Dai et al. 2025 Eqs. 26–27), closed form.

    With ``ρ = Δr/δ0`` and ``x = P/(πE* l δ0)`` the law reads ``ρ = x(ln(4/x) − 1)``.
    Substituting ``x = −ρ/W`` gives ``W e^W = −eρ/4``, so on the physical (small-load,
    ``dΔr/dP > 0``) branch ``P = πE* l δ0 · (−ρ / W₋₁(−eρ/4))``: no root finder.
    Real solutions exist only for ``ρ <= 4/e² ≈ 0.541`` (the '-' entries of the paper's
    Table 2); above that the point is flagged outside the domain.

    Parameters are as in :func:`conformal_force`; ``modulus`` defaults to plane strain
    as in the paper's Eq. 27.
    """
    pen = _penetration(penetration_m)
    check_clearance(clearance_m)
    check_width(width_m)
    e_star = composite_modulus(bearing_E_Pa, bearing_nu, support_E_Pa, support_nu, modulus)
    rho = np.maximum(pen, 0.0) / clearance_m
    ok = rho <= JOHNSON_MAX_RATIO
    arg = -math.e * np.where(ok, rho, 0.0) / 4.0
    arg = np.maximum(arg, -1.0 / math.e)       # guard round-off at the branch point
    with np.errstate(divide="ignore", invalid="ignore"):
        w = lambertw(arg, k=-1).real
        x = np.where(rho > 0, -rho / w, 0.0)
    force = np.where(ok, np.pi * e_star * width_m * clearance_m * x, np.nan)
    result = LawResult(force_N=force, in_domain=np.asarray(ok), law="johnson")
    if strict:
        result.require_in_domain(pen)
    return result


# --------------------------------------------------------------------------------------------
# Pereira et al. 2015 (Dai et al. 2025 Eqs. 28-29)
# --------------------------------------------------------------------------------------------

def pereira_exponent(clearance_m: float) -> float:
    """Clearance-dependent exponent ``n = Y δ0^(−0.005)`` of Pereira et al. (2015), δ0 in mm.

    ``Y = 1.51 [ln(1000 δ0)]^(−0.151)`` for δ0 ∈ (0.005, 0.34954] mm, ``Y = 0.0151 δ0 + 1.151``
    for δ0 ∈ (0.34954, 10] mm (Dai et al. 2025 Eq. 29). n = 1.2475 for δ0 = 0.05 mm.
    """
    check_positive("clearance_m", clearance_m, "m")
    d_mm = clearance_m * 1e3
    lo, hi = PEREIRA_CLEARANCE_RANGE_MM
    if not lo < d_mm <= hi:
        raise InputError(f"clearance_m = {clearance_m:g} m: Pereira et al. (2015) fit needs "
                         f"{lo * 1e-3:g} m < clearance_m <= {hi * 1e-3:g} m")
    y = 1.51 * math.log(1000.0 * d_mm) ** -0.151 if d_mm <= PEREIRA_BRANCH_MM else 0.0151 * d_mm + 1.151
    return y * d_mm ** -0.005


def pereira_coefficient(clearance_m: float, e_star_Pa: float) -> tuple[float, float]:
    """``(C, n)`` with ``P[N] = C · l[m] · Δr[m]^n`` equivalent to the mm/MPa fit of Pereira et al. (2015).

    In the fit's units ``P = (aδ0 + b) l E*/δ0 · Δr^n`` (δ0, l, Δr in mm, E* in MPa).
    """
    n = pereira_exponent(clearance_m)
    d_mm = clearance_m * 1e3
    c_mm = (PEREIRA_A * d_mm + PEREIRA_B) * (e_star_Pa * 1e-6) / d_mm   # N per mm of width per mm^n
    return c_mm * 1e3 * 1e3 ** n, n


def pereira_force(penetration_m, *, clearance_m: float, width_m: float,
                  bearing_E_Pa: float, bearing_nu: float, support_E_Pa: float, support_nu: float,
                  modulus: str = "plane_strain") -> LawResult:
    """Pereira, Ramalho & Ambrósio (2015) cylindrical-contact fit (Dai et al. 2025 Eqs. 28–29).

    ``P = (a δ0 + b) l E*/δ0 · Δr^n`` with a = 0.965, b = 0.0965, evaluated in mm / MPa (the
    units of the fit) and returned in N. Defined for every Δr >= 0 once the clearance lies in
    the fit's range (0.005, 10] mm; a clearance outside it raises :class:`InputError`.
    """
    pen = _penetration(penetration_m)
    check_clearance(clearance_m)
    check_width(width_m)
    e_star = composite_modulus(bearing_E_Pa, bearing_nu, support_E_Pa, support_nu, modulus)
    c, n = pereira_coefficient(clearance_m, e_star)
    force = c * width_m * np.maximum(pen, 0.0) ** n
    return LawResult(force_N=force, in_domain=np.ones(np.shape(force), dtype=bool), law="pereira")


# --------------------------------------------------------------------------------------------
# damping (Lankarani & Nikravesh 1990; Dai et al. 2025 Eq. 1)
# --------------------------------------------------------------------------------------------

def damping_factor(normal_velocity_m_s, c_c_s_per_m: float, *, clip_at_zero: bool = True):
    """Impact-damping factor ``1 + c_c v_n`` multiplying the elastic force (Dai et al. 2025 Eq. 1).

    Lankarani & Nikravesh (1990) write ``1 + 3(1−e²)/4 · v_n/v⁻``, so ``c_c = 3(1−e²)/(4v⁻)``
    has the unit s/m (the paper's Table 4 "s/N" is read as s/m, Q6).

    Parameters
    ----------
    normal_velocity_m_s : array_like
        ``v_n`` (m/s), positive while the penetration grows.
    c_c_s_per_m : float
        Collision factor (s/m), >= 0.
    clip_at_zero : bool
        Clip the factor at 0 so a separating contact never pulls (default True).
    """
    check_positive("c_c_s_per_m", c_c_s_per_m, "s/m", allow_zero=True)
    v = np.asarray(normal_velocity_m_s, dtype=float)
    check_finite("normal_velocity_m_s", v, "m/s")
    f = 1.0 + c_c_s_per_m * v
    return np.maximum(f, 0.0) if clip_at_zero else f


LAWS = {"conformal": conformal_force, "johnson": johnson_force, "pereira": pereira_force}


def force_per_width_function(law: str, *, clearance_m: float, bearing_E_Pa: float, bearing_nu: float,
                             support_E_Pa: float, support_nu: float, modulus: str | None = None,
                             beta_reading: str = "zero"):
    """Return ``f(penetration_m) -> (force per unit contact length N/m, in_domain)`` for ``law``.

    All three laws are linear in the contact length l, so the tilted-contact geometry
    (:mod:`contact.tilt`) multiplies this by the patch length ``l_k``. ``modulus`` None
    means the law's default (conformal: plane stress; Johnson and Pereira: plane strain).
    Parameters are validated once here.
    """
    _check_choice("law", law, tuple(LAWS))
    modulus = modulus or ("plane_stress" if law == "conformal" else "plane_strain")
    kw = dict(clearance_m=clearance_m, width_m=1.0, bearing_E_Pa=bearing_E_Pa, bearing_nu=bearing_nu,
              support_E_Pa=support_E_Pa, support_nu=support_nu, modulus=modulus)
    if law == "conformal":
        kw["beta_reading"] = beta_reading
    LAWS[law](np.zeros(1), **kw)          # validates every parameter now, not at the first call
    fn = LAWS[law]

    def per_width(penetration_m):
        res = fn(penetration_m, **kw)
        return res.force_N, res.in_domain

    return per_width
