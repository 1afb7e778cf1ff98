"""contact/threads.py and the sweep pool: each process gets its share of the cores for BLAS/OpenMP."""
from __future__ import annotations

import os

from contact.threads import THREAD_VARIABLES, set_thread_env, thread_share, usable_cores


def _worker_env() -> dict:
    import numpy  # noqa: F401 - loaded after the variables were inherited
    return {k: os.environ.get(k) for k in THREAD_VARIABLES}


def test_share_is_cores_over_processes_at_most_the_idle_ones(monkeypatch):
    monkeypatch.delenv("RINGCONTACT_THREADS", raising=False)
    monkeypatch.setattr(os, "getloadavg", lambda: (0.0, 0.0, 0.0))
    cores = usable_cores()
    assert thread_share(1) == cores and thread_share(cores) == 1 and thread_share(10 * cores) == 1
    monkeypatch.setattr(os, "getloadavg", lambda: (cores + 3.0, 0.0, 0.0))    # busy machine: one thread
    assert thread_share(1) == 1
    monkeypatch.setenv("RINGCONTACT_THREADS", "3")                           # explicit choice wins
    assert thread_share(1) == 3


def test_set_thread_env_keeps_explicit_values(monkeypatch):
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "7")
    monkeypatch.delenv("OMP_NUM_THREADS", raising=False)
    env = set_thread_env(2)
    assert env["OPENBLAS_NUM_THREADS"] == "7" and env["OMP_NUM_THREADS"] == "2"
    assert set_thread_env(2, override=True)["OPENBLAS_NUM_THREADS"] == "2"


def test_pool_workers_start_with_the_thread_variables(monkeypatch):
    # sweep.run.local_pool(threads_per_worker=n) spawns fresh workers (numpy loads after the
    # variables are set in their environment); forked workers would keep the parent's BLAS threads
    from sweep.run import local_pool

    for k in THREAD_VARIABLES:
        monkeypatch.setenv(k, "5")
    with local_pool(1, threads_per_worker=1) as ex:
        env = ex.submit(_worker_env).result(timeout=120)
    assert env == {k: "1" for k in THREAD_VARIABLES}
