"""A Jeffcott rotor whirling in a frictionless clearance ring: the verification case of the periodic-orbit tools.

The rotor (Jeffcott 1919) is a point mass ``m`` on a massless shaft of stiffness ``k`` with viscous
damping ``c`` and unbalance (mass eccentricity) ``e``, here carrying a bearing ring that meets a rigid
ground support through the radial clearance ``δ0`` with the suite's own contact law
(:mod:`contact.loose_support`, the line contact of the tilt-ignored model, Dai et al. 2025 §5.2), and no
end-face friction (``μ = 0``). The model is a :class:`~rotor.dynamics.system.RotorSystem` with four DOFs
``(y, z, θy, θz)``: the two tilts carry a small decoupled, damped oscillator so that the support node has
the four DOFs the integrators expect; nothing excites them and the tilt-ignored law passes no moment.

Exact synchronous orbit
-----------------------
The forward whirl ``y + i z = r e^{iΩt}`` is an exact solution: the contact force is radial, its
magnitude ``f(r − δ0)`` depends only on the radius, and the Lankarani–Nikravesh factor ``1 + c_c v_n``
is 1 because the radial velocity ``v_n`` vanishes on a circle. Balancing the radial and tangential
forces against the unbalance force ``m e Ω²`` gives::

    ((k − m Ω²) r + f(r − δ0))² + (c Ω r)² = (m e Ω²)²

The Newmark scheme (average acceleration, :mod:`rotor.dynamics.production`) has an exact discrete
circular orbit too. Its update is the trapezoidal rule for displacement and velocity,
``x_{n+1} − x_n = Δt/2 (v_n + v_{n+1})``, ``v_{n+1} − v_n = Δt/2 (a_n + a_{n+1})``, so
``x_n = X e^{iΩ t_n}`` has ``v_n = i Ω' x_n`` and ``a_n = −Ω'² x_n`` with the *warped* frequency
``Ω' = (2/Δt) tan(Ω Δt / 2)`` (the Cayley map of ``iΩ``). The discrete velocity is still tangential
(no impact damping), and equilibrium holds at each step with the load evaluated at the exact time, so the
scheme's orbit radius solves the same equation with ``Ω'`` in the inertia and damping terms and ``Ω``
in the load. With ``N`` steps per revolution ``Ω Δt / 2 = π/N`` and ``Ω' = Ω tan(π/N)/(π/N)``
(:func:`warped_frequency`). :func:`closed_form_speeds` solves the equation for Ω at a given radius
(a quadratic in Ω²), :func:`closed_form_radius` for r at a given speed, :func:`closed_form_folds`
gives the turning points of the response curve (the jump speeds).

Grazing
-------
With a law of finite stiffness at zero penetration (``law = "conformal"``, Dai et al. 2025 Eq. 5:
``f ≈ (π/2) E* l Δr`` for small ``Δr``) the curve has corners where the free orbit's radius is the clearance,
``m e Ω² = δ0 √((k − mΩ'²)² + (cΩ')²)``: the roots of :func:`closed_form_speeds` at ``r = δ0`` (``f = 0``
there), :func:`closed_form_grazing`. Each is a *grazing fold* when the speed turns there (dΩ/dr of the free
and of the contact side have opposite signs, the corner is then a turning point of the curve that no smooth
fold locates), else a plain grazing. With ``e = 0.3 δ0`` and the other defaults the curve rises free to the
grazing at 279.6 rad/s, goes on in contact to the smooth jump-down fold near 446 rad/s (r ≈ 4.2 δ0), comes
back along the unstable middle branch to the grazing fold near 374.3 rad/s and leaves free towards high speed.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from contact.loose_support import LooseSupportParams, loose_support_force
from rotor.dynamics.kernels import support_law_from_params
from rotor.dynamics.system import HarmonicForce, LooseSupport, RotorSystem


@dataclass(frozen=True)
class JeffcottParams:
    """The Jeffcott rotor in a clearance ring (SI).

    Attributes
    ----------
    mass_kg, stiffness_N_m, damping_N_s_m, eccentricity_m : float
        ``m``, shaft stiffness ``k``, viscous damping ``c``, unbalance eccentricity ``e``.
    clearance_m : float, radial clearance δ0.
    ring_width_m : float, axial width of the ring (line contact length).
    modulus_Pa : float, Young's modulus of ring and support (ν 0.3): sets the contact stiffness.
    collision_factor_s_m : float, Lankarani–Nikravesh c_c (s/m); inactive on a circular orbit.
    tilt_inertia_kg_m2, tilt_stiffness_Nm_rad, tilt_damping_ratio : the decoupled tilt oscillator.

    Defaults: ω_n = √(k/m) = 316 rad/s, ζ = c/(2√(km)) = 0.05, e = 2 δ0, the Pereira et al. (2015) law
    (Dai et al. 2025 Eqs. 28–29; force ∝ penetration^1.25, so the contact stiffness starts from zero and the
    response curve has smooth folds) with E = 10 MPa (secant contact stiffness ≈ 1.1 k at 1 δ0 of
    penetration): the resonance curve bends to the right, with the jump-up fold near 624 rad/s
    (r ≈ 7.4 δ0) and the jump-down fold near 727 rad/s (r ≈ 45 δ0), every fold in contact.
    """

    mass_kg: float = 1.0
    stiffness_N_m: float = 1.0e5
    damping_N_s_m: float = 31.622776601683793   # ζ = 0.05
    eccentricity_m: float = 2.0e-5
    clearance_m: float = 1.0e-5
    ring_width_m: float = 10e-3
    modulus_Pa: float = 1.0e7
    collision_factor_s_m: float = 50.0
    tilt_inertia_kg_m2: float = 1.0e-3
    tilt_stiffness_Nm_rad: float = 100.0
    tilt_damping_ratio: float = 0.05
    law: str = "pereira"

    def law_params(self, clearance_m: float | None = None) -> LooseSupportParams:
        """The contact law (tilt-ignored line contact, frictionless) of :mod:`contact.loose_support`."""
        return LooseSupportParams(clearance_m=self.clearance_m if clearance_m is None else clearance_m,
                                  width_m=self.ring_width_m, bearing_E_Pa=self.modulus_Pa, bearing_nu=0.3,
                                  support_E_Pa=self.modulus_Pa, support_nu=0.3,
                                  c_c_s_per_m=self.collision_factor_s_m, tilt_ignored=True, law=self.law)


def jeffcott_system(params: JeffcottParams, speed_rad_s: float, *, clearance_m: float | None = None) -> RotorSystem:
    """The rotor at spin speed ``speed_rad_s`` (rad/s): DOFs ``(y, z, θy, θz)``, unbalance ``m e Ω²``
    as ``(cos, sin)`` in ``(y, z)`` (forward whirl), the ring on ground. ``clearance_m`` overrides δ0."""
    p = params
    m, jt = p.mass_kg, p.tilt_inertia_kg_m2
    ct = 2.0 * p.tilt_damping_ratio * math.sqrt(p.tilt_stiffness_Nm_rad * jt)
    M = np.diag([m, m, jt, jt])
    C = np.diag([p.damping_N_s_m, p.damping_N_s_m, ct, ct])
    K = np.diag([p.stiffness_N_m, p.stiffness_N_m, p.tilt_stiffness_Nm_rad, p.tilt_stiffness_Nm_rad])
    amp = m * p.eccentricity_m * speed_rad_s ** 2
    force = HarmonicForce(np.zeros(4), np.array([1.0]), np.array([[amp, 0.0, 0.0, 0.0]]),
                          np.array([[0.0, amp, 0.0, 0.0]]), float(speed_rad_s))
    law = support_law_from_params(p.law_params(clearance_m))
    support = LooseSupport((0, 1, 2, 3), None, law, p.ring_width_m, 0.0, 0.0, tilt_ignored=True)
    return RotorSystem(M, C, np.zeros((4, 4)), K, float(speed_rad_s), force, np.zeros(4), np.zeros((0, 4)),
                       support, ("y", "z", "theta_y", "theta_z"))


def contact_force_N(params: JeffcottParams, radius_m, clearance_m: float | None = None) -> np.ndarray:
    """Radial contact force magnitude ``f(r − δ0)`` (N) at orbit radius ``radius_m`` (m), zero radial
    velocity, from the suite's law (:func:`contact.loose_support.loose_support_force`)."""
    r = np.atleast_1d(np.asarray(radius_m, dtype=float))
    res = loose_support_force(params.law_params(clearance_m), r, np.zeros_like(r))
    return -np.asarray(res.Fy_N, dtype=float).reshape(r.shape)


