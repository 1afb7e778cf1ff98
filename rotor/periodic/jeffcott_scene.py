"""A Jeffcott rotor in a conformal clearance ring written as an ordinary rotor scene, with its closed form.

:mod:`rotor.periodic.jeffcott` verifies the orbit tools on an internal four-DOF model. This module writes
the same physics as a scene file (``ringcontact.rotor-scene/1``) that every job reads, so the checks run
through the scene parser, the assembly, the static condensation and the loose-support node of a real rotor:

* a disk of mass ``m`` at mid-span of a massless steel shaft of length ``L`` and diameter ``d`` on two
  bearings of stiffness ``k_b`` (no damping); the disk station's lateral stiffness is the Jeffcott (1919)
  ``k`` with ``1/k = L³/(48 EI) + L/(4 κ G A) + 1/(2 k_b)`` (Timoshenko shaft, κ the Cowper (1966) shear
  coefficient of :func:`rotor.model.elements.cowper_shear_coefficient`);
* viscous damping ``c`` at the disk (a bearing of zero stiffness; its angular damping ``c (L/4)²`` damps the
  disk's tilt, which the whirl does not excite), unbalance ``m e``;
* the disk station carries the loose bearing: its ring meets a support node of mass ``m_s`` on a spring
  ``k_s`` and damper ``c_s`` to ground through the radial clearance ``δ0`` with the paper's conformal law
  (Dai et al. 2025 Eq. 5) and no end-face friction (``μ = 0``).

Exact synchronous orbit
-----------------------
By symmetry the disk does not tilt, so the forward whirls ``X e^{iΩt}`` of the disk and ``S e^{iΩt}`` of the
support are exact: the relative motion ``D = X − S`` is a circle of radius ``r = |D|``, the contact force is
radial with magnitude ``f(r − δ0)`` and the Lankarani–Nikravesh factor is 1 (no radial velocity). With
``A = k − mΩ'² + i c Ω'``, ``B = k_s − m_s Ω'² + i c_s Ω'`` and ``g = f/r``::

    A X + g D = m e Ω²,   B S − g D = 0   ⇒   r |A (B + g) + g B| = m e Ω² |B|

``Ω' = Ω`` in continuous time; the average-acceleration Newmark scheme at ``N`` steps per revolution has the
exact discrete orbit with the warped ``Ω' = Ω tan(π/N)/(π/N)`` in the inertia and damping terms and ``Ω`` in
the load (the argument of :mod:`rotor.periodic.jeffcott`, which holds node by node here). For a given radius
the equation squared is a real polynomial of degree 8 in Ω: :func:`closed_form_speeds` takes its positive
roots; :func:`closed_form_folds` the turning points (double roots), :func:`closed_form_grazing` the roots
at ``r = δ0``. :func:`random_family` draws a seeded family of such rotors.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import polynomial as P
from scipy.optimize import brentq

from contact.loose_support import LooseSupportParams, loose_support_force
from rotor.model.elements import cowper_shear_coefficient

STEEL_E_PA, STEEL_NU = 200e9, 0.3


@dataclass(frozen=True)
class JeffcottRing:
    """A Jeffcott rotor whose disk station carries a loose bearing ring (SI units).

    Attributes
    ----------
    mass_kg : disk mass m.
    shaft_length_m, shaft_diameter_m : massless steel shaft (E 200 GPa, ν 0.3), disk at mid-span.
    bearing_stiffness_N_m : each end bearing's stiffness k_b.
    damping_N_s_m : viscous damping c at the disk.
    eccentricity_m : unbalance eccentricity e (unbalance m e).
    clearance_m : radial clearance δ0.
    ring_width_m, ring_modulus_Pa : the ring's width and Young's modulus (ring and support, ν 0.3).
    support_mass_kg, support_stiffness_N_m, support_damping_N_s_m : the support node m_s, k_s, c_s.
    support_inertia_kg_m2, support_angular_stiffness_Nm_rad : its (unexcited) tilt oscillator.
    """

    mass_kg: float = 10.0
    shaft_length_m: float = 0.8
    shaft_diameter_m: float = 0.02
    bearing_stiffness_N_m: float = 2.0e6
    damping_N_s_m: float = 60.0
    eccentricity_m: float = 20e-6
    clearance_m: float = 50e-6
    ring_width_m: float = 0.02
    ring_modulus_Pa: float = 2.0e9
    support_mass_kg: float = 2.0
    support_stiffness_N_m: float = 2.0e6
    support_damping_N_s_m: float = 200.0
    support_inertia_kg_m2: float = 0.01
    support_angular_stiffness_Nm_rad: float = 1.0e4

    @property
    def stiffness_N_m(self) -> float:
        """The disk station's lateral stiffness k (N/m): bending and shear of the shaft, then the bearings."""
        d, L = self.shaft_diameter_m, self.shaft_length_m
        area, inertia = math.pi * d * d / 4.0, math.pi * d ** 4 / 64.0
        shear_modulus = STEEL_E_PA / (2.0 * (1.0 + STEEL_NU))
        kappa = cowper_shear_coefficient(d, 0.0, STEEL_NU)
        flex = L ** 3 / (48.0 * STEEL_E_PA * inertia) + L / (4.0 * kappa * shear_modulus * area)
        return 1.0 / (flex + 1.0 / (2.0 * self.bearing_stiffness_N_m))

    def law_params(self) -> LooseSupportParams:
        """The line contact (tilt ignored: the orbit has no tilt) of :mod:`contact.loose_support`, frictionless."""
        return LooseSupportParams(clearance_m=self.clearance_m, width_m=self.ring_width_m,
                                  bearing_E_Pa=self.ring_modulus_Pa, bearing_nu=0.3, support_E_Pa=self.ring_modulus_Pa,
                                  support_nu=0.3, c_c_s_per_m=0.0, tilt_ignored=True, law="conformal")


