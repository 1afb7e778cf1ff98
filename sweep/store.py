"""Parallel, resumable sweeps of independent points with self-describing results on disk.

A sweep is a list of :class:`Task` (a key, a picklable top-level function, JSON parameters).
:func:`run_sweep` submits the tasks that have no valid result yet to a
:class:`concurrent.futures.Executor` — a local process pool by default; for a cluster pass a
``dask.distributed.Client`` (optional dependency, not required here): its
``get_executor()`` is such an executor, so no other code changes — and stores every finished
point as soon as it arrives.

Result store layout (:class:`ResultStore`)::

    <root>/sweep.json            what the sweep is: description, code revision, versions, tasks
    <root>/points/<key>.npz      arrays of one point (numpy NPZ, compressed)
    <root>/points/<key>.json     its parameters, scalar results, run info and the SHA-256 of the NPZ

Why NPZ + JSON and not NetCDF/HDF5: both need a new dependency (netCDF4/h5py) for a few
arrays per point; NPZ is numpy's own format, JSON is readable anywhere, and the pair is
fully self-describing (every parameter, the git revision, package versions, units in the
field names). Both files are written atomically (:mod:`contact.files`), the NPZ first, the
JSON last: the JSON is the completion mark. A point counts as done only if its JSON parses,
its own checksum matches, its parameters equal the task's, and the NPZ's SHA-256 matches; a
truncated or altered file is reported and recomputed, never read.
"""
from __future__ import annotations

import concurrent.futures as cf
import dataclasses
import datetime as _dt
import hashlib
import io
import json
import math
import os
import platform
import re
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from contact.errors import DatasetError, InputError
from contact.files import atomic_write_bytes, atomic_write_text

FORMAT = "ringcontact.sweep-point/1"
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


def code_revision(path: str | os.PathLike | None = None) -> dict:
    """Git commit of the source tree and whether it had uncommitted changes (``dirty``)."""
    root = Path(path) if path is not None else Path(__file__).resolve().parents[1]
    try:
        rev = subprocess.run(["git", "rev-parse", "HEAD"], cwd=root, capture_output=True, text=True,
                             timeout=10).stdout.strip()
        st = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=root,
                            capture_output=True, text=True, timeout=10).stdout
        return {"git_commit": rev or "unknown", "git_dirty": bool(st.strip())}
    except (OSError, subprocess.SubprocessError):
        return {"git_commit": "unknown", "git_dirty": None}


def environment() -> dict:
    """Python, numpy, scipy, numba versions and the machine (for the sweep record)."""
    env = {"python": platform.python_version(), "numpy": np.__version__, "machine": platform.machine(),
           "cpu_count": os.cpu_count()}
    for mod in ("scipy", "numba"):
        try:
            env[mod] = __import__(mod).__version__
        except ImportError:
            env[mod] = None
    return env


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


class Progress:
    """Count, rate and time left on one terminal line; silent under CI or when not a terminal.

    ``enabled=None`` decides from the stream (``isatty``) and the ``CI`` environment variable.
    """

    def __init__(self, total: int, *, label: str = "sweep", stream=None, enabled: bool | None = None):
        self.total = int(total)
        self.label = label
        self.stream = stream if stream is not None else sys.stderr
        if enabled is None:
            isatty = getattr(self.stream, "isatty", lambda: False)
            enabled = bool(isatty()) and not os.environ.get("CI")
        self.enabled = enabled
        self.done = 0
        self.t0 = time.monotonic()

    def update(self, n: int = 1, note: str = "") -> None:
        self.done += n
        if not self.enabled:
            return
        el = time.monotonic() - self.t0
        rate = self.done / el if el > 0 else 0.0
        left = (self.total - self.done) / rate if rate > 0 else math.inf
        eta = f"{int(left // 60)}m{int(left % 60):02d}s" if math.isfinite(left) else "?"
        self.stream.write(f"\r{self.label}: {self.done}/{self.total}  {rate:.2f} pt/s  ~{eta} left  {note[:40]:40s}")
        self.stream.flush()

    def close(self) -> None:
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()


