"""Which version of the suite is running, and the commit it was built from.

A wheel carries ``contact/_build.json`` written at build time by the in-tree build backend
(``build_backend/ringcontact_build.py``): version, commit, whether the tree had uncommitted changes.
A source checkout (``pyproject.toml`` beside the packages) asks git instead. An installed copy never
asks git: the repository around a virtual environment is not the code that runs.
"""
from __future__ import annotations

import json
from importlib import metadata, resources
from pathlib import Path

SOURCE_ROOT = Path(__file__).resolve().parents[1]


def is_source_checkout() -> bool:
    """True when running from the repository (editable install or PYTHONPATH), not an installed wheel."""
    return (SOURCE_ROOT / "pyproject.toml").is_file() and (SOURCE_ROOT / "contact" / "__init__.py").is_file()


def build_stamp() -> dict | None:
    """The stamp written into the wheel at build time, or None (a source checkout has none)."""
    try:
        return json.loads(resources.files("contact").joinpath("_build.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def version() -> str:
    """The package version (installed metadata, else the ``pyproject.toml`` of the checkout)."""
    try:
        return metadata.version("ringcontact")
    except metadata.PackageNotFoundError:
        import tomllib
        return tomllib.loads((SOURCE_ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]
