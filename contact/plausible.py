"""Plausible ranges of every physical input, in the unit the user types it (one table, checked at the edge).

A value outside its range is refused with :class:`~contact.errors.InputError` naming the input, the
value as typed with its unit and the range: a 5 mm penetration, a 200e9 GPa modulus or 1e30 rpm is a
typing or unit mistake, not a question the suite can answer. The ranges are wide on purpose (they
catch the absurd, not the unusual); the reason for each bound is the last field of its row.
``docs`` and ``ringcontact --ranges`` print this table.
"""
from __future__ import annotations

import math

from contact.errors import InputError

# name (with its unit) -> (low, high, unit, low allowed?, high allowed?, why the bounds)
RANGES: dict[str, tuple[float, float, str, bool, bool, str]] = {
    # contact: command line
    "penetration_mm": (-1.0, 2.0, "mm", True, True, "20x past the paper's 0.05 mm clearance on a 10 mm ring; negative = no contact"),
    "tilt_arcmin": (-600.0, 600.0, "arcmin", True, True, "10 deg: beyond any bearing misalignment"),
    "clearance_mm": (0.0, 2.0, "mm", False, True, "radial clearance of a bearing seat (paper 0.01-0.08 mm)"),
    "width_mm": (1.0, 500.0, "mm", True, True, "ring width l0 (paper 30 mm)"),
    "E_GPa": (1.0, 1000.0, "GPa", True, True, "polymers to tungsten carbide"),
    "nu": (-1.0, 0.5, "-", False, False, "Poisson's ratio of an isotropic solid"),
    "h_mm": (0.1, 10.0, "mm", True, True, "FEM contact element size: finer does not finish, coarser is not a mesh of a 10 mm ring"),
    "scale": (-1e6, 1e6, "-", True, True, "displacement magnification for viewing"),
    "tol": (0.0, 1.0, "-", False, True, "relative difference"),
    # rotor: command line
    "speed_rpm": (0.0, 200000.0, "rpm", True, True, "200 000 rpm: beyond any aero-engine spool"),
    "rpm_max": (0.0, 200000.0, "rpm", False, True, "top of a speed range"),
    "run_speed_rpm": (0.0, 200000.0, "rpm", False, True, "spin speed of a time integration (> 0: the step is a fraction of a revolution)"),
    "revolutions": (0.0, 100000.0, "rev", False, True, "a run longer than 1e5 revolutions does not fit a working day"),
    "duration_s": (0.0, 3600.0, "s", False, True, "run-up duration: an hour at most"),
    "mu": (0.0, 2.0, "-", True, True, "dry friction coefficient"),
    "preload_N": (0.0, 1e7, "N", True, True, "nut preload per face: 10 MN crushes any bearing"),
    "misalignment_mm": (0.0, 50.0, "mm", True, True, "misalignment offset δ (paper 0.5-3 mm)"),
    # rotor scene files (TOML keys)
    "density_kg_m3": (0.0, 30000.0, "kg/m^3", True, True, "0 (massless model) to osmium"),
    "youngs_modulus_gpa": (1.0, 1000.0, "GPa", True, True, "polymers to tungsten carbide"),
    "bearing_modulus_gpa": (1.0, 1000.0, "GPa", True, True, "polymers to tungsten carbide"),
    "support_modulus_gpa": (1.0, 1000.0, "GPa", True, True, "polymers to tungsten carbide"),
    "x_mm": (-100000.0, 100000.0, "mm", True, True, "a rotor shorter than 200 m"),
    "outer_diameter_mm": (1.0, 5000.0, "mm", True, True, "a shaft or disk, not a wire or a building"),
    "inner_diameter_mm": (0.0, 5000.0, "mm", True, True, "bore of a hollow shaft or of a disk"),
    "thickness_mm": (0.1, 5000.0, "mm", True, True, "axial thickness of a disk"),
    "ring_width_mm": (1.0, 500.0, "mm", True, True, "ring width l0 (paper 30 mm)"),
    "mass_kg": (0.0, 1e6, "kg", True, True, "up to a 1000 t turbine-generator rotor part"),
    "shaft_mass_kg": (0.0, 1e6, "kg", True, True, "up to a 1000 t rotor part"),
    "unbalance_g_mm": (0.0, 1e8, "g·mm", True, True, "100 kg·m: far beyond any balance grade of a 1000 t rotor part"),
    "stiffness_n_per_m": (0.0, 1e13, "N/m", True, True, "stiffer than 1e13 N/m is a rigid boundary: fix the DOF"),
    "stiffness_yy_n_per_m": (0.0, 1e13, "N/m", True, True, "stiffer than 1e13 N/m is a rigid boundary: fix the DOF"),
    "stiffness_zz_n_per_m": (0.0, 1e13, "N/m", True, True, "stiffer than 1e13 N/m is a rigid boundary: fix the DOF"),
    "stiffness_yz_n_per_m": (-1e13, 1e13, "N/m", True, True, "cross-coupling beyond a rigid boundary's stiffness"),
    "stiffness_zy_n_per_m": (-1e13, 1e13, "N/m", True, True, "cross-coupling beyond a rigid boundary's stiffness"),
    # dampers: beyond 1e10 N·s/m is past critical damping of a 1e13 N/m mount under a 1000 t rotor (2 sqrt(k m))
    "damping_n_s_per_m": (0.0, 1e10, "N·s/m", True, True, "past critical damping of any rotor's mount: fix the DOF"),
    "damping_yy_n_s_per_m": (0.0, 1e10, "N·s/m", True, True, "past critical damping of any rotor's mount: fix the DOF"),
    "damping_zz_n_s_per_m": (0.0, 1e10, "N·s/m", True, True, "past critical damping of any rotor's mount: fix the DOF"),
    "damping_yz_n_s_per_m": (-1e10, 1e10, "N·s/m", True, True, "cross-coupled damping beyond any mount's direct damping"),
    "damping_zy_n_s_per_m": (-1e10, 1e10, "N·s/m", True, True, "cross-coupled damping beyond any mount's direct damping"),
    "angular_stiffness_n_m_per_rad": (0.0, 1e12, "N·m/rad", True, True, "stiffer than 1e12 N·m/rad is a clamp: fix the DOF"),
    "angular_damping_n_m_s_per_rad": (0.0, 1e9, "N·m·s/rad", True, True, "past critical damping of any tilting mount"),
    "speed_table_rpm": (0.0, 200000.0, "rpm", True, True, "200 000 rpm: beyond any aero-engine spool"),
    "acceleration_y_m_per_s2": (-1e4, 1e4, "m/s^2", True, True, "1000 g: a shock test, not a steady load"),
    "acceleration_z_m_per_s2": (-1e4, 1e4, "m/s^2", True, True, "1000 g: a shock test, not a steady load"),
    "force_y_n": (-1e9, 1e9, "N", True, True, "1 GN: beyond any rotor's static load"),
    "force_z_n": (-1e9, 1e9, "N", True, True, "1 GN: beyond any rotor's static load"),
    "moment_y_n_m": (-1e9, 1e9, "N·m", True, True, "1 GN·m: beyond any rotor's static moment"),
    "moment_z_n_m": (-1e9, 1e9, "N·m", True, True, "1 GN·m: beyond any rotor's static moment"),
    "max_speed_rpm": (0.0, 200000.0, "rpm", False, True, "200 000 rpm: beyond any aero-engine spool"),
    "friction_coefficient": (0.0, 2.0, "-", True, True, "dry friction coefficient"),
    "preload_n": (0.0, 1e7, "N", True, True, "nut preload per face"),
    "offset_mm": (-50.0, 50.0, "mm", True, True, "misalignment offset δ"),
    "lever_mm": (0.0, 100000.0, "mm", True, True, "a lever shorter than the rotor"),
    "speed_points": (1, 10000, "-", True, True, "speeds of a linear sweep"),
    "modes": (1, 200, "-", True, True, "modes of a rotor model"),
    "elements": (1, 64, "-", True, True, "elements per shaft segment (64 resolve any mode below 1 MHz)"),
    # ring-pair files (fem_reference.ring_scene) and the calibrated-law files made from them (contact.calibrate)
    "ring_length_mm": (1e-4, 10000.0, "mm", True, True, "a ring's radius, thickness, width or clearance: wrong unit? millimetres expected"),
    "ring_modulus_gpa": (0.5, 1200.0, "GPa", True, True, "soft polymers to tungsten carbide: 7.2e10 typed here is Pa, not GPa"),
    "stiffness_factor": (0.0, 1000.0, "-", False, True, "factor on the conformal law's stiffness (1: the law as published)"),
    "foundation_modulus_pa_per_m": (0.0, 1e18, "Pa/m", False, True, "1000 GPa over 1 um of ring: stiffer is no ring"),
    "law_exponent": (0.5, 5.0, "-", True, True, "force ~ penetration^n: 1 (line contact) to 1.5 (Hertz point) in practice"),
    "far_field_constant": (-1000.0, 1000.0, "-", True, True, "the conformal-compliance law's far-field constant C (fits give 1-5)"),
}

