"""Resumable, checksummed result store: one NPZ + one JSON per finished point.

Result store layout (:class:`ResultStore`)::

    <root>/sweep.json            what the sweep is: description, code revision, versions, tasks
    <root>/points/<key>.npz      arrays of one point (numpy NPZ, compressed)
    <root>/points/<key>.json     its parameters, scalar results, run info and the SHA-256 of the NPZ
    <root>/status.json           "running", "interrupted", "incomplete" (failed points) or "complete":
                                 written when a run starts and when it ends (:func:`run_status` reads it)

Why NPZ + JSON and not NetCDF/HDF5: both need a new dependency (netCDF4/h5py) for a few
arrays per point; NPZ is numpy's own format, JSON is readable anywhere, and the pair is
fully self-describing (every parameter, the git revision, package versions, units in the
field names). Both files are written atomically (:mod:`contact.files`), the NPZ first, the
JSON last: the JSON is the completion mark. A point counts as done only if its JSON parses,
its own checksum matches, its parameters equal the task's, and the NPZ's SHA-256 matches; a
truncated or altered file is reported and recomputed, never read.

Used by the rotor studies (:mod:`rotor.studies`) and the 2D/3D FEM reference sweeps.
"""
from __future__ import annotations

import dataclasses
import hashlib
import io
import json
import os
from pathlib import Path

import numpy as np

from contact.errors import DatasetError
from contact.files import atomic_write_bytes, atomic_write_text
from sweep.tasks import PointResult, Task

FORMAT = "ringcontact.sweep-point/1"


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _canonical(obj) -> str:
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), default=_json_default)


def _json_default(o):
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.floating,)):
        return float(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, (np.bool_,)):
        return bool(o)
    if dataclasses.is_dataclass(o):
        return dataclasses.asdict(o)
    if isinstance(o, Path):
        return str(o)
    raise TypeError(f"not JSON-serialisable: {type(o).__name__}")


class ResultStore:
    """Directory of finished points (one NPZ + one JSON per point), see the module docstring."""

    def __init__(self, root: str | os.PathLike):
        self.root = Path(root)
        self.points = self.root / "points"

    # -- paths ---------------------------------------------------------
    def npz_path(self, key: str) -> Path:
        return self.points / f"{key}.npz"

    def json_path(self, key: str) -> Path:
        return self.points / f"{key}.json"

    # -- writing -------------------------------------------------------
    def write_manifest(self, manifest: dict) -> Path:
        """Write ``sweep.json`` (atomically): what the sweep is, code revision, environment."""
        doc = dict(manifest)
        doc.setdefault("format", "ringcontact.sweep/1")
        return atomic_write_text(self.root / "sweep.json", json.dumps(doc, indent=2, sort_keys=True,
                                                                       default=_json_default) + "\n")

    def read_manifest(self) -> dict:
        p = self.root / "sweep.json"
        try:
            return json.loads(p.read_text())
        except (OSError, ValueError) as e:
            raise DatasetError(f"{p}: cannot read sweep record ({e})") from None

    def save(self, key: str, params: dict, arrays: dict, info: dict, *, run: dict | None = None) -> Path:
        """Store one finished point: NPZ first, then the JSON record holding its checksum."""
        buf = io.BytesIO()
        np.savez_compressed(buf, **{k: np.asarray(v) for k, v in arrays.items()})
        data = buf.getvalue()
        atomic_write_bytes(self.npz_path(key), data)
        rec = {"format": FORMAT, "key": key, "params": params, "info": info, "run": run or {},
               "arrays": {k: {"shape": list(np.shape(v)), "dtype": str(np.asarray(v).dtype)} for k, v in arrays.items()},
               "npz_sha256": _sha256(data), "npz_bytes": len(data)}
        rec["record_sha256"] = _sha256(_canonical(rec).encode())
        return atomic_write_text(self.json_path(key), json.dumps(rec, indent=1, sort_keys=True,
                                                                 default=_json_default) + "\n")

    # -- reading -------------------------------------------------------
    def check(self, key: str, params: dict | None = None) -> tuple[str, str]:
        """``(status, reason)``: ``'done'``, ``'missing'``, ``'corrupt'`` or ``'stale'`` (other params)."""
        jp, npth = self.json_path(key), self.npz_path(key)
        if not jp.exists():
            return "missing", "no record"
        try:
            rec = json.loads(jp.read_text())
            claimed = rec.pop("record_sha256")
        except (OSError, ValueError, KeyError, AttributeError) as e:
            return "corrupt", f"{jp.name}: unreadable record ({type(e).__name__})"
        if _sha256(_canonical(rec).encode()) != claimed:
            return "corrupt", f"{jp.name}: record checksum mismatch"
        if rec.get("format") != FORMAT:
            return "corrupt", f"{jp.name}: format {rec.get('format')!r}, expected {FORMAT!r}"
        try:
            data = npth.read_bytes()
        except OSError:
            return "corrupt", f"{npth.name}: missing"
        if _sha256(data) != rec.get("npz_sha256"):
            return "corrupt", f"{npth.name}: SHA-256 mismatch ({len(data)} bytes, expected {rec.get('npz_bytes')})"
        if params is not None and _canonical(rec.get("params")) != _canonical(params):
            return "stale", f"{jp.name}: computed with other parameters"
        return "done", ""

    def load(self, key: str, params: dict | None = None) -> PointResult:
        """Read a verified point; :class:`DatasetError` if it is missing, corrupt or stale."""
        status, why = self.check(key, params)
        if status != "done":
            raise DatasetError(f"point {key!r} in {self.points}: {status} ({why})")
        rec = json.loads(self.json_path(key).read_text())
        with np.load(io.BytesIO(self.npz_path(key).read_bytes()), allow_pickle=False) as z:
            arrays = {k: z[k] for k in z.files}
        return PointResult(key, arrays, rec)

    def keys(self) -> list[str]:
        return sorted(p.stem for p in self.points.glob("*.json")) if self.points.exists() else []


