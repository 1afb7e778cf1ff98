"""The checksummed result store (sweep.store): corrupted points are detected and recomputed, not read.

Must show (issue 8): a corrupted result file is detected and recomputed, never read; a point
computed with other parameters is stale. The store format (file names, FORMAT, checksums) is what
existing result directories hold, so it is pinned here too.
"""
import concurrent.futures as cf
import hashlib
import json

import numpy as np
import pytest

from contact.errors import DatasetError
from sweep import FORMAT, ResultStore, Task, load_sweep, run_sweep
from sweep_helpers import calls as _calls, square_task, square_tasks as _tasks


@pytest.fixture
def dirs(tmp_path):
    calls = tmp_path / "calls"
    calls.mkdir()
    return tmp_path / "store", calls


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


def test_store_format_is_unchanged(tmp_path):
    # existing result directories must keep loading: the record names its format, the NPZ's
    # SHA-256 and its own checksum over the canonical JSON without the checksum field
    st = ResultStore(tmp_path)
    st.save("rpm3600", {"speed_rpm": 3600}, {"t_s": np.arange(3.0)}, {"peak_m": 1e-5})
    assert FORMAT == "ringcontact.sweep-point/1"
    assert sorted(p.name for p in (tmp_path / "points").iterdir()) == ["rpm3600.json", "rpm3600.npz"]
    rec = json.loads(st.json_path("rpm3600").read_text())
    assert rec["format"] == FORMAT
    assert rec["npz_sha256"] == hashlib.sha256(st.npz_path("rpm3600").read_bytes()).hexdigest()
    claimed = rec.pop("record_sha256")
    canonical = json.dumps(rec, sort_keys=True, separators=(",", ":"))
    assert claimed == hashlib.sha256(canonical.encode()).hexdigest()


def test_point_without_arrays_round_trips(tmp_path):
    # the FEM sweeps keep a whole point in the JSON record (no arrays): still checksummed
    st = ResultStore(tmp_path)
    info = {"force_n": 1234.5678901234567, "levels": [1, 2, 3], "order": None, "method": "pdas"}
    st.save("pen10000nm-tilt0nrad", {"penetration_m": 1e-5}, {}, info)
    assert st.check("pen10000nm-tilt0nrad", {"penetration_m": 1e-5}) == ("done", "")
    back = st.load("pen10000nm-tilt0nrad")
    assert back.info == info and back.arrays == {}
    assert st.check("pen10000nm-tilt0nrad", {"penetration_m": 2e-5})[0] == "stale"