def contact_force_N(rotor: JeffcottRing, radius_m: float) -> float:
    """Radial contact force magnitude ``f(r − δ0)`` (N) at relative orbit radius ``radius_m`` (m)."""
    res = loose_support_force(rotor.law_params(), float(radius_m), 0.0)
    return -float(res.Fy_N)


def scene_toml(rotor: JeffcottRing, name: str = "jeffcott-ring") -> str:
    """The rotor as a scene file's text (``ringcontact.rotor-scene/1``), every value in the scene's units."""
    p = rotor
    half = p.shaft_length_m / 2.0
    return f"""# A Jeffcott rotor in a conformal clearance ring (rotor/periodic/jeffcott_scene.py wrote it).
schema = "ringcontact.rotor-scene/1"
name = "{name}"
title = "Jeffcott rotor: disk at mid-span in a loose conformal ring"
source = "rotor/periodic/jeffcott_scene.py"
[[materials]]
name = "massless"
density_kg_m3 = 0
youngs_modulus_gpa = {STEEL_E_PA / 1e9!r}
poisson_ratio = {STEEL_NU!r}
[[stations]]
name = "A"
x_mm = 0
[[stations]]
name = "disk"
x_mm = {half * 1e3!r}
[[stations]]
name = "B"
x_mm = {p.shaft_length_m * 1e3!r}
[[shafts]]
from = "A"
to = "disk"
outer_diameter_mm = {p.shaft_diameter_m * 1e3!r}
material = "massless"
[[shafts]]
from = "disk"
to = "B"
outer_diameter_mm = {p.shaft_diameter_m * 1e3!r}
material = "massless"
[[disks]]
name = "d"
station = "disk"
mass_kg = {p.mass_kg!r}
polar_inertia_kg_m2 = 0
diametral_inertia_kg_m2 = {p.mass_kg * 1e-3!r}
unbalance_g_mm = {p.mass_kg * p.eccentricity_m * 1e6!r}
[[bearings]]
name = "bA"
station = "A"
stiffness_n_per_m = {p.bearing_stiffness_N_m!r}
[[bearings]]
name = "bB"
station = "B"
stiffness_n_per_m = {p.bearing_stiffness_N_m!r}
[[bearings]]
name = "damper"
station = "disk"
stiffness_n_per_m = 0
damping_n_s_per_m = {p.damping_N_s_m!r}
angular_damping_n_m_s_per_rad = {p.damping_N_s_m * (p.shaft_length_m / 4.0) ** 2!r}
[[supports]]
name = "housing"
station = "disk"
mass_kg = {p.support_mass_kg!r}
inertia_kg_m2 = {p.support_inertia_kg_m2!r}
stiffness_n_per_m = {p.support_stiffness_N_m!r}
damping_n_s_per_m = {p.support_damping_N_s_m!r}
angular_stiffness_n_m_per_rad = {p.support_angular_stiffness_Nm_rad!r}
angular_damping_n_m_s_per_rad = 1.0
[loose_support]
bearing_station = "disk"
support = "housing"
clearance_mm = {p.clearance_m * 1e3!r}
ring_width_mm = {p.ring_width_m * 1e3!r}
bearing_modulus_gpa = {p.ring_modulus_Pa / 1e9!r}
bearing_poisson_ratio = 0.3
support_modulus_gpa = {p.ring_modulus_Pa / 1e9!r}
support_poisson_ratio = 0.3
collision_factor_s_per_m = 0
friction_coefficient = 0
preload_n = 0
"""


