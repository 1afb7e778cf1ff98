"""Sweeps on a real dask.distributed LocalCluster (2 process workers), issue 15.

Must show: the sweep equals the local pool bit for bit; a worker killed mid-sweep loses no
finished point and the re-run resumes; the recorded host/commit are the worker's; closing the
cluster logs no "worker still alive" warning.
"""
import json
import logging
import os

import numpy as np
import pytest

from sweep import ResultStore, Task, load_sweep, run_sweep
from sweep.cluster import connect
from sweep_helpers import calls as _calls, dying_task

distributed = pytest.importorskip("distributed")  # the test extra installs it

RPM = (1500.0, 3000.0, 4500.0)
OPTIONS = {"steps_per_rev": 64, "max_revs": 100}


class _Records(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.messages = []

    def emit(self, record):
        self.messages.append(record.getMessage())


def _cluster(**config):
    import dask

    with dask.config.set(config):
        return distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                        dashboard_address=":0")


def _close(c):
    """Close a cluster; fail on a 'worker still alive' (or any other) warning while closing."""
    records = _Records()
    logging.getLogger("distributed").addHandler(records)
    try:
        c.close()
    finally:
        logging.getLogger("distributed").removeHandler(records)
    assert not records.messages, records.messages


@pytest.fixture(scope="module")
def cluster():
    c = _cluster()
    try:
        yield c
    finally:
        _close(c)


def _rotor_tasks():
    from rotor.studies.steady_state import sweep_tasks

    return sweep_tasks("paper-table4", RPM, options=OPTIONS)


def _worker_pids(client):
    return set(client.run(os.getpid).values())


def test_dask_sweep_equals_the_local_pool_bit_for_bit(cluster, tmp_path):
    tasks = _rotor_tasks()
    pool = run_sweep(tasks, tmp_path / "pool", max_workers=2, progress=False)
    with connect(cluster.scheduler_address) as client:
        on_dask = run_sweep(tasks, tmp_path / "dask", executor=client, progress=False)
        pids = _worker_pids(client)
    assert sorted(pool.computed) == sorted(on_dask.computed) == sorted(t.key for t in tasks)
    a, b = load_sweep(tmp_path / "pool", tasks), load_sweep(tmp_path / "dask", tasks)
    for t in tasks:
        assert sorted(a[t.key].arrays) == sorted(b[t.key].arrays)
        for name, x in a[t.key].arrays.items():
            y = b[t.key].arrays[name]
            assert x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes(), (t.key, name)
        drop = {"wall_s"}
        assert {k: v for k, v in a[t.key].info.items() if k not in drop} == \
               {k: v for k, v in b[t.key].info.items() if k not in drop}
        assert b[t.key].record["run"]["worker"]["pid"] in pids
    assert np.abs(a["rpm3000.0"].arrays["harm_v"]).max() > 0  # a real response, not zeros


def test_recorded_host_and_commit_are_the_workers(cluster, tmp_path, monkeypatch):
    import platform

    import sweep.provenance as prov
    import sweep.run as run

    # the client process claims another host and commit: none of it may reach the point records
    monkeypatch.setattr(platform, "node", lambda: "client-host")
    monkeypatch.setattr(run, "code_revision", lambda **kw: {"git_commit": "client-commit", "git_dirty": True})
    monkeypatch.setattr(prov, "_process_revision", lambda: ("client-commit", True))
    calls = tmp_path / "calls"
    calls.mkdir()
    from sweep_helpers import square_tasks

    tasks = square_tasks(calls, (1.0, 2.0, 3.0, 4.0))
    with connect(cluster.scheduler_address) as client:
        run_sweep(tasks, tmp_path / "st", executor=client, progress=False)
        stamps = {s["pid"]: s for s in client.run(prov.worker_stamp).values()}
    st = ResultStore(tmp_path / "st")
    assert st.read_manifest()["git_commit"] == "client-commit"  # the client's own record is the client's
    for t in tasks:
        run_rec = st.load(t.key).record["run"]
        w = run_rec["worker"]
        assert w["pid"] != os.getpid() and w["pid"] in stamps
        assert run_rec["host"] == w["host"] == stamps[w["pid"]]["host"] != "client-host"
        assert run_rec["git_commit"] == w["git_commit"] == stamps[w["pid"]]["git_commit"] != "client-commit"
        assert run_rec["client_host"] == "client-host"
        assert w["blas_threads"] == stamps[w["pid"]]["blas_threads"]


