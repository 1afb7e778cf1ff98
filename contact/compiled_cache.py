"""Where numba keeps the suite's compiled code, and when that code is stale.

Every ``@njit(cache=True)`` function of the suite (the contact kernel of :mod:`contact._kernel`, the
production step loop of :mod:`rotor.dynamics.production_kernels` …) is compiled once per machine and
loaded from disk by every later process. This module decides:

- **where**: ``$RINGCONTACT_CACHE/numba`` if set (the variable the 3D FEM cache uses), else
  ``$XDG_CACHE_HOME/ringcontact/numba``, else ``~/.cache/ringcontact/numba``; one sub-folder per
  source folder (its path hashed, as numba does), so two checkouts never share entries. Nothing is
  written into the source tree. If that folder cannot be written, a per-user folder under the
  system's temporary directory is used.
- **when stale**: numba checks only the cached function's own source file. A module whose kernels
  inline compiled functions of other modules names them with :func:`compiled_with`; the stamp of
  its entries is then the hash of its own source *and* those modules' sources, so a change in any of
  them recompiles (the old entries are simply not matched; nothing is deleted, so processes starting
  together cannot remove each other's files).

Several processes starting at once are safe: numba writes each index and data file to a unique
temporary name and renames it into place, and a reader that finds an index entry whose data file is
not there yet compiles instead. The worst case is that each of them compiles once.
"""
from __future__ import annotations

import hashlib
import importlib.util
import os
import tempfile
from pathlib import Path

from numba.core.caching import CacheImpl, _CacheLocator

_PACKAGE_ROOT = Path(__file__).resolve().parent.parent   # the folder holding contact/, rotor/, …
_WATCHED: dict[str, tuple[str, ...]] = {}                # source file -> modules compiled into it


def cache_root() -> Path:
    """The folder numba's cache entries of this suite go to (see the module docstring)."""
    root = os.environ.get("RINGCONTACT_CACHE")
    if root:
        return Path(root) / "numba"
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg) if xdg else Path.home() / ".cache") / "ringcontact" / "numba"


def compiled_with(owner_file: str, dependency_modules: list[str]) -> None:
    """Declare that ``owner_file``'s cached kernels compile in code from ``dependency_modules``.

    Call it at the top of the owner module, before its first ``@njit(cache=True)``.

    Parameters
    ----------
    owner_file : str
        ``__file__`` of the module whose ``@njit(cache=True)`` functions use the dependencies.
    dependency_modules : list of str
        Importable module names whose source is compiled into the owner's kernels.
    """
    _install()
    _WATCHED[str(Path(owner_file).resolve())] = tuple(dependency_modules)


def source_stamp(py_file: str) -> bytes:
    """SHA-256 of ``py_file`` followed by the sources of the modules declared with :func:`compiled_with`."""
    path = Path(py_file).resolve()
    digest = hashlib.sha256(path.read_bytes())
    for name in _WATCHED.get(str(path), ()):
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.origin is not None:
            digest.update(name.encode())
            digest.update(Path(spec.origin).read_bytes())
    return digest.digest()


class _SuiteLocator(_CacheLocator):
    """numba cache locator for the suite's own source files (see the module docstring)."""

    def __init__(self, py_func, py_file):
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        self._cache_path = str(cache_root() / self.get_suitable_cache_subpath(py_file))

    def get_cache_path(self):
        return self._cache_path

    def get_source_stamp(self):
        return source_stamp(self._py_file)

    def get_disambiguator(self):
        return str(self._lineno)

    @classmethod
    def from_function(cls, py_func, py_file):
        path = Path(py_file).resolve()
        if str(path) not in _WATCHED and _PACKAGE_ROOT not in path.parents:
            return None
        self = cls(py_func, py_file)
        try:
            self.ensure_cache_path()
        except OSError:
            fallback = Path(tempfile.gettempdir()) / f"ringcontact-numba-{os.getuid()}"
            self._cache_path = str(fallback / self.get_suitable_cache_subpath(py_file))
            try:
                self.ensure_cache_path()
            except OSError:
                return None
        return self


def _install() -> None:
    """Put the suite's locator first in numba's list (once per process)."""
    if _SuiteLocator not in CacheImpl._locator_classes:
        CacheImpl._locator_classes.insert(0, _SuiteLocator)
