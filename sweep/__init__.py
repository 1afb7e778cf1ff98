"""Resumable sweeps of independent tasks: checksummed result store, executors, progress, provenance.

One machinery for every sweep of the suite (rotor studies, 2D and 3D FEM reference datasets):

- :mod:`sweep.tasks`: :class:`Task` (key, picklable function, JSON parameters), :class:`PointResult`;
- :mod:`sweep.store`: :class:`ResultStore` (one checksummed NPZ + JSON per point), :func:`load_sweep`;
- :mod:`sweep.run`: :func:`run_sweep` over a :class:`concurrent.futures.Executor` (default a local
  process pool), resuming from the store;
- :mod:`sweep.progress`: :class:`Progress` (count, rate, time left on a terminal; quiet under CI
  or when piped);
- :mod:`sweep.provenance`: :func:`code_revision`, :func:`package_versions`, :func:`environment`,
  :func:`worker_stamp` (taken in the process computing a point);
- :mod:`sweep.guard`: :class:`DirectoryLock` (one writer per result directory), stale temporaries;
- :mod:`sweep.cluster`: :func:`connect` to a ``dask.distributed`` scheduler (the ``dask`` extra).
"""
from sweep.guard import DirectoryBusy, DirectoryLock
from sweep.progress import Progress
from sweep.provenance import (code_revision, environment, machine, package_versions, revision_label, utc_stamp,
                              worker_stamp)
from sweep.run import SweepSummary, as_executor, local_pool, run_sweep
from sweep.store import FORMAT, ResultStore, append_timing, load_sweep, read_timing, run_state, run_status, write_status
from sweep.tasks import PointResult, Task, point_tasks

__all__ = ["FORMAT", "DirectoryBusy", "DirectoryLock", "PointResult", "Progress", "ResultStore", "SweepSummary",
           "Task", "append_timing", "as_executor", "local_pool", "code_revision", "environment", "load_sweep", "machine",
           "package_versions", "point_tasks", "read_timing", "revision_label", "run_state", "run_status", "run_sweep", "utc_stamp", "worker_stamp",
           "write_status"]
