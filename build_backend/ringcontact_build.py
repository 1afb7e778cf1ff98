"""In-tree build backend: setuptools, plus a stamp of the version and commit in every wheel.

``pyproject.toml`` names this module as the build backend (``backend-path = ["build_backend"]``).
Before setuptools builds a wheel, ``contact/_build.json`` is written with the version, the git
commit and whether the tree had uncommitted changes; it is removed again afterwards, so a source
checkout never carries a stale stamp. ``ringcontact --version`` and the provenance of every result
written by an installed copy read it (:mod:`contact.stamp`).
"""
from __future__ import annotations

import datetime
import json
import subprocess
import tomllib
from pathlib import Path

from setuptools import build_meta as _setuptools
from setuptools.build_meta import *  # noqa: F401,F403 - every other hook unchanged

ROOT = Path(__file__).resolve().parents[1]
STAMP = ROOT / "contact" / "_build.json"


def _git(*args: str) -> str:
    try:
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, timeout=20).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""


def _write_stamp() -> None:
    version = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]
    commit = _git("rev-parse", "HEAD") or "unknown"
    dirty = bool(_git("status", "--porcelain", "--untracked-files=no")) if commit != "unknown" else None
    stamp = {"version": version, "git_commit": commit, "git_dirty": dirty,
             "built_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")}
    STAMP.write_text(json.dumps(stamp, indent=1) + "\n", encoding="utf-8")


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    """setuptools' ``build_wheel`` with ``contact/_build.json`` written first and removed after."""
    _write_stamp()
    try:
        return _setuptools.build_wheel(wheel_directory, config_settings, metadata_directory)
    finally:
        STAMP.unlink(missing_ok=True)
