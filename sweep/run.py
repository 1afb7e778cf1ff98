"""Parallel, resumable sweeps of independent points with self-describing results on disk.

A sweep is a list of :class:`~sweep.tasks.Task` (a key, a picklable top-level function, JSON
parameters). :func:`run_sweep` submits the tasks that have no valid result yet to a
:class:`concurrent.futures.Executor` — a local process pool by default, or a
``dask.distributed.Client`` (the ``dask`` extra; :func:`sweep.cluster.connect` opens one from a
scheduler address) — and stores every finished point in a :class:`~sweep.store.ResultStore` as
soon as it arrives. An interrupted sweep resumes with the points that are still missing.

Faults it guards against:

- one writer per result directory (:class:`~sweep.guard.DirectoryLock`: a second sweep into the
  same directory is refused, or waits ``lock_wait_s``); temporaries left by a killed writer are
  removed when the next one takes the lock;
- the local pool's workers watch their parent and exit when it dies (kill -9 included), so none is
  left orphaned; they leave Ctrl-C to their parent (no traceback of their own);
- an interruption (Ctrl-C, SIGTERM through :mod:`contact.interrupts`) marks ``status.json``
  ``interrupted`` and notes that the finished points are kept; a ``running`` mark whose process died
  (kill -9) is named when the next run starts (:func:`sweep.store.run_state`);
- every point's provenance (host, pid, package version, git commit, BLAS threads) is taken in the
  process that computed it (:func:`sweep.provenance.worker_stamp`), not in the client;
- a damaged ``sweep.json`` is refused with its name; a damaged or deleted point record is
  recomputed with a message naming it.
"""
from __future__ import annotations

import concurrent.futures as cf
import datetime as _dt
import os
import platform
import sys
import threading
import time
from dataclasses import dataclass, field
from typing import Callable

from contact.errors import InputError
from contact.interrupts import keep, worker_signals
from sweep.guard import DirectoryLock, remove_stale_temporaries
from sweep.progress import Progress
from sweep.provenance import code_revision, environment, worker_stamp
from sweep.store import ResultStore, run_state, write_status
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


def _call(func, params, stored=None):
    """Run one task where the executor puts it; its result, wall time and the worker's stamp.

    ``stored`` (a task with outputs: key -> info of the outputs already stored) is passed on to ``func``, whose
    result is then ``{key: (arrays, info)}``; else the result is ``(arrays, info)``."""
    t0 = time.perf_counter()
    result = func(**params) if stored is None else func(**params, stored=stored)
    return result, time.perf_counter() - t0, worker_stamp()


def _watch_parent(parent_pid: int, period_s: float) -> None:
    while True:
        time.sleep(period_s)
        if os.getppid() != parent_pid:
            os._exit(70)  # orphaned: the sweep that started this worker is gone


def die_with_parent(parent_pid: int, period_s: float = 0.5) -> None:
    """Pool-worker initializer: exit as soon as ``parent_pid`` is no longer this process's parent.

    A daemon thread polls ``os.getppid()``; it works whatever killed the parent (kill -9 included),
    on any POSIX system, and from whichever thread the pool started the worker. Ctrl-C is left to the
    parent, which stops its workers, and SIGTERM ends a worker quietly (:func:`contact.interrupts.worker_signals`):
    no worker prints a traceback of its own.
    """
    worker_signals()
    threading.Thread(target=_watch_parent, args=(int(parent_pid), float(period_s)), daemon=True,
                     name="ringcontact-parent-watch").start()


def local_pool(max_workers: int, threads_per_worker: int | None = None) -> cf.ProcessPoolExecutor:
    """The default executor: ``max_workers`` processes that die with this one (:func:`die_with_parent`).

    With ``threads_per_worker`` the workers are started fresh (``spawn``) with the BLAS/OpenMP
    thread variables set to that number before numpy loads in them (:mod:`contact.threads`; the
    variables are set in this process's environment, which the workers inherit); without it they
    are forked as before and inherit this process's threading."""
    if threads_per_worker is None:
        return cf.ProcessPoolExecutor(max_workers=max_workers, initializer=die_with_parent, initargs=(os.getpid(),))
    import multiprocessing

    from contact.threads import set_thread_env
    set_thread_env(threads_per_worker, override=True)
    return cf.ProcessPoolExecutor(max_workers=max_workers, initializer=die_with_parent, initargs=(os.getpid(),),
                                  mp_context=multiprocessing.get_context("spawn"))