#: largest penetration a law holds for, as a fraction of the contact radius (small-strain limit of both FEM
#: references; a ring-pair file's range and a law file's validity)
MAX_PENETRATION_TO_RADIUS = 0.02
#: largest radial clearance, as a fraction of the contact radius (a larger gap is not a bearing seat)
MAX_CLEARANCE_TO_RADIUS = 0.05
#: largest tilt (arcmin) of a ring-pair file's range and a law file's validity (small-rotation model)
MAX_TILT_ARCMIN = 60.0


def range_text(name: str) -> str:
    """``"in [-1, 2] mm"`` for ``name`` (open ends shown with parentheses)."""
    lo, hi, unit, lo_in, hi_in, _ = RANGES[name]
    u = "" if unit == "-" else f" {unit}"
    return f"in {'[' if lo_in else '('}{lo:g}, {hi:g}{']' if hi_in else ')'}{u}"


def top(name: str) -> float:
    """The high end of ``name``'s range: the one bound a job and its parser share (e.g. the highest speed)."""
    return RANGES[name][1]


def inside(name: str, value: float) -> bool:
    """True if ``value`` is finite and inside the plausible range of ``name``."""
    lo, hi, _, lo_in, hi_in, _ = RANGES[name]
    if not math.isfinite(value):
        return False
    return (value >= lo if lo_in else value > lo) and (value <= hi if hi_in else value < hi)


