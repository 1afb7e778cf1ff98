"""What a sweep is made of: independent :class:`Task` points and the :class:`PointResult` of one.

A task is a key, a top-level (picklable) function and JSON parameters; the function returns
``(arrays, info)``: a dict of numpy arrays and a JSON-serialisable dict. The store
(:mod:`sweep.store`) keeps both, :func:`sweep.run.run_sweep` computes the missing ones.
"""
from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from typing import Callable

from contact.errors import InputError

_KEY = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.+-]{0,120}$")


@dataclass(frozen=True)
class Task:
    """One independent point of a sweep.

    Attributes
    ----------
    key : str
        Unique, file-safe name (letters, digits, ``_ . + -``), e.g. ``rpm10500``.
    func : callable
        Top-level (picklable) function ``func(**params) -> (arrays: dict[str, ndarray], info: dict)``;
        ``info`` must be JSON-serialisable.
    params : dict
        JSON-serialisable keyword arguments, units in the names (``speed_rpm``, ``clearance_m``).
    """

    key: str
    func: Callable
    params: dict = field(default_factory=dict)

    def __post_init__(self):
        if not _KEY.match(self.key):
            raise InputError(f"task key {self.key!r}: use letters, digits, '_', '.', '+', '-' (max 121 chars)")
        try:
            json.dumps(self.params, sort_keys=True)
        except TypeError as e:
            raise InputError(f"task {self.key}: params are not JSON-serialisable ({e})") from None


@dataclass
class PointResult:
    """A stored point: its arrays (read from NPZ) and its JSON record."""

    key: str
    arrays: dict
    record: dict

    @property
    def info(self) -> dict:
        return self.record.get("info", {})

    @property
    def params(self) -> dict:
        return self.record.get("params", {})
