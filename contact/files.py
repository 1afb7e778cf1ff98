"""Atomic file writing: never leave a half-written result file, nor a summary beside another run's data.

Files get the mode an ordinary ``open()`` would give them (0666 less the umask: 0644 usually),
not the 0600 of the temporary file they are written through.

:func:`write_run_files` writes a run's files as one unit (``simulate.csv``, ``simulate.npz`` and the
``simulate-summary.json`` describing them): the old summary and old files of the same prefix go
first, the new files are written to temporary names and renamed, and the summary comes last,
carrying the SHA-256 of every file it describes. Interrupted anywhere, the folder holds either a
complete run or files without a summary, never a summary beside files of another run;
:func:`check_run_files` tells which.

Temporaries are named ``.NAME.PID.XXXXXXXX.tmp`` (PID: the writing process). An interruption that
reaches Python (Ctrl-C, SIGTERM through :mod:`contact.interrupts`) removes them on its way out
(:func:`discard_own_temporaries`); those of a writer killed outright (kill -9, power loss) are removed
by the next process writing into the same folder (:func:`remove_stale_temporaries`): only names of
this pattern whose writer is no longer running, or which are older than :data:`STALE_AFTER_S`.
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import tempfile
import time
from pathlib import Path

from contact.errors import DatasetError


#: a temporary of this module: ``.NAME.[PID.]RANDOM.tmp`` (no PID: written by an older version)
_TEMPORARY = re.compile(r"^\.(?P<stem>.+)\.(?P<random>[A-Za-z0-9_]+)\.tmp$")
#: a temporary older than this is stale whoever wrote it (a writer holds one for a single write and rename)
STALE_AFTER_S = 3600.0
_LIVE: set[str] = set()          # temporaries this process holds right now
_SWEPT: set[str] = set()         # folders this process has already cleared of stale temporaries


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def atomic_write_bytes(path: str | os.PathLike, data: bytes) -> Path:
    """Write ``data`` to a temporary file beside ``path`` (``.NAME.*.tmp``), fsync, then rename over ``path``
    (mode 0666 less the umask, as ``open()`` gives)."""
    path = Path(path)
    return _rename_into(_temporary(path, data), path)


def _rename_into(tmp: str, path: Path) -> Path:
    """Rename the temporary ``tmp`` over ``path`` (removed if that fails); ``path``."""
    try:
        _replace(tmp, path)
    except BaseException:
        _discard([tmp])
        raise
    return path


def _temporary(path: Path, data: bytes) -> str:
    """``data`` written and synced to a temporary file beside ``path`` (mode as ``open()`` gives); its name."""
    return _new_temporary(path, lambda fh, name: fh.write(data))


def _new_temporary(path: Path, write) -> str:
    """A temporary file beside ``path`` (``.NAME.PID.XXXXXXXX.tmp``, held in :data:`_LIVE`), filled by
    ``write(binary file object, its name)``, synced, mode as ``open()`` gives; its name. Removed if anything
    fails."""
    path.parent.mkdir(parents=True, exist_ok=True)
    folder = str(path.parent.resolve())
    if folder not in _SWEPT:
        _SWEPT.add(folder)
        remove_stale_temporaries(path.parent)
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.{os.getpid()}.", suffix=".tmp", dir=path.parent)
        _LIVE.add(tmp)
        with os.fdopen(fd, "r+b") as fh:
            write(fh, tmp)
            fh.flush()
            os.fchmod(fh.fileno(), 0o666 & ~_umask())
            os.fsync(fh.fileno())
    except OSError as exc:          # a full disk raises in write or fsync without a file name: name the target
        _discard([tmp] if tmp else [])
        if exc.filename is None:
            raise OSError(exc.errno, exc.strerror or str(exc), str(path)) from exc
        raise
    except BaseException:
        _discard([tmp] if tmp else [])
        raise
    return tmp


def atomic_write_via(path: str | os.PathLike, write_to_name) -> Path:
    """Atomic write for a library that writes only to a file name (meshio): ``write_to_name(tmp)`` writes a
    temporary of this module beside ``path`` (its name ends in ``.tmp``: name the format explicitly, e.g.
    ``meshio.write(tmp, mesh, file_format="vtu")``), which is then renamed over ``path``."""
    path = Path(path)
    return _rename_into(_new_temporary(path, lambda fh, name: write_to_name(name)), path)


def _discard(paths) -> None:
    for p in paths:
        _LIVE.discard(str(p))
        try:
            os.unlink(p)
        except FileNotFoundError:
            pass


def _replace(tmp: str, path) -> None:
    os.replace(tmp, path)
    _LIVE.discard(tmp)


def discard_own_temporaries() -> list[str]:
    """Remove the temporaries this process is writing (an interruption's way out); returns their names."""
    held = sorted(_LIVE)
    _discard(held)
    return held


def writer_running(pid: int) -> bool:
    """Is process ``pid`` (of this machine) still running? (a process of another user counts as running)"""
    try:
        os.kill(int(pid), 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, ValueError):
        return True
    return True


def _stale(entry: os.DirEntry, max_age_s: float, now: float) -> bool:
    """Is ``entry``, a temporary of this module, no longer being written? (see the module docstring)"""
    pid = _TEMPORARY.match(entry.name)["stem"].rpartition(".")[2]
    if pid.isdigit() and not writer_running(int(pid)):
        return True
    try:
        return now - entry.stat(follow_symlinks=False).st_mtime > max_age_s
    except FileNotFoundError:
        return False


def remove_stale_temporaries(*folders: str | os.PathLike, max_age_s: float = STALE_AFTER_S) -> list[Path]:
    """Delete the temporaries of this module (``.NAME.[PID.]RANDOM.tmp``) left in ``folders`` by writers
    that are gone: whose process is no longer running, or older than ``max_age_s`` (0: every one, for a
    caller that knows nobody else writes there, e.g. holding the folder's lock). Returns those removed.
    """
    removed, now = [], time.time()
    for folder in folders:
        try:
            entries = list(os.scandir(folder))
        except (FileNotFoundError, NotADirectoryError):
            continue
        for e in entries:
            if (_TEMPORARY.match(e.name) and e.is_file(follow_symlinks=False)
                    and (max_age_s <= 0 or _stale(e, max_age_s, now))):
                try:
                    os.unlink(e.path)
                    removed.append(Path(e.path))
                except FileNotFoundError:
                    pass
    return removed


def atomic_write_text(path: str | os.PathLike, text: str) -> Path:
    """Text version of :func:`atomic_write_bytes` (UTF-8)."""
    return atomic_write_bytes(path, text.encode("utf-8"))


def sha256_bytes(data: bytes) -> str:
    """Hex SHA-256 of ``data``."""
    return hashlib.sha256(data).hexdigest()


def write_run_files(out: str | os.PathLike, prefix: str, files: dict[str, bytes], summary: dict) -> Path:
    """Write one run's ``files`` (name -> content, each named ``<prefix>.*``) and its summary as one unit.

    Order: the old ``<prefix>-summary.json`` is removed, then the old run's files (the names about to
    be written and every ``<prefix>.*`` file the old summary describes: stale companions, never a
    user's other file) and stale temporaries; the new files are written to temporary names and
    renamed into place; the summary (``summary`` plus ``"files": {name: {"sha256", "bytes"}}``) is
    written last, atomically. Returns the summary's path.
    """
    out = Path(out)
    if any(not name.startswith(prefix + ".") or "/" in name for name in files):
        raise ValueError(f"run files must be named {prefix}.*: {sorted(files)}")
    summary_path = out / f"{prefix}-summary.json"
    out.mkdir(parents=True, exist_ok=True)
    stale = set(files) | _described(summary_path, prefix)
    _discard([summary_path])                                   # from here on the old run is incomplete
    _discard([out / name for name in sorted(stale)] + [p for pattern in (f".{prefix}.*.tmp", f".{prefix}-summary.json.*.tmp")
                                                       for p in out.glob(pattern) if p.is_file()])
    temporaries = {}
    try:
        for name, data in files.items():
            temporaries[name] = _temporary(out / name, data)
        for name, tmp in temporaries.items():
            _replace(tmp, out / name)
    except BaseException:
        _discard(temporaries.values())
        raise
    described = {name: {"sha256": sha256_bytes(data), "bytes": len(data)} for name, data in files.items()}
    return atomic_write_text(summary_path, json.dumps({**summary, "files": described}, indent=2) + "\n")


def _described(summary_path: Path, prefix: str) -> set[str]:
    """Names of the ``<prefix>.*`` files an existing summary describes (none if it is unreadable)."""
    try:
        described = json.loads(summary_path.read_text(encoding="utf-8")).get("files", {})
    except (OSError, ValueError, AttributeError):
        return set()
    return {n for n in described if isinstance(n, str) and n.startswith(prefix + ".") and "/" not in n
            and "\\" not in n and n not in (".", "..")} if isinstance(described, dict) else set()


def check_run_files(out: str | os.PathLike, prefix: str) -> dict:
    """The summary of the run in ``out``, after checking that the files it describes are the ones present.

    Raises
    ------
    DatasetError
        no summary (the run was interrupted or never ran), or a described file missing or changed.
    """
    out = Path(out)
    path = out / f"{prefix}-summary.json"
    try:
        summary = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise DatasetError(f"{path}: no complete run here (no readable summary: {exc})") from None
    described = summary.get("files")
    if not isinstance(described, dict) or not described:
        raise DatasetError(f"{path}: the summary lists no files (written by an older version?)")
    for name, want in described.items():
        try:
            data = (out / name).read_bytes()
        except OSError:
            raise DatasetError(f"{path}: {name} is missing: the run is incomplete") from None
        if sha256_bytes(data) != want.get("sha256"):
            raise DatasetError(f"{path}: {name} is not the file this summary describes (checksum differs)")
    return summary
