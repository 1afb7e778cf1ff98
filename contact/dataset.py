"""Reader/writer of reference datasets (FEM points that the contact laws are judged against).

One JSON file per dataset, UTF-8, written atomically (:mod:`contact.files`)::

    {
      "schema": "ringcontact/reference-dataset",
      "version": 1,
      "metadata": {...},                 # free-form, but must hold the REQUIRED_METADATA keys
      "columns": {"force_n": "N", ...},  # unit of every point field (SI; '-' if none)
      "points": [{"scene": "clamped", "penetration_m": 1e-05, "force_n": 308956.0, ...}, ...],
      "points_sha256": "...",            # of the canonical JSON of "points"
      "sha256": "..."                    # of the canonical JSON of the whole document without this key
    }

Every point holds the REQUIRED_POINT keys; other fields are free (scalars or lists of numbers,
e.g. the pressure along the arc) but must be declared in ``columns`` with their unit. The 2D
reference uses tilt 0; a 3D dataset adds e.g. ``tilt_rad`` and ``moment_nm`` with the same schema.

:func:`read_dataset` raises :class:`~contact.errors.DatasetError` (naming the file and what is
wrong) for a missing or unreadable file, invalid JSON, a wrong schema or version, a checksum
mismatch (a hand-edited or truncated file: the whole-document ``sha256`` covers the metadata and
the column units too, so an edited scene clearance is caught like an edited force), missing keys or
non-finite numbers.
"""
from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from contact.errors import DatasetError
from contact.files import atomic_write_text
from contact.package_data import location

SCHEMA = "ringcontact/reference-dataset"
VERSION = 1
REQUIRED_POINT = ("scene", "penetration_m", "force_n")
REQUIRED_METADATA = ("title", "created_utc", "code_revision", "package_versions")


def _canonical(points) -> str:
    return json.dumps(points, sort_keys=True, separators=(",", ":"), allow_nan=False)


def document_sha256(doc: dict) -> str:
    """SHA-256 of the canonical JSON of ``doc`` without its own ``"sha256"`` key (datasets, calibrated laws)."""
    body = {k: v for k, v in doc.items() if k != "sha256"}
    return hashlib.sha256(json.dumps(body, sort_keys=True, separators=(",", ":"), allow_nan=False).encode()).hexdigest()


def check_document_sha256(doc: dict, path) -> None:
    """Raise :class:`DatasetError` unless ``doc["sha256"]`` matches its content."""
    stored = doc.get("sha256")
    if not isinstance(stored, str):
        raise DatasetError(f"{path}: no whole-file checksum 'sha256' (written by an older version or edited)")
    try:
        digest = document_sha256(doc)
    except ValueError as exc:
        raise DatasetError(f"{path}: holds non-finite numbers ({exc})") from exc
    if digest != stored:
        raise DatasetError(f"{path}: checksum mismatch (edited or corrupted): stored {stored[:12]}…, "
                           f"computed {digest[:12]}…")


def _check_value(path, i: int, key: str, value) -> None:
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return
    if isinstance(value, (int, float)):
        if not math.isfinite(value):
            raise DatasetError(f"{path}: point {i} field {key!r} = {value!r} is not finite")
        return
    if isinstance(value, list):
        for v in value:
            if isinstance(v, (int, float)) and not isinstance(v, bool) and not math.isfinite(v):
                raise DatasetError(f"{path}: point {i} field {key!r} holds a non-finite value")
        return
    raise DatasetError(f"{path}: point {i} field {key!r} has unsupported type {type(value).__name__}")