def _warp(steps_per_rev: int | None) -> float:
    """``Ω'/Ω``: 1 in continuous time, ``tan(π/N)/(π/N)`` for the Newmark scheme at N steps per revolution."""
    if steps_per_rev is None:
        return 1.0
    h = math.pi / int(steps_per_rev)
    return math.tan(h) / h


def _balance_polynomial(rotor: JeffcottRing, radius_m: float, steps_per_rev: int | None) -> np.ndarray:
    """Coefficients (ascending powers of Ω) of ``r² |A(B + g) + gB|² − (m e)² Ω⁴ |B|²``, real for real Ω."""
    p, w = rotor, _warp(steps_per_rev)
    g = contact_force_N(p, radius_m) / radius_m
    A = np.array([p.stiffness_N_m, 1j * p.damping_N_s_m * w, -p.mass_kg * w * w])
    B = np.array([p.support_stiffness_N_m, 1j * p.support_damping_N_s_m * w, -p.support_mass_kg * w * w])
    poly = P.polyadd(P.polymul(A, P.polyadd(B, [g])), g * B)

    def abs2(c):        # |c(Ω)|² for real Ω: c(Ω) times the polynomial with conjugated coefficients
        return P.polymul(c, np.conj(c)).real

    load = np.array([0.0, 0.0, 0.0, 0.0, (p.mass_kg * p.eccentricity_m) ** 2])
    return P.polysub(radius_m ** 2 * abs2(poly), P.polymul(load, abs2(B)))


def closed_form_speeds(rotor: JeffcottRing, radius_m: float, steps_per_rev: int | None = None) -> np.ndarray:
    """Speeds (rad/s, ascending) at which the relative orbit has radius ``radius_m`` (m); ``steps_per_rev``
    None: continuous time, else the Newmark scheme's orbit at that many steps per revolution."""
    c = _balance_polynomial(rotor, radius_m, steps_per_rev)
    roots = P.polyroots(c)
    scale = np.maximum(np.abs(roots), 1.0)
    real = roots[(np.abs(roots.imag) <= 1e-9 * scale) & (roots.real > 0)].real
    return np.sort(real)


def closed_form_radius(rotor: JeffcottRing, speed_rad_s: float, guess_m: float,
                       steps_per_rev: int | None = None) -> float:
    """The relative orbit radius (m) at ``speed_rad_s`` nearest ``guess_m``: the root of the balance in r,
    bracketed by stepping outwards from the guess (factor 1.0005) and refined by Brent's method."""
    def h(r):
        return P.polyval(speed_rad_s, _balance_polynomial(rotor, r, steps_per_rev)) / r ** 2

    h0 = h(guess_m)
    for i in range(1, 4000):
        for r, prev in ((guess_m * 1.0005 ** i, guess_m * 1.0005 ** (i - 1)),
                        (guess_m / 1.0005 ** i, guess_m / 1.0005 ** (i - 1))):
            if np.sign(h(r)) != np.sign(h0):
                a, b = sorted((r, prev))
                return float(brentq(h, a, b, xtol=1e-18, rtol=1e-15))
    raise ValueError(f"no orbit radius near {guess_m:g} m at {speed_rad_s:g} rad/s")


