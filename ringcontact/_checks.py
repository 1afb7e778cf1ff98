"""The API's arguments checked with the command line's own ranges, messages and work budget (one source).

Each check runs the very ``type=`` the job's option uses (:func:`reports.cli._edge.quantity` for a physical
value, :func:`reports.cli._edge.count` with :data:`reports.cli._edge.COUNTS` for a whole number) on the value
in the option's unit, and raises :class:`~contact.errors.InputError` with the keyword, its value in SI and the
command line's own words: ``penetration_m = -1 m, i.e. --penetration-mm = -1000 mm: must be in [-1, 2] mm``.
Long work is estimated and refused as the jobs do (:mod:`reports.cli._budget`), accepted with the keyword
``accept_long=True`` where the jobs take ``--accept-long``.
"""
from __future__ import annotations

import argparse
import numbers
import os

import numpy as np

from contact.errors import InputError
from reports.cli import _budget
from reports.cli._edge import COUNTS, count, quantity

#: how the API accepts work beyond the budget (the jobs' ``--accept-long``)
OVERRIDE = "accept_long=True"


def _typed(value: float) -> str:
    return f"{value:.15g}"


def number(keyword: str, value, flag: str, range_name: str, si_per_unit: float = 1.0, si_unit: str = "") -> float:
    """``value`` (SI) as float if the option ``flag`` would take ``value / si_per_unit`` (its plausible range)."""
    unit = f" {si_unit}" if si_unit else ""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputError(f"{keyword} = {value!r}: must be a number{unit}")
    v = float(value)
    try:
        quantity(range_name)(_typed(v / si_per_unit))
    except argparse.ArgumentTypeError as exc:
        raise InputError(f"{keyword} = {v:g}{unit}, i.e. {flag} {exc}") from None
    return v


def numbers_in(keyword: str, values, flag: str, range_name: str, si_per_unit: float = 1.0,
               si_unit: str = "") -> np.ndarray:
    """Every element of ``values`` through :func:`number` (the first bad one named); a float array."""
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{keyword} = {str(values)[:60]}: must be numbers ({si_unit or '-'})") from None
    for v in arr.ravel():
        number(keyword, float(v), flag, range_name, si_per_unit, si_unit)
    return arr


def whole(keyword: str, value, flag: str, key: str, *, low: int | None = None) -> int:
    """``value`` as int if the option ``flag`` would take it (``COUNTS[key]``; ``low`` narrows the low end)."""
    lo, hi, what = COUNTS[key]
    lo = lo if low is None else low
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not np.isfinite(value) \
            or value != int(value):
        raise InputError(f"{keyword} = {value!r}: must be a whole number, i.e. {flag} in [{lo}, {hi}]")
    try:
        count(lo, hi, what)(str(int(value)))
    except argparse.ArgumentTypeError as exc:
        raise InputError(f"{keyword} = {int(value)}, i.e. {flag} {exc}") from None
    return int(value)


def speed_list(keyword: str, values, flag: str, range_name: str, key: str, *, low: int = 1) -> np.ndarray:
    """A 1-D list of speeds (rpm): ``low`` to ``COUNTS[key]`` of them (the jobs' ``--points``), each in range."""
    size, hi = int(np.size(values)) if np.ndim(values) else 1, COUNTS[key][1]
    if not low <= size <= hi:             # the count first: 200 000 speeds are refused before each is read
        raise InputError(f"{keyword}: {size} speeds, i.e. --points = {size}: must be in [{low}, {hi}]")
    arr = numbers_in(keyword, np.atleast_1d(values) if np.ndim(values) == 0 else values, flag, range_name,
                     si_unit="rpm")
    if arr.ndim != 1:
        raise InputError(f"{keyword}: a list of speeds (rpm), not a {arr.ndim}-D array")
    return arr


def flag_of(keyword: str, value) -> bool:
    """``value`` if it is a bool (``damped``, ``steady`` …)."""
    if not isinstance(value, (bool, np.bool_)):
        raise InputError(f"{keyword} = {value!r}: must be True or False")
    return bool(value)


def budget(func: str, est, accept_long, cause: str, remedy: str) -> None:
    """The jobs' budget (:func:`reports.cli._budget.check`) for ``ringcontact.<func>``, overridden by the keyword."""
    _budget.check(f"ringcontact.{func}", est, flag_of("accept_long", accept_long), cause, remedy, override=OVERRIDE)


def scene_argument(scene) -> None:
    """Refuse what cannot name a scene (None, a number …) before any path is built from it."""
    if not isinstance(scene, (str, os.PathLike)) or not str(os.fspath(scene)).strip():
        from rotor.model.scene import bundled_scenes
        raise InputError(f"scene = {scene!r}: must be a ringcontact.Scene, a scene file's path (.toml) or a bundled "
                         f"scene's name ({', '.join(bundled_scenes())})")
