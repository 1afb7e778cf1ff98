"""The study figures: drawn again from the committed CSV tables, readable on their own, one harmonic naming.

* ``study redraw`` draws the committed study-sensitivity, study-params-* and study-cascade* figures
  byte for byte from the committed ``study-*.csv`` (so they are up to date with the numbers and the
  plotting code), reading the CSV and Markdown files only;
* the CSV adapters give back the numbers ``study publish`` plotted (round trip through the CSV);
* the sensitivity figure names its rows in words with units and keeps its axis to ±2 decades, a ratio
  beyond drawn on the edge; the params figures never draw a zero at the floor as a point of a curve;
  the cascade maps name the orders 1X–5X and share one amplitude scale per figure;
* no "1f"-style harmonic names are left in the study code and reports (quotes of the paper aside).
"""
from __future__ import annotations

import hashlib
import re
from pathlib import Path

import numpy as np
import pytest

from reports import sensitivity as rep
from reports import sensitivity_figure as sf
from reports.studies import cascade, params
from reports.studies.common import write_csv
from reports.studies.redraw import redraw
from rotor.studies import sensitivity as sens

ROOT = Path(__file__).resolve().parents[2]
PUBLISHED = ROOT / "reports" / "published"
FIGURES = [f"{stem}.{ext}" for stem in ("study-sensitivity", "study-params-clearance", "study-params-misalignment",
                                        "study-params-clearance-ratio", "study-params-misalignment-ratio",
                                        "study-cascade", "study-cascade-tilt", "study-cascade-notilt",
                                        "study-cascade-notilt-tilt") for ext in ("png", "svg")]


def _digest(paths) -> dict:
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in paths}


def test_committed_study_figures_are_redrawn_byte_for_byte_from_the_committed_csv(tmp_path):
    tables = sorted(PUBLISHED.glob("study-*.csv")) + sorted(PUBLISHED.glob("study-*.md"))
    before = _digest(tables)
    files = redraw(PUBLISHED, tmp_path)
    assert sorted(f.name for f in files) == sorted(FIGURES)
    stale = [f.name for f in files if f.read_bytes() != (PUBLISHED / f.name).read_bytes()]
    assert stale == [], f"{stale} differ from a redraw: run `ringcontact study redraw` and look at them"
    assert _digest(tables) == before


def _capture(monkeypatch, module) -> list:
    """Keep the figures ``module`` saves (instead of writing and closing them)."""
    figs = []
    monkeypatch.setattr(module, "save", lambda fig, prefix: figs.append(fig) or [Path(f"{prefix}.png")])
    return figs


def _table(seed: int = 1) -> sens.AmplitudeTable:
    rng = np.random.default_rng(seed)
    C, S, L = len(sens.CASE_NAMES), 3, len(sens.LOCATIONS)
    q, v = rng.uniform(1e-7, 1e-5, (C, S, 5, L)), rng.uniform(1e-4, 1e-2, (C, S, 5, L))
    q[sens.CASE_NAMES.index("clear0.03"), 0, 2, 1] = 1e5 * q[sens.CASE_NAMES.index("clear0.08"), 0, 2, 1]
    return sens.AmplitudeTable(np.array([9000.0, 10500.0, 12000.0]), sens.CASE_NAMES, sens.LOCATIONS, q, v,
                               rng.uniform(size=(C, S)) > 0.3, rng.uniform(size=(C, S)))


def test_the_points_csv_gives_back_the_ratios_publish_plots(tmp_path):
    variants = [sens.Variant("base", {}), sens.Variant("ks_theta-x0.01", {"ks_theta": 0.01})]
    tabs = {"base": _table(1), "ks_theta-x0.01": _table(2)}
    path = write_csv(tmp_path / "points.csv", *rep.point_rows(tabs, variants))
    back, named = sf.tables_from_points_csv(path)
    assert [v.name for v in named] == ["base", "ks_theta-x0.01"] and named[1].factors == {"ks_theta": 0.01}
    for name, t in tabs.items():
        want, got = sf.per_speed_ratios(t), sf.per_speed_ratios(back[name])
        for finding in ("clearance", "misalignment", "tilt"):
            np.testing.assert_allclose(got[finding][0], want[finding][0], rtol=2e-5)    # 6 digits in the CSV
            np.testing.assert_array_equal(got[finding][1], want[finding][1])
        np.testing.assert_allclose(back[name].contact_fraction, t.contact_fraction, rtol=1e-5)


