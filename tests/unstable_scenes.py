"""Rotors made unstable on purpose for the tests that check they are called unstable (issue 40)."""
from __future__ import annotations

from rotor.model.scene import scene_path


def table4_cross_coupled(tmp_path, k_cross: float):
    """paper-table4 with its bearing1 cross-coupled by k_yz = -k_zy = ``k_cross`` (N/m), written to ``tmp_path``."""
    text = scene_path("paper-table4").read_text(encoding="utf-8").replace(
        "damping_n_s_per_m = 1.5e3\n", f"damping_n_s_per_m = 1.5e3\nstiffness_yz_n_per_m = {k_cross:g}\n"
        f"stiffness_zy_n_per_m = {-k_cross:g}\n", 1)
    path = tmp_path / "t4.toml"
    path.write_text(text, encoding="utf-8")
    return path
