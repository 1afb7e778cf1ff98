"""What a sweep is made of: independent :class:`Task` points and the :class:`PointResult` of one.

A task is a key, a top-level (picklable) function and JSON parameters; the function returns
``(arrays, info)``: a dict of numpy arrays and a JSON-serialisable dict. The store
(:mod:`sweep.store`) keeps both, :func:`sweep.run.run_sweep` computes the missing ones.

A task with ``outputs`` stores several points, each under its own key and parameters (e.g. a block of
speeds computed in sequence, each started from the previous one's state): it is done when all its
outputs are; otherwise its function is called with ``stored`` = the info of each output already stored
(key -> info dict) and returns ``{key: (arrays, info)}`` for the outputs it computed. The store, the
readers (:func:`sweep.store.load_sweep`) and ``sweep.json`` see only the output points
(:func:`point_tasks`).
"""
from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from typing import Callable

from contact.errors import InputError

_KEY = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.+-]{0,120}\Z")     # \Z: no newline after the key


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
    outputs : tuple of (key, params)
        Empty: the task is one point stored under ``key``. Otherwise the points it stores, each under its
        own key with its own parameters (what a reader checks); ``func(**params, stored=...)`` returns
        ``{key: (arrays, info)}`` (module docstring).
    """

    key: str
    func: Callable
    params: dict = field(default_factory=dict)
    outputs: tuple = ()

    def __post_init__(self):
        for key, params in ((self.key, self.params), *self.outputs):
            if not _KEY.match(key):
                raise InputError(f"task key {key!r}: use letters, digits, '_', '.', '+', '-' (max 121 chars)")
            try:
                json.dumps(params, sort_keys=True)
            except TypeError as e:
                raise InputError(f"task {key}: params are not JSON-serialisable ({e})") from None

    @property
    def points(self) -> tuple:
        """``(key, params)`` of every point the task stores: its outputs, else itself."""
        return tuple(self.outputs) if self.outputs else ((self.key, self.params),)


def point_tasks(tasks) -> list:
    """The points of ``tasks`` as single-point tasks (key, func, params), in order: what is stored and read."""
    return [t if not t.outputs else Task(k, t.func, p) for t in tasks for k, p in t.points]


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
