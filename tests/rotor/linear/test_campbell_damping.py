"""Campbell diagram with damping (``rotor campbell --damped``) and mode-shape plots (``rotor modes --plot``).

Closed forms: a disk on a massless shaft pinned at both ends with a viscous damper c at the disk is one
degree of freedom per direction, λ = −ζω_n ± iω_n√(1−ζ²), ζ = c/(2√(km)), log decrement
δ = 2πζ/√(1−ζ²) (e.g. Rao 2011, Mechanical Vibrations, Eqs. 2.72 and 2.85), the same at every speed
(no polar inertia: no gyroscopic term). A pinned–pinned uniform Euler–Bernoulli beam's first mode is
sin(πx/L) (e.g. Blevins 1979, Table 8-1).
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from reports.cli import rotor as cli
from rotor.model.elements import cowper_shear_coefficient

E, D, L, NU, M, C = 200e9, 0.02, 0.8, 0.3, 10.0, 150.0


def _scene(tmp_path):
    """tests/rotor/scenes/damped-jeffcott.toml (c = 150 N·s/m at the disk)."""
    return Path(__file__).resolve().parents[1] / "scenes" / "damped-jeffcott.toml"


def test_campbell_damping_ratio_and_log_decrement_are_the_closed_form(tmp_path, capsys):
    A, I = math.pi / 4 * D * D, math.pi / 64 * D ** 4
    k = 1 / (L ** 3 / (48 * E * I) + L / (4 * cowper_shear_coefficient(D, 0, NU) * E / (2 * (1 + NU)) * A))
    wn, zeta = math.sqrt(k / M), C / (2 * math.sqrt(k * M))
    assert cli.main(["campbell", str(_scene(tmp_path)), "--damped", "--points", "3", "--max-rpm", "3000",
                     "--modes", "2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["damped"] is True
    assert np.array(data["damping_ratio"]) == pytest.approx(np.full((3, 2), zeta), rel=1e-9)
    assert np.array(data["log_decrement"]) == pytest.approx(
        np.full((3, 2), 2 * math.pi * zeta / math.sqrt(1 - zeta ** 2)), rel=1e-9)
    assert np.array(data["frequency_hz"]) == pytest.approx(
        np.full((3, 2), wn * math.sqrt(1 - zeta ** 2) / (2 * math.pi)), rel=1e-9)
    # the table gains the column; undamped, ζ is 0
    assert cli.main(["campbell", str(_scene(tmp_path)), "--points", "2", "--modes", "2"]) == 0
    table = capsys.readouterr().out
    assert "(Hz, zeta)" in table and "(undamped: zeta = 0)" in table
    assert cli.main(["campbell", str(_scene(tmp_path)), "--points", "2", "--modes", "2", "--json"]) == 0
    assert np.array(json.loads(capsys.readouterr().out)["damping_ratio"]) == pytest.approx(0.0, abs=1e-12)


PINNED_BEAM = """
schema = "ringcontact.rotor-scene/1"
name = "pinned-beam"
title = "pinned-pinned uniform beam"
[[materials]]
name = "steel"
density_kg_m3 = 7800
youngs_modulus_gpa = 200
poisson_ratio = 0.3
[[stations]]
name = "A"
x_mm = 0
[[stations]]
name = "B"
x_mm = 1000
[[shafts]]
from = "A"
to = "B"
outer_diameter_mm = 30
material = "steel"
elements = 16
[[boundaries]]
station = "A"
fixed = ["y", "z"]
[[boundaries]]
station = "B"
fixed = ["y", "z"]
"""


def test_mode_shape_plot_is_the_pinned_beam_sine_and_has_its_own_file_names(tmp_path, capsys):
    from reports.rotor_plots import mode_shape_figure
    from rotor.linear.modes import modes
    from rotor.model.assembly import assemble
    from rotor.model.scene import loads_scene
    model = assemble(loads_scene(PINNED_BEAM), shear=False, rotary_inertia=False)
    res = modes(model, 0.0, n_modes=4)
    fig = mode_shape_figure(model, [("mode 1", res, 0), ("mode 2", res, 1), ("mode 3", res, 2)], "t")
    lines = [ln for ln in fig.axes[0].lines if ln.get_linestyle() == "-" and len(ln.get_xdata()) > 2]
    for line in lines[:2]:                 # forward and backward of the first pair: one shape, sin(πx/L)
        x_mm, amp = line.get_data()
        assert x_mm[0] == 0 and amp[0] == 0 and amp[-1] == pytest.approx(0, abs=1e-12)   # the pinned ends at 0
        assert len(x_mm) > 30                                      # drawn between the nodes, not only at them
        assert amp == pytest.approx(np.sin(math.pi * x_mm / 1000.0), abs=1e-3)
    x_mm, amp = lines[2].get_data()         # the second bending mode: sin(2πx/L), its sign change at midspan shows
    # the sign convention (reports/rotor_plots.py _first_largest): +1 at the first of the two equal extrema (x = L/4)
    assert amp == pytest.approx(np.sin(2 * math.pi * x_mm / 1000.0), abs=2e-3)
    assert amp.min() == pytest.approx(-1, abs=2e-3) and amp.max() == pytest.approx(1, abs=2e-3)
    # the tie is broken by node order, not by round-off: a perturbation of 1e-12 either way keeps the sign
    from reports.rotor_plots import _first_largest
    assert _first_largest(np.array([0.0, 1.0 - 1e-12, 0.2, -1.0, 0.0])) == 1
    assert _first_largest(np.abs(np.array([0.0, 1.0, 0.2, -1.0 - 1e-12, 0.0]))) == 1
    scene = tmp_path / "beam.toml"
    scene.write_text(PINNED_BEAM)
    prefix = tmp_path / "beam"
    assert cli.main(["modes", str(scene), "--plot", str(prefix)]) == 0
    capsys.readouterr()
    assert sorted(p.name for p in tmp_path.glob("beam*.*") if p.suffix != ".toml") == [
        "beam-modeshapes.png", "beam-modeshapes.svg"]
    assert b"<svg" in (tmp_path / "beam-modeshapes.svg").read_bytes()