def test_worker_killed_mid_sweep_loses_no_finished_point_and_rerun_resumes(tmp_path):
    calls = tmp_path / "calls"
    calls.mkdir()
    tasks = [Task(f"x{x:g}", dying_task, {"x": x, "calls_dir": str(calls), "die_at": 4.0})
             for x in (1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0)]
    said = []
    c = _cluster(**{"distributed.scheduler.allowed-failures": 0})  # a task whose worker dies fails at once
    try:
        with connect(c.scheduler_address) as client:
            first = run_sweep(tasks, tmp_path / "st", executor=client, progress=False, log=said.append)
            # x4 and whatever else the dead worker held fail (KilledWorker); the rest is stored
            assert (calls / "died").exists() and "x4" in first.failed
            assert all("KilledWorker" in why for why in first.failed.values())
            assert sorted(first.computed + list(first.failed)) == sorted(t.key for t in tasks)
            assert len(first.computed) >= 4
            st = ResultStore(tmp_path / "st")
            assert all(st.check(k)[0] == "done" for k in first.computed)  # nothing finished was lost
            again = run_sweep(tasks, tmp_path / "st", executor=client, progress=False, log=said.append)
    finally:
        _close(c)
    assert sorted(again.computed) == sorted(first.failed) and sorted(again.reused) == sorted(first.computed)
    assert _calls(calls, 4.0) == 1 and sorted(load_sweep(tmp_path / "st", complete=True)) == sorted(
        t.key for t in tasks)


@pytest.mark.parametrize("command", ["study cascade", "study sensitivity", "fem-sweep", "fem3d sweep"])
def test_unreachable_scheduler_is_one_line_on_every_sweep_command(command, tmp_path, capsys):
    from reports.cli import fem, fem3d, study

    out = tmp_path / "never"
    main, argv = {"study cascade": (study.main, ["cascade", "--points", "2", "--out", str(out)]),
                  "study sensitivity": (study.main, ["sensitivity", "--out", str(out), "--to", str(out)]),
                  "fem-sweep": (fem.sweep_main, ["--out", str(out / "d.json")]),
                  "fem3d sweep": (fem3d.sweep_main, ["--out", str(out / "d.json")])}[command]
    assert main(argv + ["--scheduler", "tcp://127.0.0.1:9"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "tcp://127.0.0.1:9" in err and "no dask scheduler" in err
    assert not out.exists()


def test_study_cascade_on_the_cluster_by_its_address(cluster, tmp_path, capsys):
    from reports.cli import study

    out = tmp_path / "c"
    argv = ["cascade", "--rpm-min", "1500", "--rpm-max", "3000", "--points", "2", "--steps-per-rev", "64",
            "--max-revs", "100", "--no-progress", "--out", str(out), "--scheduler", cluster.scheduler_address]
    assert study.main(argv) == 0
    assert "2 computed" in capsys.readouterr().out
    with connect(cluster.scheduler_address) as client:
        pids = _worker_pids(client)
    st = ResultStore(out)
    assert {st.load(k).record["run"]["worker"]["pid"] for k in ("rpm1500.0", "rpm3000.0")} <= pids
    assert (out / "figures" / "study-cascade.csv").exists()


def test_fem2d_scene_on_the_cluster_equals_the_local_run(cluster):
    # gmsh meshes in a dask worker's task thread (it used to fail: 'signal only works in main thread')
    from fem_reference.plane.sweep import sweep_dataset

    kw = {"scene_names": ("clamped",), "penetrations_m": [1e-5], "levels_m": (4e-3, 2e-3, 1e-3)}
    with connect(cluster.scheduler_address) as client:
        _, on_dask = sweep_dataset(executor=client, **kw)
    _, local = sweep_dataset(**kw)
    drop = ("wall_s", "wall_levels_s")
    assert [{k: v for k, v in p.items() if k not in drop} for p in on_dask] == \
           [{k: v for k, v in p.items() if k not in drop} for p in local]
    assert on_dask[0]["force_n"] > 1e5


def test_bearing_job_on_the_cluster_equals_the_local_pool(cluster, tmp_path, capsys):
    """``ringcontact bearing FILE --scheduler ADDRESS``: the 2D points computed by the cluster's workers are the
    local pool's, bit for bit, and so is the law (a 2D-only variant of the bundled steel-in-aluminium pair)."""
    from fem_reference.ring_scene import RING_SCENE_DIR
    from contact.dataset import read_dataset
    from reports.cli.bearing import main

    text = RING_SCENE_DIR.joinpath("steel-in-aluminium.toml").read_text().replace(
        "tilt_arcmin = [0, 2]", "tilt_arcmin = [0, 0]\npenetration_points_mm = [0.004, 0.01, 0.02, 0.04]")
    f = tmp_path / "pair.toml"
    f.write_text(text)
    assert main([str(f), "--out", str(tmp_path / "pool"), "--workers", "2"]) == 0
    assert main([str(f), "--out", str(tmp_path / "dask"), "--scheduler", cluster.scheduler_address]) == 0
    a = read_dataset(tmp_path / "pool" / "fem2d-steel-in-aluminium.json").points
    b = read_dataset(tmp_path / "dask" / "fem2d-steel-in-aluminium.json").points
    assert [p["force_n"] for p in a] == [p["force_n"] for p in b] and len(a) == 4
    law_a = json.loads((tmp_path / "pool" / "steel-in-aluminium-law.json").read_text())
    law_b = json.loads((tmp_path / "dask" / "steel-in-aluminium-law.json").read_text())
    assert law_a["parameters"] == law_b["parameters"]
