"""BLAS/OpenMP threads per process: each process gets its share of the machine's cores.

Threaded BLAS in every one of several worker processes on a shared 2-core machine oversubscribes
the cores (a 3D level build took 79-89 s with default threading against 29 s with one thread,
issue 17). The thread count of OpenBLAS, MKL and OpenMP is read from environment variables when
the library loads, so it must be set before numpy/scipy are imported in the process
(threadpoolctl, which changes it later, is not a dependency). The sweep's local pool therefore starts
its workers with the ``spawn`` method (:func:`sweep.run.local_pool`), after setting the variables below in the parent's
environment, which the workers inherit. A command-line job that computes in its own process
(``ringcontact fem3d point``) calls :func:`set_thread_env` before importing numpy. This module
imports nothing heavy so that it can run first.
"""
from __future__ import annotations

import os

THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
USER_OVERRIDE = "RINGCONTACT_THREADS"


def usable_cores() -> int:
    """Cores this process may run on (its CPU affinity), at least 1."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def thread_share(processes: int) -> int:
    """BLAS threads for each of ``processes`` concurrent processes, or ``$RINGCONTACT_THREADS`` when set.

    The share is ``cores // processes``, but no more than the cores the others leave idle,
    ``round(cores - load)`` with ``load`` the 1-minute load average, and at least 1. Measured on the
    shared 2-core machine at load 4.4 (reports/published/fem3d-perf.md): a cold 3D point took 55 s
    with 2 BLAS threads against 11 s with 1."""
    text = os.environ.get(USER_OVERRIDE, "").strip()
    if text.isdigit() and int(text) > 0:
        return int(text)
    cores = usable_cores()
    try:
        idle = round(cores - os.getloadavg()[0])
    except (AttributeError, OSError):
        idle = cores
    return max(1, min(cores // max(1, int(processes)), idle))


def set_thread_env(threads: int, override: bool = False) -> dict:
    """Set the thread variables in ``os.environ`` (kept if already set, unless ``override``);
    returns what they hold afterwards. Effective only for libraries loaded later (child processes,
    or this one if numpy is not imported yet)."""
    for k in THREAD_VARIABLES:
        if override or k not in os.environ:
            os.environ[k] = str(int(threads))
    return {k: os.environ[k] for k in THREAD_VARIABLES}
