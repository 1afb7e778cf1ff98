"""Faults of the local pool and of result directories (issue 15), each measured before the fix.

- kill -9 of a running sweep left both pool workers orphaned (blocked forever) and its
  temporaries on disk;
- two sweeps into one directory both computed every point (no lock);
- a damaged sweep.json was silently rewritten, a deleted point record silently recomputed;
- a damaged timing.json made every later run die with a traceback;
- the recorded host and commit were the client's, not the worker's.
"""
import concurrent.futures as cf
import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from contact.errors import DatasetError
from sweep import ResultStore, Task, load_sweep, run_sweep
from sweep_helpers import alive, calls as _calls, square_tasks as _tasks, waiting_task

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent


def _wait_for(pred, timeout_s=30.0, what="condition"):
    t0 = time.monotonic()
    while not pred():
        if time.monotonic() - t0 > timeout_s:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.05)


def _waiting_tasks(calls, gate, n=4):
    return [Task(f"x{i}", waiting_task, {"x": float(i), "calls_dir": str(calls), "gate": str(gate)})
            for i in range(n)]


def test_kill_9_of_a_sweep_leaves_no_orphan_worker_and_no_temporary(dirs, tmp_path):
    store, calls = dirs
    gate = tmp_path / "gate"
    script = (f"import sys; sys.path[:0] = [{str(ROOT)!r}, {str(HERE)!r}]\n"
              "from sweep import Task, run_sweep\nfrom sweep_helpers import waiting_task\n"
              f"tasks = [Task(f'x{{i}}', waiting_task, {{'x': float(i), 'calls_dir': {str(calls)!r}, "
              f"'gate': {str(gate)!r}}}) for i in range(4)]\n"
              f"run_sweep(tasks, {str(store)!r}, max_workers=2, progress=False)\n")
    proc = subprocess.Popen([sys.executable, "-c", script], env={**os.environ, "PYTHONPATH": str(ROOT)})
    pids = []
    try:
        _wait_for(lambda: len([f for f in os.listdir(calls) if f.startswith("start-")]) == 2, 60, "two workers")
        pids = [int(f.rsplit("-", 1)[1]) for f in os.listdir(calls) if f.startswith("start-")]
        assert proc.pid not in pids and all(alive(p) for p in pids)
        proc.send_signal(signal.SIGKILL)
        proc.wait(10)
        t0 = time.monotonic()
        while any(alive(p) for p in pids) and time.monotonic() - t0 < 10:
            time.sleep(0.1)
        assert not any(alive(p) for p in pids), "pool workers outlived their killed sweep"
    finally:
        for p in pids:
            if alive(p):
                os.kill(p, signal.SIGKILL)
        if proc.poll() is None:
            proc.kill()
    # a writer killed between writing and renaming leaves '.NAME.*.tmp' behind: the next run removes it
    leftover = store / "points" / ".x0.npz.k1ll3d.tmp"
    leftover.parent.mkdir(parents=True, exist_ok=True)
    leftover.write_bytes(b"half a result")
    gate.write_text("go")
    said = []
    s = run_sweep(_waiting_tasks(calls, gate), store, max_workers=2, progress=False, log=said.append)
    assert sorted(s.computed) == ["x0", "x1", "x2", "x3"]  # the kernel released the dead sweep's lock
    assert not leftover.exists() and any("x0.npz.k1ll3d.tmp" in m for m in said)
    assert not [p for p in (store / "points").iterdir() if p.name.endswith(".tmp")]


def test_second_writer_is_refused_with_the_holder_named(dirs, tmp_path):
    store, calls = dirs
    gate = tmp_path / "gate"
    first = {}
    th = threading.Thread(target=lambda: first.update(s=run_sweep(
        _waiting_tasks(calls, gate, 2), store, executor=cf.ThreadPoolExecutor(1), progress=False)))
    th.start()
    try:
        _wait_for(lambda: any(f.startswith("start-") for f in os.listdir(calls)), 30, "the first sweep")
        with pytest.raises(Exception, match="another sweep is writing here") as err:
            run_sweep(_waiting_tasks(calls, gate, 2), store, executor=cf.ThreadPoolExecutor(1), progress=False)
        assert str(store) in str(err.value) and f"pid {os.getpid()}" in str(err.value)
        assert len([f for f in os.listdir(calls) if f.startswith("start-")]) == 1  # the second computed nothing
    finally:
        gate.write_text("go")
        th.join(30)
    assert sorted(first["s"].computed) == ["x0", "x1"]


