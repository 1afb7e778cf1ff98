"""Resumable sweeps over an executor (sweep.run_sweep).

Must show (issue 8): an interrupted sweep resumes without recomputing finished points. Each task
leaves a marker file per call (sweep_helpers.square_task), so "not recomputed" is counted, not
assumed. Corrupted points: test_store.py.
"""
import concurrent.futures as cf
import json
import os

import numpy as np
import pytest

from contact.errors import InputError
from sweep import Progress, ResultStore, Task, load_sweep, run_status, run_sweep
from sweep_helpers import calls as _calls, failing_task, square_tasks as _tasks


class _InterruptAfter(Progress):
    """Progress whose update raises KeyboardInterrupt after n points (a Ctrl-C mid-sweep)."""

    def __init__(self, total, n):
        super().__init__(total, enabled=False)
        self.n = n

    def update(self, n=1, note=""):
        super().update(n, note)
        if self.done >= self.n:
            raise KeyboardInterrupt


@pytest.fixture
def dirs(tmp_path):
    calls = tmp_path / "calls"
    calls.mkdir()
    return tmp_path / "store", calls


def test_interrupted_sweep_resumes_without_recomputing(dirs):
    store, calls = dirs
    tasks = _tasks(calls)
    with cf.ThreadPoolExecutor(max_workers=1) as ex:
        with pytest.raises(KeyboardInterrupt):
            run_sweep(tasks, store, executor=ex, progress=_InterruptAfter(len(tasks), 2))
    st = ResultStore(store)
    done = [t.key for t in tasks if st.check(t.key, t.params)[0] == "done"]
    assert len(done) == 2
    status = run_status(store)                      # the directory says it is not finished
    assert not status["complete"] and "interrupted" in status["why"] and status["done"] == 2
    before = {t.params["x"]: _calls(calls, t.params["x"]) for t in tasks}
    with cf.ThreadPoolExecutor(max_workers=2) as ex:
        s = run_sweep(tasks, store, executor=ex, progress=False)
    assert sorted(s.reused) == sorted(done)
    assert sorted(s.computed) == sorted(set(t.key for t in tasks) - set(done))
    assert run_status(store)["complete"]
    for t in tasks:
        x = t.params["x"]
        if t.key in done:
            assert _calls(calls, x) == before[x] == 1  # finished points: never called again
        else:
            assert _calls(calls, x) == before[x] + 1
    res = load_sweep(store, tasks)
    assert res["x3"].info["sum_y"] == pytest.approx(float(np.sum(np.linspace(0, 3, 50) ** 2)))
    np.testing.assert_array_equal(res["x4"].arrays["y"], np.linspace(0, 4, 50) ** 2)


def test_process_pool_default_and_self_describing_records(dirs):
    store, calls = dirs
    tasks = _tasks(calls, (1.0, 2.0, 3.0, 4.0))
    s = run_sweep(tasks, store, max_workers=2, progress=False, manifest={"study": "unit-test", "scene": {"a": 1}})
    assert sorted(s.computed) == ["x1", "x2", "x3", "x4"] and not s.failed
    pids = {f.split("-")[2] for f in os.listdir(calls)}
    assert os.getpid() not in {int(p) for p in pids}  # really ran in worker processes
    man = ResultStore(store).read_manifest()
    assert man["study"] == "unit-test" and man["scene"] == {"a": 1}
    assert len(man["git_commit"]) in (40, 7) or man["git_commit"] == "unknown"
    assert man["tasks"]["x3"]["params"]["x"] == 3.0
    assert man["tasks"]["x3"]["func"].endswith("square_task")
    rec = json.loads(ResultStore(store).json_path("x3").read_text())
    assert rec["params"]["x"] == 3.0 and "git_commit" in rec["run"] and rec["arrays"]["y"]["shape"] == [50]


def test_failed_point_reported_others_kept(tmp_path):
    tasks = [Task(f"x{x:g}", failing_task, {"x": x}) for x in (1.0, 2.0, 3.0)]
    with cf.ThreadPoolExecutor(max_workers=2) as ex:
        s = run_sweep(tasks, tmp_path, executor=ex, progress=False, log=lambda m: None)
    assert list(s.failed) == ["x2"] and "boom at 2" in s.failed["x2"]
    assert sorted(s.computed) == ["x1", "x3"]
    assert ResultStore(tmp_path).check("x2")[0] == "missing"
    status = run_status(tmp_path)
    assert not status["complete"] and "incomplete" in status["why"]
    assert json.loads((tmp_path / "status.json").read_text())["failed"] == ["x2"]


def test_bad_tasks_rejected(tmp_path):
    with pytest.raises(InputError, match="key"):
        Task("bad key/../x", failing_task, {})
    with pytest.raises(InputError, match="JSON"):
        Task("k", failing_task, {"x": object()})
    with pytest.raises(InputError, match="duplicate"):
        run_sweep([Task("a", failing_task, {"x": 1.0}), Task("a", failing_task, {"x": 1.0})], tmp_path)


class _ClientLike:
    """Stands in for dask.distributed.Client (optional dependency, not installed here): a client is
    not a concurrent.futures.Executor itself but hands one out through get_executor()."""

    def __init__(self, ex):
        self.ex = ex
        self.asked = 0

    def get_executor(self):
        self.asked += 1
        return self.ex


def test_client_with_get_executor_is_used_like_dask(dirs):
    store, calls = dirs
    tasks = _tasks(calls, (1.0, 2.0))
    with cf.ThreadPoolExecutor(max_workers=2) as ex:
        client = _ClientLike(ex)
        s = run_sweep(tasks, store, executor=client, progress=False)
    assert client.asked == 1 and sorted(s.computed) == ["x1", "x2"]


def test_fresh_run_recomputes_kept_points(dirs):
    # resume=False (`fem3d sweep --fresh`): every point computed again, the store overwritten
    store, calls = dirs
    tasks = _tasks(calls, (1.0, 2.0))
    with cf.ThreadPoolExecutor(max_workers=1) as ex:
        run_sweep(tasks, store, executor=ex, progress=False)
        s = run_sweep(tasks, store, executor=ex, progress=False, resume=False)
    assert sorted(s.computed) == ["x1", "x2"] and s.reused == []
    assert _calls(calls, 1.0) == 2 and _calls(calls, 2.0) == 2


def test_failed_point_keeps_its_exception(tmp_path):
    tasks = [Task(f"x{x:g}", failing_task, {"x": x}) for x in (1.0, 2.0)]
    with cf.ThreadPoolExecutor(max_workers=1) as ex:
        s = run_sweep(tasks, tmp_path, executor=ex, progress=False, log=lambda m: None)
    assert isinstance(s.errors["x2"], ValueError) and str(s.errors["x2"]) == "boom at 2"