def as_executor(executor):
    """A ``dask.distributed.Client`` exposes a concurrent.futures executor via ``get_executor``.

    Asked for impure tasks (``pure=False``): dask otherwise names a task by its arguments and hands a
    re-run the remembered failure of a task whose worker died, instead of computing it again."""
    if executor is not None and not isinstance(executor, cf.Executor) and hasattr(executor, "get_executor"):
        try:
            return executor.get_executor(pure=False)
        except TypeError:
            return executor.get_executor()
    return executor


def _now() -> str:
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


def _write_manifest(store: ResultStore, tasks: list[Task], manifest: dict | None) -> None:
    """``sweep.json`` for this run; a damaged one is refused (DatasetError naming it), never rewritten."""
    previous = store.read_manifest(required=False) or {}
    man = {"created_utc": previous.get("created_utc", _now()), "updated_utc": _now(), **code_revision(),
           "environment": environment(),
           "tasks": {k: {"func": f"{t.func.__module__}.{t.func.__qualname__}", "params": p,
                         **({"task": t.key} if t.outputs else {})} for t in tasks for k, p in t.points}}
    man.update(manifest or {})
    store.write_manifest(man)


def _plan(tasks: list[Task], store: ResultStore, summary: SweepSummary, say,
          resume: bool) -> list[tuple[Task, dict | None]]:
    """The tasks to compute: those without a verified result (all of them unless ``resume``), each with the
    info of its outputs already stored (key -> info; None for a single-point task).

    A damaged record, or one gone although the journal says it was stored, is named in a message."""
    todo = []
    journal = store.journal_keys() if resume else set()
    for t in tasks:
        done = {}
        for key, params in t.points:
            status, why = store.check(key, params) if resume else ("missing", "not resuming")
            if status == "done":
                done[key] = store.info(key) if t.outputs else None
                continue
            if status == "missing" and key in journal:
                status, why = "deleted", "its record was stored, then removed"
            if status in ("corrupt", "stale", "deleted"):
                summary.recomputed[key] = why
                say(f"sweep: {key}: {status} ({why}); recomputing")
        summary.reused.extend(done)
        if len(done) < len(t.points):
            todo.append((t, done if t.outputs else None))
    return todo


def _collect(futures: dict, store: ResultStore, summary: SweepSummary, prog: Progress, say) -> None:
    """Store every point as its future finishes; a failing point is recorded, not raised."""
    client_host = platform.node()
    for fut in cf.as_completed(futures):
        t, stored = futures[fut]
        try:
            result, wall, stamp = fut.result()
            results = result if t.outputs else {t.key: result}
            todo = [(k, p) for k, p in t.points if k not in (stored or {})]
            missing = [k for k, _ in todo if k not in results]
            if missing:
                raise RuntimeError(f"task {t.key} returned no result for {', '.join(missing)}")
        except Exception as e:  # a failing point must not lose the others
            for key in ([t.key] if not t.outputs else [k for k, _ in t.points if k not in stored]):
                summary.failed[key] = f"{type(e).__name__}: {e}"
                summary.errors[key] = e
            say(f"sweep: {t.key} failed: {type(e).__name__}: {e}")
            prog.update(note=f"{t.key} FAILED")
            continue
        run = {"git_commit": stamp["git_commit"], "git_dirty": stamp["git_dirty"], "host": stamp["host"],
               "worker": stamp, "client_host": client_host, "wall_s": round(wall, 4), "finished_utc": _now()}
        for key, params in todo:
            arrays, info = results[key]
            store.save(key, params, arrays, info, run={**run, **({"task": t.key} if t.outputs else {})})
            summary.computed.append(key)
            summary.point_wall_s[key] = wall / len(todo)
        prog.update(note=t.key)


def _execute(todo: list[tuple[Task, dict | None]], executor, max_workers: int, store: ResultStore, summary: SweepSummary,
             prog: Progress, say) -> None:
    """Submit ``todo`` to the executor (a local pool of its own if None) and store what comes back."""
    own = executor is None
    ex = local_pool(max_workers) if own else as_executor(executor)
    futures = {}
    try:
        for t, stored in todo:
            futures[ex.submit(_call, t.func, t.params, stored)] = (t, stored)
        _collect(futures, store, summary, prog, say)
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