def test_second_writer_may_wait_then_reuses_everything(dirs, tmp_path):
    store, calls = dirs
    gate = tmp_path / "gate"
    th = threading.Thread(target=lambda: run_sweep(_waiting_tasks(calls, gate, 2), store,
                                                   executor=cf.ThreadPoolExecutor(1), progress=False))
    th.start()
    _wait_for(lambda: any(f.startswith("start-") for f in os.listdir(calls)), 30, "the first sweep")
    threading.Timer(0.5, gate.write_text, args=("go",)).start()
    s = run_sweep(_waiting_tasks(calls, gate, 2), store, executor=cf.ThreadPoolExecutor(1), progress=False,
                  lock_wait_s=30)
    th.join(30)
    assert s.computed == [] and sorted(s.reused) == ["x0", "x1"]


@pytest.mark.parametrize("damage", ["garbage", "truncated", "edited"])
def test_damaged_sweep_json_is_refused_by_name_not_rewritten(dirs, damage):
    store, calls = dirs
    tasks = _tasks(calls, (1.0, 2.0))
    with cf.ThreadPoolExecutor(1) as ex:
        run_sweep(tasks, store, executor=ex, progress=False)
    man = store / "sweep.json"
    text = man.read_text()
    bad = {"garbage": "{not json", "truncated": text[: len(text) // 2],
           "edited": text.replace('"x": 2.0', '"x": 2.5')}[damage]
    assert bad != text
    man.write_text(bad)
    with cf.ThreadPoolExecutor(1) as ex, pytest.raises(DatasetError, match="sweep.json: damaged"):
        run_sweep(_tasks(calls, (1.0, 2.0, 3.0)), store, executor=ex, progress=False)
    assert man.read_text() == bad and _calls(calls, 3.0) == 0
    with pytest.raises(DatasetError, match="sweep.json"):
        load_sweep(store, complete=True)


def test_deleted_point_record_is_named_when_recomputed(dirs):
    store, calls = dirs
    tasks = _tasks(calls, (1.0, 2.0, 3.0))
    with cf.ThreadPoolExecutor(2) as ex:
        run_sweep(tasks, store, executor=ex, progress=False)
    st = ResultStore(store)
    st.json_path("x2").unlink()
    st.npz_path("x2").unlink()
    with pytest.raises(DatasetError, match=r"1 of 3 points missing or damaged: x2 \(missing\)"):
        load_sweep(store, complete=True)  # what `study publish` reads
    said = []
    with cf.ThreadPoolExecutor(2) as ex:
        s = run_sweep(tasks, store, executor=ex, progress=False, log=said.append)
    assert s.computed == ["x2"] and "x2" in s.recomputed
    assert any(m.startswith("sweep: x2: deleted") for m in said), said
    assert _calls(calls, 2.0) == 2 and sorted(load_sweep(store, complete=True)) == ["x1", "x2", "x3"]


def test_damaged_timing_json_is_set_aside_with_a_message(tmp_path):
    from sweep import append_timing, read_timing

    (tmp_path / "timing.json").write_text('[{"wall_s": 1.0}, {"wall')
    with pytest.raises(DatasetError, match="timing.json: damaged"):
        read_timing(tmp_path)
    said = []
    append_timing(tmp_path, {"wall_s": 2.0}, said.append)
    assert read_timing(tmp_path) == [{"wall_s": 2.0}]
    aside = [p for p in tmp_path.iterdir() if p.name.startswith("timing.json.damaged-")]
    assert len(aside) == 1 and aside[0].read_text().startswith('[{"wall_s": 1.0}')
    assert len(said) == 1 and aside[0].name in said[0]
    append_timing(tmp_path, {"wall_s": 3.0})
    assert [r["wall_s"] for r in read_timing(tmp_path)] == [2.0, 3.0]


def test_provenance_is_the_workers_and_files_are_0644(dirs):
    store, calls = dirs
    tasks = _tasks(calls, (1.0, 2.0))
    run_sweep(tasks, store, max_workers=2, progress=False)
    st = ResultStore(store)
    worker_pids = {int(f.split("-")[2]) for f in os.listdir(calls)}
    for t in tasks:
        run = st.load(t.key).record["run"]
        w = run["worker"]
        assert w["pid"] in worker_pids and w["pid"] != os.getpid()
        assert run["host"] == w["host"] and run["git_commit"] == w["git_commit"]
        assert set(w) >= {"host", "pid", "package_version", "git_commit", "git_dirty", "blas_threads", "thread_env"}
        assert w["thread_env"].get("OPENBLAS_NUM_THREADS") == os.environ.get("OPENBLAS_NUM_THREADS")
    for p in [store / "sweep.json", *(store / "points").iterdir()]:
        assert p.stat().st_mode & 0o777 == 0o644, p
    assert json.loads((store / "journal.jsonl").read_text().splitlines()[0])["key"] in ("x1", "x2")
