"""A digest of what a study point computes with: the resolved scene, not its name.

A sweep store (sweep/store.py) reuses a stored point when its parameters equal the task's. The parameters
of a study point name the scene (``"paper-table4"``), so without more a point computed before the scene file
changed (its reading of Eq. 34, a stiffness, the law) would be reused as if it were current. The study tasks
therefore carry :func:`scene_digest` of the scene as the point will build it (reading and overrides applied,
the mesh refinement included), and the point function checks it (:func:`check_digest`): a changed scene makes
every stored point stale, and a task built from one scene cannot silently run on another.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
from pathlib import Path

import numpy as np

from contact.errors import InputError

#: descriptive fields of a scene that do not enter the model (where the file lives, its title and source)
_DESCRIPTIVE = ("path", "title", "source")


def _plain(o):
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, Path):
        return str(o)
    raise TypeError(f"scene digest: {type(o).__name__} is not a scene value")


def scene_digest(scene, elements_per_segment: int | None = None) -> str:
    """SHA-256 (first 16 hex digits) of the scene's model-relevant content and the mesh refinement.

    ``scene``: a :class:`rotor.model.scene.Scene` as the point builds it. A calibrated law enters by its
    file's checksum (``law_sha256``), not by the fitted object."""
    if scene.loose_support is not None and getattr(scene.loose_support, "calibrated", None) is not None:
        scene = dataclasses.replace(scene, loose_support=dataclasses.replace(scene.loose_support, calibrated=None))
    doc = dataclasses.asdict(scene)
    for k in _DESCRIPTIVE:
        doc.pop(k, None)
    doc["elements_per_segment"] = elements_per_segment
    text = json.dumps(doc, sort_keys=True, default=_plain, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def check_digest(expected: str | None, scene, elements_per_segment: int | None = None, *, what: str = "point"):
    """Refuse (:class:`InputError`) when the scene the point builds is not the one its task was made from."""
    if expected is None:
        return
    now = scene_digest(scene, elements_per_segment)
    if now != expected:
        raise InputError(f"{what}: scene_sha256 = {expected}, but the scene {scene.name!r} now digests to {now} "
                         "(it changed since the task was made); rebuild the tasks")