def _to_jsonable(value):
    if isinstance(value, np.ndarray):
        return [_to_jsonable(v) for v in value.tolist()]
    if isinstance(value, (np.floating,)):
        return float(value)
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (list, tuple)):
        return [_to_jsonable(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _to_jsonable(v) for k, v in value.items()}
    return value


@dataclass(frozen=True)
class ReferenceDataset:
    """A validated dataset: metadata, column units and points (dicts, SI)."""

    metadata: dict
    columns: dict
    points: tuple

    def scenes(self) -> list[str]:
        """Scene names in order of first appearance."""
        return list(dict.fromkeys(p["scene"] for p in self.points))

    def select(self, **equal) -> list[dict]:
        """Points whose fields equal the given values, e.g. ``select(scene='clamped')``."""
        return [p for p in self.points if all(p.get(k) == v for k, v in equal.items())]

    def column(self, name: str, scene: str | None = None) -> np.ndarray:
        """One scalar field as a float array (optionally of one scene), in file order."""
        if name not in self.columns:
            raise DatasetError(f"column {name!r} not in dataset (have {sorted(self.columns)})")
        pts = self.points if scene is None else self.select(scene=scene)
        return np.array([p[name] for p in pts], dtype=float)


def write_dataset(path, metadata: dict, columns: dict, points: list[dict]) -> Path:
    """Validate and write a dataset atomically; returns the path."""
    metadata = _to_jsonable(dict(metadata))
    columns = {str(k): str(v) for k, v in columns.items()}
    points = [_to_jsonable(dict(p)) for p in points]
    _validate(path, metadata, columns, points)
    doc = {"schema": SCHEMA, "version": VERSION, "metadata": metadata, "columns": columns,
           "points": points, "points_sha256": hashlib.sha256(_canonical(points).encode()).hexdigest()}
    doc["sha256"] = document_sha256(doc)
    text = json.dumps(doc, indent=1, sort_keys=False, allow_nan=False)
    return atomic_write_text(path, text + "\n")


def _validate(path, metadata, columns, points) -> None:
    missing = [k for k in REQUIRED_METADATA if k not in metadata]
    if missing:
        raise DatasetError(f"{path}: metadata lacks {missing}")
    for k in REQUIRED_POINT:
        if k not in columns:
            raise DatasetError(f"{path}: columns lack the required {k!r}")
    for i, p in enumerate(points):
        miss = [k for k in REQUIRED_POINT if k not in p]
        if miss:
            raise DatasetError(f"{path}: point {i} lacks {miss}")
        undeclared = [k for k in p if k not in columns]
        if undeclared:
            raise DatasetError(f"{path}: point {i} has fields without a unit in 'columns': {undeclared}")
        for k, v in p.items():
            _check_value(path, i, k, v)


def dataset_kind(columns: dict) -> str:
    """``"3d"`` for a tilted-ring (3D) dataset (it has moments), else ``"2d"``."""
    return "3d" if "moment_nm" in columns else "2d"


def read_dataset(path, kind: str | None = None) -> ReferenceDataset:
    """Read and validate a dataset file (see module docstring for what is checked).

    ``kind`` (``"2d"`` or ``"3d"``) refuses a dataset of the other kind with a :class:`DatasetError`.
    ``path`` is a file path or a shipped entry (:mod:`contact.package_data`).
    """
    path = location(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise DatasetError(f"{path}: cannot read reference dataset ({exc})") from exc
    try:
        doc = json.loads(text)
    except (json.JSONDecodeError, RecursionError) as exc:     # RecursionError: nested beyond any dataset
        raise DatasetError(f"{path}: not valid JSON (truncated, corrupted or nested too deeply): "
                           f"{str(exc)[:120]}") from None
    if not isinstance(doc, dict) or doc.get("schema") != SCHEMA:
        raise DatasetError(f"{path}: schema is {doc.get('schema') if isinstance(doc, dict) else None!r}, "
                           f"expected {SCHEMA!r}")
    if doc.get("version") != VERSION:
        raise DatasetError(f"{path}: dataset version {doc.get('version')!r}, this reader supports {VERSION}")
    for key in ("metadata", "columns", "points", "points_sha256"):
        if key not in doc:
            raise DatasetError(f"{path}: missing top-level key {key!r}")
    points = doc["points"]
    if not isinstance(points, list):
        raise DatasetError(f"{path}: 'points' must be a list")
    try:
        digest = hashlib.sha256(_canonical(points).encode()).hexdigest()
    except ValueError as exc:
        raise DatasetError(f"{path}: points hold non-finite numbers ({exc})") from exc
    if digest != doc["points_sha256"]:
        raise DatasetError(f"{path}: checksum mismatch (points edited or corrupted): "
                           f"stored {doc['points_sha256'][:12]}…, computed {digest[:12]}…")
    check_document_sha256(doc, path)
    _validate(path, doc["metadata"], doc["columns"], points)
    if kind is not None and dataset_kind(doc["columns"]) != kind:
        raise DatasetError(f"{path}: a {dataset_kind(doc['columns']).upper()} dataset; this job needs a "
                           f"{kind.upper()} one")
    return ReferenceDataset(metadata=doc["metadata"], columns=doc["columns"], points=tuple(points))
