"""Fixtures shared by the sweep tests."""
from __future__ import annotations

import pytest


@pytest.fixture
def dirs(tmp_path):
    """``(store directory, calls directory)``: where a sweep keeps its points, and where test tasks record
    each call (``sweep_helpers.calls`` counts them)."""
    calls = tmp_path / "calls"
    calls.mkdir()
    return tmp_path / "store", calls
