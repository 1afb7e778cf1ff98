"""Resumable, corruption-detecting sweeps (sweep.store).

Must show (issue 8): an interrupted sweep resumes without recomputing finished points, and a
corrupted result file is detected and recomputed, not read. Each task below leaves a marker
file per call, so "not recomputed" is counted, not assumed.
"""
import concurrent.futures as cf
import io
import json
import os

import numpy as np
import pytest

from contact.errors import DatasetError, InputError
from sweep.store import Progress, ResultStore, Task, load_sweep, run_sweep


def square_task(x: float, calls_dir: str):
    """Cheap deterministic task; records each call in calls_dir (top level: picklable)."""
    n = len(os.listdir(calls_dir))
    with open(os.path.join(calls_dir, f"call-{x:g}-{os.getpid()}-{n}-{os.urandom(4).hex()}"), "w"):
        pass
    return {"x": np.array([x]), "y": np.linspace(0, x, 50) ** 2}, {"sum_y": float(np.sum(np.linspace(0, x, 50) ** 2))}


def failing_task(x: float):
    if x == 2.0:
        raise ValueError("boom at 2")
    return {"x": np.array([x])}, {}


def _calls(d, x):
    return sum(1 for f in os.listdir(d) if f.startswith(f"call-{x:g}-"))


def _tasks(calls, xs=(1.0, 2.0, 3.0, 4.0, 5.0)):
    return [Task(f"x{x:g}", square_task, {"x": x, "calls_dir": str(calls)}) for x in xs]


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
    before = {t.params["x"]: _calls(calls, t.params["x"]) for t in tasks}
    with cf.ThreadPoolExecutor(max_workers=2) as ex:
        s = run_sweep(tasks, store, executor=ex, progress=False)
    assert sorted(s.reused) == sorted(done)
    assert sorted(s.computed) == sorted(set(t.key for t in tasks) - set(done))
    for t in tasks:
        x = t.params["x"]
        if t.key in done:
            assert _calls(calls, x) == before[x] == 1  # finished points: never called again
        else:
            assert _calls(calls, x) == before[x] + 1
    res = load_sweep(store, tasks)
    assert res["x3"].info["sum_y"] == pytest.approx(float(np.sum(np.linspace(0, 3, 50) ** 2)))
    np.testing.assert_array_equal(res["x4"].arrays["y"], np.linspace(0, 4, 50) ** 2)


@pytest.mark.parametrize("damage", ["flip-npz-byte", "truncate-npz", "delete-npz", "truncate-json",
                                    "edit-json-value", "garbage-json"])
def test_corrupted_point_is_detected_and_recomputed_not_read(dirs, damage):
    store, calls = dirs
    tasks = _tasks(calls, (1.0, 2.0, 3.0))
    with cf.ThreadPoolExecutor(max_workers=2) as ex:
        run_sweep(tasks, store, executor=ex, progress=False)
    st = ResultStore(store)
    npz, js = st.npz_path("x2"), st.json_path("x2")
    if damage == "flip-npz-byte":
        b = bytearray(npz.read_bytes())
        b[len(b) // 2] ^= 0x01
        npz.write_bytes(bytes(b))
    elif damage == "truncate-npz":
        npz.write_bytes(npz.read_bytes()[:-10])
    elif damage == "delete-npz":
        npz.unlink()
    elif damage == "truncate-json":
        js.write_text(js.read_text()[:40])
    elif damage == "edit-json-value":
        rec = json.loads(js.read_text())
        rec["info"]["sum_y"] = 123.0  # valid JSON, wrong content: the record checksum catches it
        js.write_text(json.dumps(rec))
    elif damage == "garbage-json":
        js.write_text("not json at all")
    status, why = st.check("x2", tasks[1].params)
    assert status == "corrupt", why
    with pytest.raises(DatasetError, match="corrupt"):
        st.load("x2")  # never read
    assert "x2" not in load_sweep(store, tasks)
    messages = []
    with cf.ThreadPoolExecutor(max_workers=2) as ex:
        s = run_sweep(tasks, store, executor=ex, progress=False, log=messages.append)
    assert s.computed == ["x2"] and sorted(s.reused) == ["x1", "x3"]
    assert "x2" in s.recomputed and any("x2" in m and "corrupt" in m for m in messages)
    assert _calls(calls, 2.0) == 2 and _calls(calls, 1.0) == 1
    assert st.check("x2", tasks[1].params)[0] == "done"
    assert st.load("x2").info["sum_y"] == pytest.approx(float(np.sum(np.linspace(0, 2, 50) ** 2)))


def test_changed_parameters_make_a_point_stale(dirs):
    store, calls = dirs
    tasks = _tasks(calls, (1.0,))
    with cf.ThreadPoolExecutor(max_workers=1) as ex:
        run_sweep(tasks, store, executor=ex, progress=False)
    other = [Task("x1", square_task, {"x": 1.5, "calls_dir": str(calls)})]
    assert ResultStore(store).check("x1", other[0].params)[0] == "stale"
    with cf.ThreadPoolExecutor(max_workers=1) as ex:
        s = run_sweep(other, store, executor=ex, progress=False, log=lambda m: None)
    assert s.computed == ["x1"]
    assert ResultStore(store).load("x1").arrays["x"][0] == 1.5


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


def test_bad_tasks_rejected(tmp_path):
    with pytest.raises(InputError, match="key"):
        Task("bad key/../x", failing_task, {})
    with pytest.raises(InputError, match="JSON"):
        Task("k", failing_task, {"x": object()})
    with pytest.raises(InputError, match="duplicate"):
        run_sweep([Task("a", failing_task, {"x": 1.0}), Task("a", failing_task, {"x": 1.0})], tmp_path)


class _FakeTTY(io.StringIO):
    def isatty(self):
        return True


def test_progress_quiet_when_piped_or_under_ci(monkeypatch):
    monkeypatch.delenv("CI", raising=False)
    piped = io.StringIO()
    p = Progress(3, stream=piped)
    p.update()
    p.close()
    assert piped.getvalue() == ""
    tty = _FakeTTY()
    p = Progress(3, stream=tty)
    p.update(note="x1")
    assert "1/3" in tty.getvalue() and "pt/s" in tty.getvalue()
    monkeypatch.setenv("CI", "true")
    tty2 = _FakeTTY()
    p = Progress(3, stream=tty2)
    p.update()
    assert tty2.getvalue() == ""


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
