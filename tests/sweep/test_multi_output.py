"""Tasks that store several points (``Task.outputs``): each point under its own key, resumed point by point.

A block task (sweep_helpers.chain_block) is a running sum, each point depending on its lower neighbour:
the expected totals are the partial sums of the block's x (1, 1+2, 1+2+3; 4, 4+5), so a resumed point that
did not start from its stored neighbour would come out wrong. Calls are counted by marker files.
"""
import json

import pytest

from contact.errors import InputError
from sweep import ResultStore, Task, load_sweep, point_tasks, run_status, run_sweep
from sweep_helpers import calls as _calls, chain_block, chain_tasks

EXPECTED = {"c1": 1.0, "c2": 3.0, "c3": 6.0, "c4": 4.0, "c5": 9.0}    # partial sums within each block


def _totals(store, tasks):
    return {k: p.info["total"] for k, p in load_sweep(store, tasks, complete=True).items()}


def test_each_output_stored_under_its_key_and_listed_in_the_manifest(dirs):
    store, calls = dirs
    tasks = chain_tasks(calls)
    s = run_sweep(tasks, store, max_workers=2, progress=False, log=lambda m: None)
    assert sorted(s.computed) == sorted(EXPECTED) and not s.failed
    assert _totals(store, tasks) == EXPECTED
    assert ResultStore(store).load("c2", {"x": 2.0}).params == {"x": 2.0}
    man = json.loads((store / "sweep.json").read_text())
    assert sorted(man["tasks"]) == sorted(EXPECTED) and man["tasks"]["c5"]["task"] == "block4-5"
    assert run_status(store)["complete"] and run_status(store)["tasks"] == 5
    assert [t.key for t in point_tasks(tasks)] == ["c1", "c2", "c3", "c4", "c5"]


def test_complete_block_skipped_partial_block_recomputes_only_its_missing_point(dirs):
    store, calls = dirs
    tasks = chain_tasks(calls)
    run_sweep(tasks, store, max_workers=1, progress=False, log=lambda m: None)
    ResultStore(store).json_path("c2").unlink()
    msgs = []
    s = run_sweep(tasks, store, max_workers=1, progress=False, log=msgs.append)
    assert s.computed == ["c2"] and sorted(s.reused) == ["c1", "c3", "c4", "c5"]
    assert "c2" in s.recomputed and any("c2: deleted" in m for m in msgs)
    assert [_calls(calls, x) for x in (1, 2, 3, 4, 5)] == [1, 2, 1, 1, 1]
    assert _totals(store, tasks) == EXPECTED
    assert ResultStore(store).load("c2").info["neighbour_stored"] is True     # started from the stored c1


def test_failing_block_marks_its_missing_points_failed_and_keeps_the_others(dirs):
    store, calls = dirs
    s = run_sweep(chain_tasks(calls, fail_at=5.0), store, max_workers=2, progress=False, log=lambda m: None)
    assert sorted(s.failed) == ["c4", "c5"] and "boom at 5" in s.failed["c5"]
    assert sorted(s.computed) == ["c1", "c2", "c3"]
    assert not run_status(store)["complete"]


def test_block_returning_too_few_points_is_a_failure(dirs):
    store, calls = dirs
    bad = Task("bad", chain_block, {"xs": [1.0], "calls_dir": str(calls)}, (("c1", {"x": 1.0}), ("c9", {"x": 9.0})))
    s = run_sweep([bad], store, max_workers=1, progress=False, log=lambda m: None)
    assert "no result for c9" in s.failed["c9"] and not (store / "points" / "c1.json").exists()


def test_output_keys_must_be_unique_and_file_safe(dirs):
    _, calls = dirs
    with pytest.raises(InputError, match="duplicate keys"):
        run_sweep(chain_tasks(calls, blocks=((1.0, 2.0), (2.0, 3.0))), dirs[0], progress=False)
    with pytest.raises(InputError, match="task key"):
        Task("ok", chain_block, {}, (("bad/key", {}),))


def test_interrupted_after_one_block_resumes_with_the_other_only(dirs):
    from sweep import Progress

    class _StopAfterOne(Progress):
        def update(self, n=1, note=""):
            super().update(n, note)
            raise KeyboardInterrupt

    store, calls = dirs
    tasks = chain_tasks(calls)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(tasks, store, max_workers=1, progress=_StopAfterOne(2, enabled=False), log=lambda m: None)
    assert json.loads((store / "status.json").read_text())["state"] == "interrupted"
    first = {k for k in EXPECTED if (store / "points" / f"{k}.json").exists()}
    assert first in ({"c1", "c2", "c3"}, {"c4", "c5"})
    s = run_sweep(tasks, store, max_workers=1, progress=False, log=lambda m: None)
    assert set(s.computed) == set(EXPECTED) - first and set(s.reused) == first
    # the stored block is not computed again (the other may have been under way when interrupted: lost, rerun)
    assert all(_calls(calls, float(k[1:])) == 1 for k in first) and _totals(store, tasks) == EXPECTED