def load_sweep(store: ResultStore | str | os.PathLike, tasks: list[Task] | None = None) -> dict[str, PointResult]:
    """All verified points of a store (those of ``tasks`` if given, checking their params);
    corrupt, stale or missing points are left out."""
    store = store if isinstance(store, ResultStore) else ResultStore(store)
    out = {}
    items = [(t.key, t.params) for t in tasks] if tasks is not None else [(k, None) for k in store.keys()]
    for key, params in items:
        if store.check(key, params)[0] == "done":
            out[key] = store.load(key, params)
    return out


STATUS_FILE = "status.json"


def write_status(root: str | os.PathLike, state: str, **fields) -> Path:
    """Mark a run directory ``state`` (running | interrupted | incomplete | complete), atomically."""
    doc = {"state": state, "complete": state == "complete", **fields}
    return atomic_write_text(Path(root) / STATUS_FILE, json.dumps(doc, indent=1, sort_keys=True, default=_json_default) + "\n")


def run_status(root: str | os.PathLike) -> dict:
    """Is ``root`` a finished run directory? ``{"complete": bool, "tasks": n, "done": m, "why": text}``.

    Complete means: ``sweep.json`` lists the tasks, the last run ended ``complete`` and every task has
    its point record (each is still verified by checksum when it is loaded).
    """
    root = Path(root)
    out = {"complete": False, "tasks": 0, "done": 0, "why": ""}
    try:
        tasks = json.loads((root / "sweep.json").read_text(encoding="utf-8")).get("tasks", {})
    except (OSError, ValueError, AttributeError):
        out["why"] = "no readable sweep.json: not a study directory"
        return out
    out["tasks"] = len(tasks)
    out["done"] = sum((root / "points" / f"{k}.json").exists() for k in tasks)
    try:
        state = json.loads((root / STATUS_FILE).read_text(encoding="utf-8")).get("state", "unknown")
    except (OSError, ValueError, AttributeError):
        state = "complete" if out["done"] == out["tasks"] else "unknown"   # a run from before status files
    if state != "complete" or out["done"] < out["tasks"] or not tasks:
        out["why"] = f"state {state}, {out['done']} of {out['tasks']} points"
        return out
    out["complete"] = True
    return out