def test_sensitivity_rows_are_named_in_words_and_the_axis_keeps_to_two_decades(tmp_path, monkeypatch):
    figs = _capture(monkeypatch, sf)
    variants = [sens.Variant("base", {}), sens.Variant("ks-x10+muN-x0.2", {"ks": 10.0, "preload": 0.2})]
    sf.figure({"base": _table(1), "ks-x10+muN-x0.2": _table(2)}, variants, tmp_path / "s")
    (fig,) = figs
    axes = fig.axes[:3]
    labels = [t.get_text() for t in axes[0].get_yticklabels()]
    assert labels[0] == "Table 4 rotor as published (reference)"
    # paper-table4.toml: k_s = 1.5e7 N/m, μ = 0.3, preload 5 000 N
    assert labels[1] == "support-to-ground stiffness & damping k_s ×10 → 150 MN/m\nend-face friction limit μN ×0.2 → 300 N"
    assert not any(re.search(r"[a-z_]+-x\d", lab) for lab in labels)          # no row codes
    for ax in axes:
        assert "[ratio, –]" in ax.get_xlabel() and "disk 2" in ax.get_xlabel()
        lo, hi = ax.get_xlim()
        assert (lo, hi) == (-sf.DECADES - 0.25, sf.DECADES + 0.25)
        xs = np.concatenate([c.get_offsets()[:, 0] for c in ax.collections if len(c.get_offsets())])
        assert np.all(np.abs(xs) <= sf.DECADES + 0.12)
    ticks = [t.get_text() for t in axes[0].get_xticklabels()]
    assert ticks == ["≤ 1/100", "1/10", "1", "10", "≥ 100"]
    # the 1e5 ratio of both tables (clearance, 9 000 rpm) is a triangle on the right edge of each row
    edge = [c for c in axes[0].collections if len(c.get_offsets()) and c.get_offsets()[0, 0] == sf.DECADES + 0.12]
    assert len(edge) == 2
    assert sorted(round(float(c.get_offsets()[0, 1])) for c in edge) == [0, 2]   # rows at 0.5 and 1.725, 9 000 rpm 0.15 above


def test_params_zeros_are_marked_below_the_floor_not_drawn_as_dips(monkeypatch):
    rpm = np.array([0.0, 3000.0, 6000.0, 9000.0])
    A = np.full((4, 3, 3), 2.0)
    A[0] = 0.0                          # at rest: every harmonic is zero
    A[2, 1, 2] = 0.0                    # a 3X at disk 2 that is exactly zero
    fig = params.amplitude_grid({5e-5: (rpm, A)}, lambda v: f"δ0 = {v * 1e3:g} mm", "t")
    ax = fig.axes[2 * 3 + 1]            # 3X, disk 2
    curve = next(ln for ln in ax.get_lines() if ln.get_marker() == "o")
    y = np.asarray(curve.get_ydata(), float)
    assert np.isnan(y[0]) and np.isnan(y[2]) and np.all(y[[1, 3]] == 2.0)
    below = next(ln for ln in ax.get_lines() if ln.get_marker() == "v")
    assert list(below.get_xdata()) == [0.0, 6000.0]
    assert ax.get_title() == "3X, disk 2" and "3X" in ax.get_ylabel()
    assert any("below floor" in t.get_text() for t in fig.axes[0].get_legend().get_texts())