def warped_frequency(speed_rad_s, steps_per_rev: int):
    """``Ω' = (2/Δt) tan(ΩΔt/2)`` with ``Δt = 2π/(Ω N)``: the frequency the trapezoidal rule's inertia and
    damping see on a harmonic of the spin speed sampled ``N`` times per revolution (rad/s)."""
    h = math.pi / int(steps_per_rev)
    return np.asarray(speed_rad_s, dtype=float) * (math.tan(h) / h)


def _warp(steps_per_rev: int | None) -> float:
    return 1.0 if steps_per_rev is None else float(warped_frequency(1.0, steps_per_rev))


def closed_form_residual(params: JeffcottParams, radius_m: float, speed_rad_s: float,
                         steps_per_rev: int | None = None, clearance_m: float | None = None) -> float:
    """``((k − mΩ'²) r + f)² + (cΩ' r)² − (m e Ω²)²`` over ``(m e Ω²)²`` (–); ``steps_per_rev`` None: Ω' = Ω."""
    p = params
    w = speed_rad_s * _warp(steps_per_rev)
    f = float(contact_force_N(p, radius_m, clearance_m)[0])
    load = p.mass_kg * p.eccentricity_m * speed_rad_s ** 2
    return (((p.stiffness_N_m - p.mass_kg * w * w) * radius_m + f) ** 2 + (p.damping_N_s_m * w * radius_m) ** 2
            - load ** 2) / load ** 2


