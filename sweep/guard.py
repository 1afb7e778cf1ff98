"""One writer per result directory, and no stale temporaries left in it.

:class:`DirectoryLock` holds an exclusive ``flock`` on ``<root>/.lock`` for as long as a sweep
writes into ``<root>``. The kernel drops the lock when its holder dies, however it dies (kill -9
included), so a lock is never stale. A second writer either waits (``wait_s``) or is refused
with :class:`DirectoryBusy`, whose one-line message names the directory and the holder (pid,
host, start time, read from the lock file).

:func:`remove_stale_temporaries` deletes the temporaries of :mod:`contact.files` (``.NAME.*.tmp``)
that a writer killed mid-write left behind; called only while holding the lock, when nobody else
can be writing them (outside a locked directory, :mod:`contact.files` removes only those of dead writers).

Note: ``flock`` is per machine on most network file systems; on a cluster only the client
process writes the result directory (workers return their results to it), so one machine
holds the lock.
"""
from __future__ import annotations

import fcntl
import json
import os
import platform
import time
from pathlib import Path

from contact import files
from contact.errors import RingContactError


class DirectoryBusy(RingContactError, RuntimeError):
    """Another sweep is writing into the same result directory."""


def _holder(path: Path) -> str:
    try:
        info = json.loads(path.read_text(encoding="utf-8"))
        return f"pid {info['pid']} on {info['host']} since {info['since_utc']}"
    except (OSError, ValueError, KeyError, TypeError):
        return "another process"


class DirectoryLock:
    """Exclusive lock on a result directory (context manager), see the module docstring.

    Parameters
    ----------
    root : directory to lock (created if missing)
    wait_s : how long a second writer waits for the lock before :class:`DirectoryBusy` (0: refuse at once)
    """

    def __init__(self, root: str | os.PathLike, wait_s: float = 0.0):
        self.root = Path(root)
        self.path = self.root / ".lock"
        self.wait_s = float(wait_s)
        self._fd: int | None = None

    def acquire(self) -> "DirectoryLock":
        self.root.mkdir(parents=True, exist_ok=True)
        fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        deadline = time.monotonic() + self.wait_s
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() >= deadline:
                    os.close(fd)
                    raise DirectoryBusy(f"{self.root}: another sweep is writing here ({_holder(self.path)}); "
                                        "wait for it to finish or use another output directory") from None
                time.sleep(0.2)
        stamp = {"pid": os.getpid(), "host": platform.node(),
                 "since_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
        os.ftruncate(fd, 0)
        os.pwrite(fd, (json.dumps(stamp) + "\n").encode(), 0)
        self._fd = fd
        return self

    def release(self) -> None:
        if self._fd is not None:
            fcntl.flock(self._fd, fcntl.LOCK_UN)
            os.close(self._fd)
            self._fd = None

    def __enter__(self) -> "DirectoryLock":
        return self.acquire()

    def __exit__(self, *exc) -> None:
        self.release()


def remove_stale_temporaries(*folders: str | os.PathLike) -> list[Path]:
    """Delete the atomic-write temporaries (``.NAME.*.tmp``) in ``folders``; returns those removed.

    Call only while holding the folders' :class:`DirectoryLock`: then no live writer owns them, and
    every one goes whatever its age (:func:`contact.files.remove_stale_temporaries` with ``max_age_s=0``).
    """
    return files.remove_stale_temporaries(*folders, max_age_s=0)
