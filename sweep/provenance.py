"""Where a result came from: code revision, package versions, machine, time stamp.

Every sweep record (:mod:`sweep.store` manifests and point records, the FEM reference
datasets' metadata) is stamped with these, so a number on disk says which code and which
libraries computed it.
"""
from __future__ import annotations

import datetime as _dt
import functools
import importlib
import importlib.metadata
import os
import platform
import subprocess
from pathlib import Path
from typing import Mapping, Sequence

from contact.stamp import build_stamp, is_source_checkout

ROOT = Path(__file__).resolve().parents[1]


def code_revision(path: str | os.PathLike | None = None, *, scope: Sequence[str] | None = None,
                  untracked: bool = False) -> dict:
    """Git commit of the source tree and whether it had uncommitted changes.

    Parameters
    ----------
    path : directory inside the repository (default: the suite's root)
    scope : paths (relative to the repository) whose changes count as ``dirty``; default all
    untracked : count untracked files under ``scope`` as changes too

    Returns
    -------
    ``{"git_commit": sha or "unknown", "git_dirty": bool, or None when git is unavailable}``
    """
    if path is None and not is_source_checkout():
        stamp = build_stamp() or {}                 # an installed wheel: the commit stamped at build time
        return {"git_commit": stamp.get("git_commit", "unknown"), "git_dirty": stamp.get("git_dirty")}
    root = Path(path) if path is not None else ROOT
    status = ["git", "status", "--porcelain"] + ([] if untracked else ["--untracked-files=no"])
    if scope:
        status += ["--", *scope]
    try:
        rev = subprocess.run(["git", "rev-parse", "HEAD"], cwd=root, capture_output=True, text=True,
                             timeout=10).stdout.strip()
        st = subprocess.run(status, cwd=root, capture_output=True, text=True, timeout=10).stdout
        return {"git_commit": rev or "unknown", "git_dirty": bool(st.strip())}
    except (OSError, subprocess.SubprocessError):
        return {"git_commit": "unknown", "git_dirty": None}


def revision_label(revision: Mapping) -> str:
    """One string for a :func:`code_revision`: the commit, ``+dirty`` if it had changes."""
    return str(revision.get("git_commit") or "unknown") + ("+dirty" if revision.get("git_dirty") else "")


def package_versions(modules: Mapping[str, str] | Sequence[str] = ("numpy", "scipy"), *,
                     required: bool = True) -> dict:
    """Python and package versions, e.g. ``{"python": "3.11.7", "numpy": "1.26.4", ...}``.

    ``modules`` maps the name to record to the module to import (``{"scikit-fem": "skfem"}``),
    or lists modules recorded under their own names. A missing module raises ImportError when
    ``required``, else it is recorded as None.
    """
    pairs = modules.items() if isinstance(modules, Mapping) else ((m, m) for m in modules)
    out: dict = {"python": platform.python_version()}
    for name, module in pairs:
        try:
            out[name] = importlib.import_module(module).__version__
        except ImportError:
            if required:
                raise
            out[name] = None
    return out


def environment() -> dict:
    """Python, numpy, scipy, numba versions and the machine (for the rotor sweep record)."""
    import numpy as np

    env = {"python": platform.python_version(), "numpy": np.__version__, "machine": platform.machine(),
           "cpu_count": os.cpu_count()}
    versions = package_versions(("scipy", "numba"), required=False)
    env.update({k: versions[k] for k in ("scipy", "numba")})
    return env


def machine() -> dict:
    """The platform string and CPU count (for dataset metadata)."""
    return {"platform": platform.platform(), "cpu_count": os.cpu_count()}


def utc_stamp() -> str:
    """Now in UTC, ``YYYY-MM-DDTHH:MM:SSZ``."""
    return _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS")


def blas_threads() -> dict:
    """Threads the BLAS of this process may use: ``{"blas_threads": n or None, "thread_env": {...}}``.

    ``blas_threads`` is what threadpoolctl reports when it is installed, else the first of
    ``OPENBLAS_NUM_THREADS``, ``OMP_NUM_THREADS``, ``MKL_NUM_THREADS`` that is set (None: the
    library's default, one per core). ``thread_env`` holds those variables as set in the process.
    """
    env = {k: os.environ[k] for k in _THREAD_VARIABLES if k in os.environ}
    n = None
    try:
        from threadpoolctl import threadpool_info
        found = [i["num_threads"] for i in threadpool_info() if i.get("user_api") == "blas"]
        n = max(found) if found else None
    except ImportError:
        for k in _THREAD_VARIABLES[:3]:
            if env.get(k, "").strip().isdigit():
                n = int(env[k])
                break
    return {"blas_threads": n, "thread_env": env}


def package_version(name: str = "ringcontact") -> str | None:
    """The installed version of the suite (None when it runs from a source tree not installed)."""
    try:
        return importlib.metadata.version(name)
    except importlib.metadata.PackageNotFoundError:
        return None


@functools.lru_cache(maxsize=1)
def _process_revision() -> tuple:
    rev = code_revision()
    return rev["git_commit"], rev["git_dirty"]


def worker_stamp() -> dict:
    """Where a point is computed, taken in the process computing it (a pool or cluster worker).

    Host, pid, the suite's package version and git commit as that process sees its own source
    tree (asked once per process), its BLAS threads and CPU count.
    """
    commit, dirty = _process_revision()
    return {"host": platform.node(), "pid": os.getpid(), "package_version": package_version(),
            "git_commit": commit, "git_dirty": dirty, **blas_threads(), "cpu_count": os.cpu_count()}
