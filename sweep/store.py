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

Beside them: ``sweep.json`` carries its own SHA-256 (``manifest_sha256``; a damaged one is refused
with its name, never silently rewritten), ``journal.jsonl`` lists every point stored (one line per
save, so a record deleted after it was finished is told apart from one never computed), and
``timing.json`` the wall times of the runs (a damaged one is set aside with a message and started
afresh: it is a log, not a result).

Used by the rotor studies (:mod:`rotor.studies`) and the 2D/3D FEM reference sweeps.
"""
from __future__ import annotations

import dataclasses
import hashlib
import io
import json
import os
import platform
import time
from pathlib import Path

import numpy as np

from contact.errors import DatasetError
from contact.files import atomic_write_bytes, atomic_write_text, writer_running
from sweep.tasks import PointResult, Task, point_tasks

FORMAT = "ringcontact.sweep-point/1"
MANIFEST = "sweep.json"
JOURNAL = "journal.jsonl"
TIMING = "timing.json"


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

    # -- what is there -------------------------------------------------
    def check_layout(self) -> None:
        """Refuse, by name and with what to do, a run directory whose parts are of the wrong kind or not this
        suite's (a file where ``points/`` belongs, a journal or status file holding something else), before
        anything is written: :class:`DatasetError`. Finished points are never touched by the advice."""
        keep = "move it away (the finished points stay and are verified one by one) or use another --out"
        if self.root.exists() and not self.root.is_dir():
            raise DatasetError(f"{self.root}: a file, not a run directory; use another --out")
        if (self.points.exists() or self.points.is_symlink()) and not self.points.is_dir():
            raise DatasetError(f"{self.points}: a file where the folder of finished points belongs; move it away "
                               "or use another --out")
        for name in (MANIFEST, JOURNAL, STATUS_FILE, TIMING):
            p = self.root / name
            if (p.exists() or p.is_symlink()) and not p.is_file():
                raise DatasetError(f"{p}: not a regular file (a folder, a pipe or a dangling link); {keep}")
        self._check_journal(keep)
        p = self.root / STATUS_FILE
        if p.is_file():
            try:
                doc = json.loads(p.read_bytes().decode("utf-8"))
                ok = isinstance(doc, dict) and doc.get("state") in STATES
            except (ValueError, RecursionError):
                ok = False
            if not ok:
                raise DatasetError(f"{p}: not a status file of this suite (JSON with a state of {', '.join(STATES)}); "
                                   f"{keep}")

    def _check_journal(self, keep: str) -> None:
        """The journal must be this suite's: UTF-8 lines of JSON entries (only the last may be cut by a kill)."""
        p = self.root / JOURNAL
        if not p.is_file():
            return
        try:
            lines = p.read_bytes().decode("utf-8").splitlines()
        except UnicodeDecodeError:
            raise DatasetError(f"{p}: not a journal of this suite (not UTF-8 text); {keep}") from None
        bad = 0
        for line in lines[:-1]:
            try:
                bad += not isinstance(json.loads(line).get("key"), str)
            except (ValueError, AttributeError, RecursionError):
                bad += 1
        if bad:
            raise DatasetError(f"{p}: {bad} line(s) that are not journal entries of this suite; {keep}")

    # -- writing -------------------------------------------------------
    def write_manifest(self, manifest: dict) -> Path:
        """Write ``sweep.json`` (atomically) with its own SHA-256: what the sweep is, code revision, environment."""
        doc = json.loads(json.dumps(dict(manifest), default=_json_default))
        doc.setdefault("format", "ringcontact.sweep/1")
        doc.pop("manifest_sha256", None)
        doc["manifest_sha256"] = _sha256(_canonical(doc).encode())
        return atomic_write_text(self.root / MANIFEST, json.dumps(doc, indent=2, sort_keys=True) + "\n")

    def read_manifest(self, required: bool = True) -> dict | None:
        """``sweep.json`` verified; None if absent and not ``required``; :class:`DatasetError` naming it
        if it is unreadable or its checksum does not match (files written before the checksum have none)."""
        p = self.root / MANIFEST
        if not p.exists() and not required:
            return None
        try:
            doc = json.loads(p.read_text(encoding="utf-8"))
            if not isinstance(doc, dict):
                raise ValueError("not a JSON object")
        except (OSError, ValueError) as e:
            raise DatasetError(f"{p}: damaged sweep record ({type(e).__name__}: {str(e)[:80]}); it says what this "
                               "sweep is: restore it, or move it away to start a new record (points are kept)") from None
        claimed = doc.pop("manifest_sha256", None)
        if claimed is not None and _sha256(_canonical(doc).encode()) != claimed:
            raise DatasetError(f"{p}: damaged sweep record (checksum mismatch); restore it, or move it away to "
                               "start a new record (points are kept)")
        return doc

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
        path = atomic_write_text(self.json_path(key), json.dumps(rec, indent=1, sort_keys=True,
                                                                 default=_json_default) + "\n")
        self._journal(key, rec["record_sha256"])
        return path

    # -- journal of stored points ----------------------------------------
    def _journal(self, key: str, record_sha256: str) -> None:
        line = json.dumps({"key": key, "record_sha256": record_sha256,
                           "utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}) + "\n"
        fd = os.open(self.root / JOURNAL, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        try:
            os.write(fd, line.encode())
        finally:
            os.close(fd)

    def journal_keys(self) -> set[str]:
        """Keys of every point ever stored here (unreadable lines, e.g. one cut by a kill, are skipped)."""
        try:
            lines = (self.root / JOURNAL).read_bytes().decode("utf-8", errors="replace").splitlines()
        except OSError:
            return set()
        keys = set()
        for line in lines:
            try:
                keys.add(json.loads(line)["key"])
            except (ValueError, KeyError, TypeError):
                continue
        return keys

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

    def info(self, key: str) -> dict:
        """The ``info`` of a point's JSON record (check it first: :meth:`check`)."""
        return json.loads(self.json_path(key).read_text()).get("info", {})

    def keys(self) -> list[str]:
        return sorted(p.stem for p in self.points.glob("*.json")) if self.points.exists() else []


def expected_points(store: ResultStore) -> dict[str, dict | None]:
    """The points a store should hold: the tasks of its ``sweep.json`` (key -> params), plus any
    record it holds (params not checked: None). :class:`DatasetError` if sweep.json is damaged."""
    man = store.read_manifest(required=False) or {}
    want: dict[str, dict | None] = {k: (v or {}).get("params") for k, v in (man.get("tasks") or {}).items()}
    for k in store.keys():
        want.setdefault(k, None)
    return want


def load_sweep(store: ResultStore | str | os.PathLike, tasks: list[Task] | None = None, *,
               complete: bool = False) -> dict[str, PointResult]:
    """All verified points of a store (those of ``tasks`` if given, checking their params; a task with
    ``outputs`` stands for its output points, :func:`sweep.tasks.point_tasks`).

    ``complete=False``: corrupt, stale or missing points are left out. ``complete=True``: they are
    refused with one :class:`DatasetError` naming each (without ``tasks``, the points expected are
    those of :func:`expected_points`).
    """
    store = store if isinstance(store, ResultStore) else ResultStore(store)
    if tasks is not None:
        items = [(t.key, t.params) for t in point_tasks(tasks)]
    elif complete:
        items = list(expected_points(store).items())
    else:
        items = [(k, None) for k in store.keys()]
    out, bad = {}, []
    for key, params in items:
        status, why = store.check(key, params)
        if status == "done":
            out[key] = store.load(key, params)
        elif complete:
            bad.append(f"{key} ({status}{': ' + why if why and status != 'missing' else ''})")
    if bad:
        raise DatasetError(f"{store.root}: {len(bad)} of {len(items)} points missing or damaged: "
                           f"{', '.join(bad[:8])}{' …' if len(bad) > 8 else ''}; run the sweep again to "
                           "recompute them")
    return out


STATUS_FILE = "status.json"
#: the states a status file may record
STATES = ("running", "interrupted", "incomplete", "complete")


def write_status(root: str | os.PathLike, state: str, **fields) -> Path:
    """Mark a run directory ``state`` (running | interrupted | incomplete | complete), atomically.

    A ``running`` mark carries the writer's ``pid`` and ``host``, so a reader can tell a run that is going
    on from one whose process died without a word (kill -9, power loss): :func:`run_state`."""
    doc = {"state": state, "complete": state == "complete", **fields}
    return atomic_write_text(Path(root) / STATUS_FILE, json.dumps(doc, indent=1, sort_keys=True, default=_json_default) + "\n")


def run_state(root: str | os.PathLike) -> str | None:
    """The state ``<root>/status.json`` records (None: no readable status file); a ``running`` mark whose
    writer, on this host, is no longer running reads ``interrupted (pid N no longer running)``."""
    try:
        doc = json.loads((Path(root) / STATUS_FILE).read_text(encoding="utf-8"))
        state = str(doc.get("state", "unknown"))
    except (OSError, ValueError, AttributeError):
        return None
    pid = doc.get("pid")
    if (state == "running" and isinstance(pid, int) and pid > 0 and doc.get("host") == platform.node()
            and not writer_running(pid)):
        return f"interrupted (pid {pid} no longer running)"
    return state


def run_status(root: str | os.PathLike) -> dict:
    """Is ``root`` a finished run directory? ``{"complete": bool, "tasks": n, "done": m, "why": text}``.

    Complete means: ``sweep.json`` lists the tasks, the last run ended ``complete`` and every task has
    its point record (each is still verified by checksum when it is loaded). A run left ``running`` by a
    process that died is told as such (:func:`run_state`).
    """
    root = Path(root)
    out = {"complete": False, "tasks": 0, "done": 0, "why": ""}
    try:
        tasks = json.loads((root / "sweep.json").read_text(encoding="utf-8")).get("tasks", {})
    except (OSError, ValueError, AttributeError):
        out["why"] = "no readable sweep.json: not a study directory"
        return out
    out["tasks"] = len(tasks)
    missing = [k for k in tasks if not (root / "points" / f"{k}.json").exists()]
    out["done"] = len(tasks) - len(missing)
    state = run_state(root)
    if state is None:
        state = "complete" if out["done"] == out["tasks"] else "unknown"   # a run from before status files
    if state != "complete" or out["done"] < out["tasks"] or not tasks:
        out["why"] = f"state {state}, {out['done']} of {out['tasks']} points" + (
            "; " + ", ".join(f"{k} (missing)" for k in missing[:5]) + (" …" if len(missing) > 5 else "")
            if missing else "")
        return out
    out["complete"] = True
    return out


def read_timing(root: str | os.PathLike) -> list | None:
    """The runs recorded in ``<root>/timing.json`` (None if absent); :class:`DatasetError` naming it if damaged."""
    p = Path(root) / TIMING
    if not p.exists():
        return None
    try:
        runs = json.loads(p.read_text(encoding="utf-8"))
        if not isinstance(runs, list):
            raise ValueError("not a JSON list")
    except (OSError, ValueError) as e:
        raise DatasetError(f"{p}: damaged timing record ({type(e).__name__}); a new run of the sweep sets it "
                           "aside and starts a new one") from None
    return runs


def append_timing(root: str | os.PathLike, entry: dict, say=None) -> Path:
    """Append one run's timing to ``<root>/timing.json``; a damaged file is renamed
    ``timing.json.damaged-<UTC>`` (said through ``say``) and a new list started."""
    p = Path(root) / TIMING
    try:
        runs = read_timing(root) or []
    except DatasetError as e:
        aside = p.with_name(f"{TIMING}.damaged-{time.strftime('%Y%m%dT%H%M%SZ', time.gmtime())}")
        os.replace(p, aside)
        if say is not None:
            say(f"sweep: {e.args[0].split(';')[0]}: kept as {aside.name}, starting a new one")
        runs = []
    runs.append(entry)
    return atomic_write_text(p, json.dumps(runs, indent=1, default=_json_default) + "\n")
