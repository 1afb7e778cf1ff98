"""Fixtures shared by the study tests."""
from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def damped_jeffcott_scene(tmp_path_factory):
    """``damped_jeffcott_scene(damping_n_s_per_m)``: the path (str) of the bundled ``verify-jeffcott`` with a
    steel shaft and bearings of that damping, written to a temporary TOML."""
    def write(damping_n_s_per_m: float) -> str:
        text = (ROOT / "rotor/scenes/verify-jeffcott.toml").read_text(encoding="utf-8")
        text = text.replace('name = "verify-jeffcott"', 'name = "damped-jeffcott"').replace(
            "density_kg_m3 = 0\n", "density_kg_m3 = 7800\n").replace(
            "stiffness_n_per_m = 2.0e6\n", f"stiffness_n_per_m = 2.0e6\ndamping_n_s_per_m = {damping_n_s_per_m:g}\n")
        assert text.count(f"damping_n_s_per_m = {damping_n_s_per_m:g}") == 2 and "density_kg_m3 = 7800" in text
        path = tmp_path_factory.mktemp("scene") / "damped-jeffcott.toml"
        path.write_text(text, encoding="utf-8")
        return str(path)
    return write