def test_sensitivity_figure_has_a_legend_on_every_panel(tmp_path, monkeypatch):
    """Each of the three panels names its threshold and the paper's side (issue 39: legends on every panel); the
    third carries the speeds and marks shared by all three."""
    figs = _capture(monkeypatch, sf)
    sf.figure({"base": _table(1)}, [sens.Variant("base", {})], tmp_path / "s")
    (fig,) = figs
    for ax, (_, threshold, _) in zip(fig.axes[:3], sf.PANELS.values()):
        texts = [t.get_text() for t in ax.get_legend().get_texts()]
        assert texts[:2] == [f"threshold {threshold:g}", "paper's side"], texts
    assert any(t.get_text().endswith(" rpm") for t in fig.axes[2].get_legend().get_texts())


def test_params_figures_have_a_legend_on_every_panel():
    """Figs. 18-19 and their ratios to the scene's value (issue 39: legends on every panel): each of the nine panels
    names its curves, one entry per clearance (or per ratio to the reference)."""
    rpm = np.array([3000.0, 6000.0, 9000.0])
    groups = {v: (rpm, np.full((3, 3, 3), 1.0 + k), np.ones(3, bool)) for k, v in enumerate((3e-5, 5e-5, 8e-5))}
    lab = lambda v: f"δ0 = {v * 1e3:g} mm"                                      # noqa: E731
    for fig, names in ((params.amplitude_grid(groups, lab, "t"), [lab(v) for v in groups]),
                       (params.ratio_grid(groups, 5e-5, lab, "t"), [f"{lab(v)} / {lab(5e-5)}" for v in (3e-5, 8e-5)])):
        assert len(fig.axes) == 9
        for ax in fig.axes:
            texts = [t.get_text() for t in ax.get_legend().get_texts()]
            assert texts[:len(names)] == names, (ax.get_title(), texts)


def test_cascade_maps_name_the_orders_and_share_one_amplitude_scale(tmp_path, monkeypatch):
    """The cascades are maps of speed against order: ticks 0, 1X–5X on the order axis; every panel of a figure
    (and the tilt-ignored cascade drawn beside it) on one logarithmic scale, four decades, with one colour bar
    in the unit of the amplitude (issue 25: amplitudes readable and comparable across panels)."""
    figs = _capture(monkeypatch, cascade)
    draw = cascade.spectrum_redraw(PUBLISHED / "study-cascade-spectrum.csv", tmp_path, "c", "t",
                                   PUBLISHED / "study-cascade-notilt-spectrum.csv")
    draw()
    assert len(figs) == 2
    for fig, unit in zip(figs, ("mm/s", "mrad")):
        data_axes = [ax for ax in fig.axes if ax.get_xlabel().startswith("frequency / rotation frequency")]
        assert len(data_axes) in (2, 3)
        for ax in data_axes:
            assert [t.get_text() for t in ax.get_xticklabels()] == ["0", "1X", "2X", "3X", "4X", "5X"]
        norms = {(m.norm.vmin, m.norm.vmax) for ax in data_axes for m in ax.collections}
        assert len(norms) == 1
        (lo, hi), = norms
        assert hi / lo == pytest.approx(1e4)
        bars = [ax for ax in fig.axes if unit in ax.get_ylabel()]
        assert len(bars) == 1


HARMONIC_F = re.compile(r"(?<![A-Za-z0-9_.:%{\\])[1-5]f(?=[\s_–\-,/)(\].+*|'\"`;:]|$)|\{h\}f[_\" ]|_[1-5]f(_|\b)")
PAPER_QUOTES = re.compile(r"harmonic frequenc(y|ies) [1-5]f(, [1-5]f)*")   # quoted from Dai et al. (2025)


@pytest.mark.parametrize("folder,pattern", [("reports", "**/*.py"), ("rotor/studies", "*.py"), ("tests/rotor/studies", "*.py"),
                                            ("rotor/periodic", "*.py"), ("tests/rotor/periodic", "*.py"),
                                            ("reports/published", "study-*.md"), ("reports/published", "study-*.csv"),
                                            ("reports/notes", "*.md")])
