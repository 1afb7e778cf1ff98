"""Unit conversion at the edge: engineers type mm, rpm, arcminutes; the code uses SI."""
from __future__ import annotations

import math

import numpy as np

from contact.errors import InputError

MM = 1e-3                      # m per mm
ARCMIN = math.pi / (180 * 60)  # rad per arcminute
DEG = math.pi / 180            # rad per degree
RPM = 2 * math.pi / 60         # rad/s per rpm
GPA = 1e9                      # Pa per GPa
MPA = 1e6                      # Pa per MPa


def mm_to_m(value_mm):
    """Millimetres to metres."""
    return np.asarray(value_mm, dtype=float) * MM if np.ndim(value_mm) else float(value_mm) * MM


def arcmin_to_rad(value_arcmin):
    """Arcminutes to radians."""
    return np.asarray(value_arcmin, dtype=float) * ARCMIN if np.ndim(value_arcmin) else float(value_arcmin) * ARCMIN


def rpm_to_rad_s(value_rpm):
    """Revolutions per minute to rad/s."""
    return np.asarray(value_rpm, dtype=float) * RPM if np.ndim(value_rpm) else float(value_rpm) * RPM


def check_finite(name: str, value, unit: str):
    """Raise :class:`InputError` naming ``name`` if ``value`` holds NaN or inf."""
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)):
        bad = arr[~np.isfinite(arr)].ravel()[0] if arr.ndim else arr
        raise InputError(f"{name} = {bad} {unit}: must be finite")
    return value


def check_positive(name: str, value, unit: str, *, allow_zero: bool = False, upper: float | None = None):
    """Raise :class:`InputError` unless every element of ``value`` is finite and > 0 (>= 0).

    ``upper`` (same unit) catches values typed in the wrong unit, e.g. a clearance
    of 0.05 meant as mm but passed as metres.
    """
    check_finite(name, value, unit)
    arr = np.asarray(value, dtype=float)
    bad = arr < 0 if allow_zero else arr <= 0
    if np.any(bad):
        v = arr[bad].ravel()[0] if arr.ndim else float(arr)
        rel = ">= 0" if allow_zero else "> 0"
        raise InputError(f"{name} = {v:g} {unit}: must be {rel}")
    if upper is not None and np.any(arr > upper):
        v = arr[arr > upper].ravel()[0] if arr.ndim else float(arr)
        raise InputError(f"{name} = {v:g} {unit}: must be <= {upper:g} {unit} (wrong unit? SI expected)")
    return value