def closed_form_speeds(params: JeffcottParams, radius_m: float, steps_per_rev: int | None = None,
                       clearance_m: float | None = None) -> np.ndarray:
    """Speeds (rad/s, ascending) at which the circular orbit has radius ``radius_m``: the positive roots
    of the closed form as a quadratic in ``s = Ω²`` (Ω' = κΩ, κ from :func:`warped_frequency`)::

        (m²κ⁴ r² − m² e²) s² + (c²κ² r² − 2 m κ² r (k r + f)) s + (k r + f)² = 0
    """
    p = params
    kap2 = _warp(steps_per_rev) ** 2
    r = float(radius_m)
    g = p.stiffness_N_m * r + float(contact_force_N(p, r, clearance_m)[0])
    a = p.mass_kg ** 2 * (kap2 ** 2 * r * r - p.eccentricity_m ** 2)
    b = p.damping_N_s_m ** 2 * kap2 * r * r - 2.0 * p.mass_kg * kap2 * r * g
    roots = np.roots([a, b, g * g])
    s = np.sort(roots[(np.abs(roots.imag) <= 1e-12 * np.abs(roots)) & (roots.real > 0)].real)
    return np.sqrt(s)


def closed_form_radius(params: JeffcottParams, speed_rad_s: float, guess_m: float,
                       steps_per_rev: int | None = None, clearance_m: float | None = None) -> float:
    """The orbit radius (m) at ``speed_rad_s`` nearest ``guess_m``: root of :func:`closed_form_residual`
    bracketed by stepping outwards from the guess (factor 1.001 per step) and refined by Brent's method."""
    def g(r):
        return closed_form_residual(params, r, speed_rad_s, steps_per_rev, clearance_m)

    g0 = g(guess_m)
    for i in range(1, 2000):
        for r in (guess_m * 1.001 ** i, guess_m / 1.001 ** i):
            if np.sign(g(r)) != np.sign(g0):
                a, b = sorted((r, guess_m * 1.001 ** (i - 1) if r > guess_m else guess_m / 1.001 ** (i - 1)))
                return float(brentq(g, a, b, xtol=1e-16, rtol=1e-14))
    raise ValueError(f"no orbit radius near {guess_m:g} m at {speed_rad_s:g} rad/s")


def closed_form_folds(params: JeffcottParams, steps_per_rev: int | None = None, clearance_m: float | None = None,
                      r_max_factor: float = 100.0) -> list[tuple[float, float]]:
    """Turning points ``(speed_rad_s, radius_m)`` of the response curve (the jump speeds): the local
    extrema of the larger root of :func:`closed_form_speeds` over the radius, located on a logarithmic
    grid of radii from the clearance to ``r_max_factor`` δ0 and refined by a bounded scalar minimisation.
    The radius ``e/κ²`` where that root runs off to infinite speed (the high-speed asymptote of an
    unbalance response) is excluded."""
    d0 = params.clearance_m if clearance_m is None else clearance_m

    def upper(r):
        s = closed_form_speeds(params, r, steps_per_rev, clearance_m)
        return s[-1] if len(s) else math.nan

    rs = d0 * np.geomspace(1.0 + 1e-6, r_max_factor, 4000)
    w = np.array([upper(r) for r in rs])
    r_inf = params.eccentricity_m / _warp(steps_per_rev) ** 2   # Ω → ∞ as r → e/κ²: not a turning point
    out = []
    for i in range(1, len(rs) - 1):
        if not np.isfinite(w[i - 1:i + 2]).all() or abs(rs[i] / r_inf - 1.0) < 0.01:
            continue
        if (w[i] - w[i - 1]) * (w[i + 1] - w[i]) < 0:
            sign = 1.0 if w[i] < w[i - 1] else -1.0   # minimum: +, maximum: − (minimise sign·Ω)
            res = minimize_scalar(lambda r: sign * upper(r), bounds=(rs[i - 1], rs[i + 1]), method="bounded",
                                  options={"xatol": 1e-14})
            out.append((float(upper(res.x)), float(res.x)))
    return out


def closed_form_grazing(params: JeffcottParams, steps_per_rev: int | None = None, clearance_m: float | None = None,
                        rel_step: float = 1e-7) -> list[tuple[float, str]]:
    """Speeds (rad/s, ascending) where the orbit grazes the ring (radius ``δ0``) and their kind: "grazing_fold"
    where the speed turns at the corner, "grazing" where it passes on. The kind compares the speed of the root
    nearest each grazing speed at the radii ``δ0 (1 ∓ rel_step)`` (free side, contact side)."""
    d0 = params.clearance_m if clearance_m is None else clearance_m
    out = []
    for w in closed_form_speeds(params, d0, steps_per_rev, clearance_m):
        near = [s[np.argmin(np.abs(s - w))] - w
                for s in (closed_form_speeds(params, d0 * (1.0 + k * rel_step), steps_per_rev, clearance_m)
                          for k in (-1.0, 1.0))]
        out.append((float(w), "grazing_fold" if near[0] * near[1] > 0 else "grazing"))
    return out