def test_one_naming_of_harmonic_orders(folder, pattern):
    found = []
    for path in sorted((ROOT / folder).glob(pattern)):
        lines = path.read_text(encoding="utf-8").splitlines()
        for i, line in enumerate(lines[:1] if path.suffix == ".csv" else lines):
            if HARMONIC_F.search(PAPER_QUOTES.sub("", line)):
                found.append(f"{path.relative_to(ROOT)}:{i + 1}: {line.strip()[:80]}")
    assert found == [], "use 1X…5X for harmonic orders"


def test_point_figure_has_a_legend_on_every_panel(monkeypatch):
    """Figs. 13-15 at one speed (reports.studies.point): every panel has a legend (issue 39), the deflection panel
    one entry per instant of the revolution. A synthetic record of paper-table4's channels, one revolution of 64
    samples."""
    from types import SimpleNamespace

    from reports.studies import point
    from rotor.studies.steady_state import _scene_model

    _, model = _scene_model("paper-table4", None)
    spr = 64
    phi = 2 * np.pi * np.arange(spr) / spr
    channels = np.array([f"{n}.{d}" for n in ("disk1", "disk2", "s") for d in ("y", "z")])
    q = np.column_stack([1e-6 * (np.cos if d == "y" else np.sin)(phi) for _ in range(3) for d in ("y", "z")])
    dofs = np.array(model.dof_names)
    arrays = {"dof_names": dofs, "q_all": 1e-6 * np.outer(np.cos(phi), np.ones(len(dofs))), "q": q,
              "channels": channels, "t": phi / 1000.0, "spec_orders": np.linspace(0, 6, 48),
              "spec_v": np.full((48, len(channels)), 1e-3), "r1": 49e-6 + 1e-6 * np.cos(phi),
              "r2": 49e-6 + 1e-6 * np.sin(phi)}
    p = SimpleNamespace(params={"speed_rpm": 10500.0, "scene": "paper-table4"}, arrays=arrays,
                        info={"samples_per_rev": spr, "clearance_m": 50e-6, "label": "impact", "contact_fraction": 0.5,
                              "converged": True, "period_revs": 1})
    monkeypatch.setattr(point, "load_points", lambda out, tasks=None: [p])
    figs = _capture(monkeypatch, point)
    point.point_figures("unused", Path("unused"))
    (fig,) = figs
    assert len(fig.axes) == 11
    for ax in fig.axes:
        assert ax.get_legend() is not None, ax.get_title()
    texts = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert texts == [f"{k}/8 rev" for k in range(8)]


def test_runup_cascade_has_a_legend_on_every_panel(monkeypatch):
    """The run-up's time-frequency cascade (reports.studies.runup): each of its three panels names the dotted 1X-5X
    lines (issue 39: legends on every panel), and both panels of the time histories have their legends. A synthetic
    ramp 600 -> 6 000 rpm in 1 s, its 1X at every channel."""
    from reports.studies import runup
    import rotor.studies.runup as ru

    t = np.linspace(0.0, 1.0, 20001)
    rpm = 600.0 + 5400.0 * t
    phase = 2 * np.pi * np.cumsum(rpm / 60.0) * (t[1] - t[0])
    channels = np.array(["disk1.y", "disk2.y", "s.y"])
    wave = np.column_stack([np.cos(phase)] * 3)
    r = {"t": t, "rpm": rpm, "channels": channels, "v": 1e-3 * wave, "q": 1e-6 * wave, "r1": 40e-6 + 0 * t,
         "r2": 40e-6 + 0 * t, "clearance_m": 50e-6, "info": {}}
    monkeypatch.setattr(ru, "load_runup", lambda out: r)
    figs = _capture(monkeypatch, runup)
    runup.runup_figures("unused", Path("unused"))
    cascade, time = figs
    panels = [ax for ax in cascade.axes if ax.get_xlabel() == "frequency (Hz)"]
    assert len(panels) == 3
    for ax in panels:
        assert [t.get_text() for t in ax.get_legend().get_texts()] == ["1X–5X (k × rotation frequency)"]
    assert all(ax.get_legend() is not None for ax in time.axes)