def _interrupted(store: ResultStore, summary: SweepSummary, todo: list, exc: BaseException) -> None:
    """Mark the run directory ``interrupted`` and say what the interruption keeps (:func:`contact.interrupts.keep`)."""
    signum = getattr(exc, "signum", None)
    write_status(store.root, "interrupted", tasks=len(summary.reused) + sum(len(t.points) - len(done or {})
                                                                           for t, done in todo),
                 **({"signal": signum} if signum else {}), reason=type(exc).__name__)
    if isinstance(exc, KeyboardInterrupt):
        keep(exc, f"finished points kept in {store.root}; run again to resume", where=store.root)


def run_sweep(tasks: list[Task], store: ResultStore | str | os.PathLike, *, executor=None, max_workers: int = 2,
              manifest: dict | None = None, progress: Progress | bool | None = None,
              log: Callable[[str], None] | None = None, label: str = "sweep", resume: bool = True,
              lock_wait_s: float = 0.0) -> SweepSummary:
    """Compute every task without a valid stored result, storing each as it finishes.

    Parameters
    ----------
    tasks : list of Task (unique keys; a task with ``outputs`` stores each output point under its own key,
        is skipped when all are stored and otherwise told which are, :mod:`sweep.tasks`)
    store : ResultStore or its directory
    executor : concurrent.futures.Executor, dask.distributed.Client, or None
        None: a local :class:`~concurrent.futures.ProcessPoolExecutor` with ``max_workers``
        processes that die with this one, shut down at the end. A given executor is used and left open.
    manifest : dict, optional
        Sweep description written to ``sweep.json`` with the code revision and environment.
    progress : Progress, True/False, or None (auto: on a terminal, not under CI)
    log : callable for one-line messages (default: stderr)
    label : name on the progress line
    resume : reuse verified stored points (False: compute every task again, overwriting)
    lock_wait_s : how long to wait for another sweep writing into the same directory
        (0: refuse at once with :class:`~sweep.guard.DirectoryBusy`)

    Returns
    -------
    SweepSummary. Failed tasks are listed with their error, not raised; an interruption
    (KeyboardInterrupt) cancels pending tasks, marks the directory ``interrupted`` and re-raises:
    finished points stay on disk, and the next call resumes with the rest. A damaged ``sweep.json`` raises
    :class:`~contact.errors.DatasetError` naming it, before anything is computed.
    """
    store = store if isinstance(store, ResultStore) else ResultStore(store)
    keys = [k for t in tasks for k, _ in t.points]
    if len(set(keys)) != len(keys):
        dup = sorted({k for k in keys if keys.count(k) > 1})
        raise InputError(f"tasks: duplicate keys {dup[:5]}: points whose parameters coincide at the keys' rounding "
                         "(e.g. speeds closer than 0.1 rpm); fewer points or a wider range")
    say = log if log is not None else (lambda m: print(m, file=sys.stderr))
    t_start = time.perf_counter()
    summary = SweepSummary()
    store.check_layout()          # damaged or foreign parts refused by name, before the lock file is written
    with DirectoryLock(store.root, wait_s=lock_wait_s):
        removed = remove_stale_temporaries(store.root, store.points)
        if removed:
            say(f"sweep: removed {len(removed)} temporary file(s) left by an interrupted writer: "
                f"{', '.join(p.name for p in removed[:3])}")
        _write_manifest(store, tasks, manifest)
        previous = run_state(store.root)
        if previous and previous.startswith("interrupted ("):
            say(f"sweep: {store.root}: the previous run was {previous}; resuming")
        write_status(store.root, "running", pid=os.getpid(), host=platform.node(), since_utc=_now())
        todo = []
        try:
            todo = _plan(tasks, store, summary, say, resume)
            if isinstance(progress, Progress):
                prog = progress
            else:
                prog = Progress(len(todo), label=label, enabled=(None if progress is None else bool(progress)))
            if todo:
                _execute(todo, executor, max_workers, store, summary, prog, say)
        except BaseException as exc:
            _interrupted(store, summary, todo, exc)
            raise
        write_status(store.root, "incomplete" if summary.failed else "complete", tasks=len(keys),
                     failed=sorted(summary.failed))
    summary.wall_s = time.perf_counter() - t_start
    return summary
