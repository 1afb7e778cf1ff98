"""Parallel, resumable sweeps of independent points with self-describing results on disk.

A sweep is a list of :class:`~sweep.tasks.Task` (a key, a picklable top-level function, JSON
parameters). :func:`run_sweep` submits the tasks that have no valid result yet to a
:class:`concurrent.futures.Executor` — a local process pool by default; for a cluster pass a
``dask.distributed.Client`` (optional dependency, not required here): its
``get_executor()`` is such an executor, so no other code changes — and stores every finished
point in a :class:`~sweep.store.ResultStore` as soon as it arrives. An interrupted sweep
resumes with the points that are still missing.
"""
from __future__ import annotations

import concurrent.futures as cf
import datetime as _dt
import os
import platform
import sys
import time
from dataclasses import dataclass, field
from typing import Callable

from contact.errors import InputError
from sweep.progress import Progress
from sweep.provenance import code_revision, environment
from sweep.store import ResultStore, write_status
from sweep.tasks import Task


@dataclass
class SweepSummary:
    """What :func:`run_sweep` did: keys computed, reused, recomputed after corruption, failed.

    ``failed`` holds each failed key's message, ``errors`` the exception itself (not stored on
    disk; a caller that needs every point may re-raise it).
    """

    computed: list = field(default_factory=list)
    reused: list = field(default_factory=list)
    recomputed: dict = field(default_factory=dict)
    failed: dict = field(default_factory=dict)
    wall_s: float = 0.0
    point_wall_s: dict = field(default_factory=dict)
    errors: dict = field(default_factory=dict)


def _call(func, params):
    t0 = time.perf_counter()
    arrays, info = func(**params)
    return arrays, info, time.perf_counter() - t0


def as_executor(executor):
    """A ``dask.distributed.Client`` exposes a concurrent.futures executor via ``get_executor``."""
    if executor is not None and not isinstance(executor, cf.Executor) and hasattr(executor, "get_executor"):
        return executor.get_executor()
    return executor


def _now() -> str:
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


def _write_manifest(store: ResultStore, tasks: list[Task], manifest: dict | None) -> None:
    man = {"created_utc": _now(), **code_revision(), "environment": environment(),
           "tasks": {t.key: {"func": f"{t.func.__module__}.{t.func.__qualname__}", "params": t.params} for t in tasks}}
    man.update(manifest or {})
    store.write_manifest(man)


def _plan(tasks: list[Task], store: ResultStore, summary: SweepSummary, say, resume: bool) -> list[Task]:
    """The tasks to compute: those without a verified result (all of them unless ``resume``)."""
    todo = []
    for t in tasks:
        status, why = store.check(t.key, t.params) if resume else ("missing", "not resuming")
        if status == "done":
            summary.reused.append(t.key)
            continue
        if status in ("corrupt", "stale"):
            summary.recomputed[t.key] = why
            say(f"sweep: {t.key}: {status} ({why}); recomputing")
        todo.append(t)
    return todo


def _collect(futures: dict, store: ResultStore, summary: SweepSummary, prog: Progress, say) -> None:
    """Store every point as its future finishes; a failing point is recorded, not raised."""
    run_info = {**code_revision(), "host": platform.node()}
    for fut in cf.as_completed(futures):
        t = futures[fut]
        try:
            arrays, info, wall = fut.result()
        except Exception as e:  # a failing point must not lose the others
            summary.failed[t.key] = f"{type(e).__name__}: {e}"
            summary.errors[t.key] = e
            say(f"sweep: {t.key} failed: {type(e).__name__}: {e}")
            prog.update(note=f"{t.key} FAILED")
            continue
        store.save(t.key, t.params, arrays, info, run={**run_info, "wall_s": round(wall, 4), "finished_utc": _now()})
        summary.computed.append(t.key)
        summary.point_wall_s[t.key] = wall
        prog.update(note=t.key)


def run_sweep(tasks: list[Task], store: ResultStore | str | os.PathLike, *, executor=None, max_workers: int = 2,
              manifest: dict | None = None, progress: Progress | bool | None = None,
              log: Callable[[str], None] | None = None, label: str = "sweep", resume: bool = True) -> SweepSummary:
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
    label : name on the progress line
    resume : reuse verified stored points (False: compute every task again, overwriting)

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
    _write_manifest(store, tasks, manifest)
    write_status(store.root, "running")
    todo = _plan(tasks, store, summary, say, resume)
    if isinstance(progress, Progress):
        prog = progress
    else:
        prog = Progress(len(todo), label=label, enabled=(None if progress is None else bool(progress)))
    if not todo:
        summary.wall_s = time.perf_counter() - t_start
        write_status(store.root, "complete", tasks=len(tasks))
        return summary
    own = executor is None
    ex = cf.ProcessPoolExecutor(max_workers=max_workers) if own else as_executor(executor)
    futures = {}
    try:
        for t in todo:
            futures[ex.submit(_call, t.func, t.params)] = t
        _collect(futures, store, summary, prog, say)
    except BaseException:
        write_status(store.root, "interrupted", tasks=len(tasks))
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
    write_status(store.root, "incomplete" if summary.failed else "complete", tasks=len(tasks),
                 failed=sorted(summary.failed))
    return summary