@dataclass
class SweepSummary:
    """What :func:`run_sweep` did: keys computed, reused, recomputed after corruption, failed."""

    computed: list = field(default_factory=list)
    reused: list = field(default_factory=list)
    recomputed: dict = field(default_factory=dict)
    failed: dict = field(default_factory=dict)
    wall_s: float = 0.0
    point_wall_s: dict = field(default_factory=dict)


def _call(func, params):
    t0 = time.perf_counter()
    arrays, info = func(**params)
    return arrays, info, time.perf_counter() - t0


def _as_executor(executor):
    """A ``dask.distributed.Client`` exposes a concurrent.futures executor via ``get_executor``."""
    if executor is not None and not isinstance(executor, cf.Executor) and hasattr(executor, "get_executor"):
        return executor.get_executor()
    return executor


def run_sweep(tasks: list[Task], store: ResultStore | str | os.PathLike, *, executor=None, max_workers: int = 2,
              manifest: dict | None = None, progress: Progress | bool | None = None,
              log: Callable[[str], None] | None = None) -> SweepSummary:
    """Compute every task without a valid stored result, storing each as it finishes.

    Parameters
    ----------
    tasks : list of Task (unique keys)
    store : ResultStore or its directory
    executor : concurrent.futures.Executor, dask.distributed.Client, or None
        None: a local :class:`~concurrent.futures.ProcessPoolExecutor` with ``max_workers``
        processes, shut down at the end. A given executor is used and left open.
    manifest : dict, optional
        Sweep description written to ``sweep.json`` with the code revision and environment.
    progress : Progress, True/False, or None (auto: on a terminal, not under CI)
    log : callable for one-line messages (default: stderr)

    Returns
    -------
    SweepSummary. Failed tasks are listed with their error, not raised; an interruption
    (KeyboardInterrupt) cancels pending tasks and re-raises: finished points stay on disk,
    and the next call resumes with the rest.
    """
    store = store if isinstance(store, ResultStore) else ResultStore(store)
    keys = [t.key for t in tasks]
    if len(set(keys)) != len(keys):
        dup = sorted({k for k in keys if keys.count(k) > 1})
        raise InputError(f"tasks: duplicate keys {dup[:5]}")
    say = log if log is not None else (lambda m: print(m, file=sys.stderr))
    t_start = time.perf_counter()
    summary = SweepSummary()
    man = {"created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
           **code_revision(), "environment": environment(),
           "tasks": {t.key: {"func": f"{t.func.__module__}.{t.func.__qualname__}", "params": t.params} for t in tasks}}
    man.update(manifest or {})
    store.write_manifest(man)
    todo = []
    for t in tasks:
        status, why = store.check(t.key, t.params)
        if status == "done":
            summary.reused.append(t.key)
            continue
        if status in ("corrupt", "stale"):
            summary.recomputed[t.key] = why
            say(f"sweep: {t.key}: {status} ({why}); recomputing")
        todo.append(t)
    if isinstance(progress, Progress):
        prog = progress
    else:
        prog = Progress(len(todo), enabled=(None if progress is None else bool(progress)))
    if not todo:
        summary.wall_s = time.perf_counter() - t_start
        return summary
    own = executor is None
    ex = cf.ProcessPoolExecutor(max_workers=max_workers) if own else _as_executor(executor)
    run_info = {**code_revision(), "host": platform.node()}
    futures = {}
    try:
        for t in todo:
            futures[ex.submit(_call, t.func, t.params)] = t
        for fut in cf.as_completed(futures):
            t = futures[fut]
            try:
                arrays, info, wall = fut.result()
            except Exception as e:  # a failing point must not lose the others
                summary.failed[t.key] = f"{type(e).__name__}: {e}"
                say(f"sweep: {t.key} failed: {type(e).__name__}: {e}")
                prog.update(note=f"{t.key} FAILED")
                continue
            store.save(t.key, t.params, arrays, info,
                       run={**run_info, "wall_s": round(wall, 4),
                            "finished_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")})
            summary.computed.append(t.key)
            summary.point_wall_s[t.key] = wall
            prog.update(note=t.key)
    except BaseException:
        for f in futures:
            f.cancel()
        if own:
            ex.shutdown(wait=False, cancel_futures=True)
            own = False
        raise
    finally:
        prog.close()
        if own:
            ex.shutdown(wait=True)
    summary.wall_s = time.perf_counter() - t_start
    return summary


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