def closed_form_folds(rotor: JeffcottRing, steps_per_rev: int | None = None, max_penetration: float = 9.0,
                      n_grid: int = 4000) -> list[tuple[float, float]]:
    """Smooth turning points ``(speed_rad_s, radius_m)`` of the response curve in contact: the local extrema of
    each root of :func:`closed_form_speeds` over the radius, located on a logarithmic grid of penetrations
    from 1e-10 δ0 to ``max_penetration`` δ0 (below the conformal law's neat-fit limit; roots matched in
    ascending order where their count holds) and refined by Brent's method on the root's slope."""
    d0 = rotor.clearance_m
    rs = d0 * (1.0 + np.geomspace(1e-10, max_penetration, n_grid))
    roots = [closed_form_speeds(rotor, r, steps_per_rev) for r in rs]

    def near(r, w):
        s = closed_form_speeds(rotor, r, steps_per_rev)
        return float(s[np.argmin(np.abs(s - w))]) if len(s) else math.nan

    out = []
    for i in range(1, len(rs) - 1):
        if not len(roots[i - 1]) == len(roots[i]) == len(roots[i + 1]):
            continue
        for j, w in enumerate(roots[i]):
            a, b = roots[i - 1][j], roots[i + 1][j]
            if (w - a) * (b - w) >= 0:
                continue

            def slope(r, w=w):      # dΩ/dr of the root through (r, ~w) by a central difference
                h = 1e-7 * (r - d0)
                return (near(r + h, w) - near(r - h, w)) / (2.0 * h)

            try:
                r_f = brentq(slope, rs[i - 1], rs[i + 1], xtol=1e-16 * d0, rtol=1e-13)
            except ValueError:
                r_f = rs[i]
            out.append((near(r_f, w), float(r_f)))
    return out


def closed_form_grazing(rotor: JeffcottRing, steps_per_rev: int | None = None,
                        rel_step: float = 1e-7) -> list[tuple[float, str]]:
    """Speeds (rad/s, ascending) where the orbit grazes the ring (``r = δ0``) and their kind: "grazing_fold"
    where the speed turns at the corner, "grazing" where it passes on (compared at ``δ0 (1 ∓ rel_step)``)."""
    d0 = rotor.clearance_m
    out = []
    for w in closed_form_speeds(rotor, d0, steps_per_rev):
        near = [s[np.argmin(np.abs(s - w))] - w
                for s in (closed_form_speeds(rotor, d0 * (1.0 + k * rel_step), steps_per_rev) for k in (-1.0, 1.0))]
        out.append((float(w), "grazing_fold" if near[0] * near[1] > 0 else "grazing"))
    return out


def random_family(seed: int, count: int = 10) -> list[JeffcottRing]:
    """``count`` rotors with random mass (5-20 kg), shaft (d 15-25 mm, which with the bearings sets k), damping
    ratio (2-8 %), clearance (20-80 µm), unbalance (0.3-0.8 δ0 of eccentricity) and support (k_s 2.5-5 k, m_s
    0.1-0.4 m, 5 % damping), seeded by ``seed`` (numpy's default generator). Only rotors whose response has
    the jump are kept (a smooth fold on the contact branch besides the isolated high-speed branch's,
    :func:`closed_form_folds`); draws go on until ``count`` are kept."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        base = JeffcottRing(mass_kg=float(rng.uniform(5.0, 20.0)), shaft_diameter_m=float(rng.uniform(0.015, 0.025)))
        k, m = base.stiffness_N_m, base.mass_kg
        clearance = float(rng.uniform(20e-6, 80e-6))
        ms, ks = float(rng.uniform(0.1, 0.4)) * m, float(rng.uniform(2.5, 5.0)) * k
        rotor = JeffcottRing(
            mass_kg=m, shaft_diameter_m=base.shaft_diameter_m,
            damping_N_s_m=float(2.0 * rng.uniform(0.02, 0.08) * math.sqrt(k * m)),
            eccentricity_m=float(rng.uniform(0.3, 0.8)) * clearance, clearance_m=clearance,
            support_mass_kg=ms, support_stiffness_N_m=ks, support_damping_N_s_m=float(2.0 * 0.05 * math.sqrt(ks * ms)))
        if len(closed_form_folds(rotor)) >= 2:
            out.append(rotor)
    return out