def check(name: str, value: float, shown: str | None = None, *, label: str | None = None) -> float:
    """Return ``value`` if plausible, else raise :class:`InputError` "``label = shown unit: must be in [..]``".

    ``shown`` is the value as the user typed it (default: ``value`` formatted), ``label`` the name the
    user knows (a flag, a TOML key; default ``name``).
    """
    if inside(name, value):
        return value
    unit = RANGES[name][2]
    typed = f"{value:g}" if shown is None else shown
    head = f"{label or name} = {typed}" + ("" if unit == "-" else f" {unit}")
    why = "must be finite" if not math.isfinite(value) else f"must be {range_text(name)}"
    raise InputError(f"{head}: {why} ({RANGES[name][5]})")


def check_field(where: str, key: str, value, shown: str, si) -> None:
    """A file field (a scene's TOML key): finite, and inside ``RANGES[key]`` when the key has a range."""
    if isinstance(si, float) and not math.isfinite(si):
        raise InputError(f"{where}.{key} = {shown}: must be finite")
    if key in RANGES and isinstance(value, (int, float)) and not isinstance(value, bool):
        check(key, float(value), shown, label=f"{where}.{key}")


def check_scaled(name: str, value_si: float, si_per_unit: float, label: str, typed: str, typed_unit: str) -> float:
    """A value held in SI in a file (``typed`` as written there, in ``typed_unit``) inside ``RANGES[name]``.

    ``si_per_unit`` converts the row's unit to SI (1e9 for GPa). The refusal names ``label``, the value as
    written with its unit, the value in the row's unit and the range, e.g.
    ``geometry.bearing_E_Pa = -2.04e+11 Pa (-204 GPa): must be in [0.5, 1200] GPa (...)``.
    """
    value = value_si / si_per_unit
    if inside(name, value):
        return value_si
    unit = RANGES[name][2]
    shown = f"{typed} {typed_unit}".rstrip()
    if si_per_unit != 1.0 or unit not in ("-", typed_unit):
        shown += f" ({value:g} {unit})"
    why = "must be finite" if not math.isfinite(value) else f"must be {range_text(name)}"
    raise InputError(f"{label} = {shown}: {why} ({RANGES[name][5]})")
