"""Files shipped inside the packages, found through :mod:`importlib.resources`.

The data the suite ships (``contact/calibrated/*.json``, ``rotor/scenes/*.toml``,
``fem_reference/data/**``, ``reports/notes/*.md``, listed in ``pyproject.toml`` under
``[tool.setuptools.package-data]``) is located with :func:`importlib.resources.files`, never from a
module's ``__file__``: the same code then reads it from a source checkout, an installed wheel or any
other importer. ``tests/test_layout.py`` refuses a module that locates package data through
``__file__`` again.

An entry is a :class:`importlib.resources.abc.Traversable`: ``read_text``, ``read_bytes``,
``is_file``, ``iterdir`` and ``joinpath`` work on every importer; code that needs a real file name
(a library taking a path) wraps it in :func:`importlib.resources.as_file`. Paths given by a user
(``str`` or :class:`os.PathLike`) pass through :func:`location` as :class:`pathlib.Path`.
"""
from __future__ import annotations

import os
from importlib.resources import files
from importlib.resources.abc import Traversable
from pathlib import Path

#: the suite's top-level packages, the roots :func:`shipped_name` names data relative to
PACKAGES = ("contact", "sweep", "fem_reference", "rotor", "reports")


def shipped(package: str, *parts: str) -> Traversable:
    """The entry ``parts`` inside ``package``, e.g. ``shipped("rotor", "scenes", "paper-table4.toml")``."""
    return files(package).joinpath(*parts)


def location(where: str | os.PathLike | Traversable) -> Path | Traversable:
    """A user's path as a :class:`pathlib.Path`; a shipped entry unchanged."""
    return Path(where) if isinstance(where, (str, os.PathLike)) else where


def entries(folder: str | os.PathLike | Traversable, suffix: str) -> list[Traversable]:
    """Files directly in ``folder`` whose names end in ``suffix``, sorted by name (none if no folder)."""
    folder = location(folder)
    if not folder.is_dir():
        return []
    return sorted((e for e in folder.iterdir() if e.is_file() and e.name.endswith(suffix)), key=lambda e: e.name)


def stem(entry: Traversable) -> str:
    """The name of an entry without its last suffix (``paper-table4.toml`` -> ``paper-table4``)."""
    name = entry.name
    return name.rsplit(".", 1)[0] if "." in name[1:] else name


def shipped_name(where: str | os.PathLike | Traversable) -> str:
    """``package/relative/path`` for an entry inside one of :data:`PACKAGES`, else the path as given.

    The name is the same in a checkout and in an installed wheel, so provenance written into
    committed files (a calibrated law's ``dataset.path``) does not depend on where the suite lives.
    """
    try:
        target = Path(os.fspath(where)).resolve()
    except TypeError:                        # a Traversable of a non-file importer: no path to compare
        return str(where)
    for package in PACKAGES:
        root = files(package)
        if not isinstance(root, os.PathLike):
            continue
        try:
            return f"{package}/{target.relative_to(Path(os.fspath(root)).resolve()).as_posix()}"
        except ValueError:
            continue
    return str(where)
