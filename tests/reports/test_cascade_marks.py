"""The cascade figure marks the speeds whose orbit is not a stable periodic one (``study cascade --method shooting``)."""
from __future__ import annotations

from reports.studies.cascade import STABILITY_MARKS, mark_stability
from reports.studies.common import pyplot


def _points(classes):
    """``(speed_rpm, classification)`` pairs as cascade_figures builds them from shooting points (none for
    transient points, which carry no classification)."""
    return [(1000.0 * i, c) for i, c in enumerate(classes) if c]


def test_unstable_and_quasi_periodic_speeds_are_marked_at_their_speed():
    plt = pyplot()
    fig, ax = plt.subplots()
    ax.set_xlim(0, 100)
    mark_stability(ax, _points(["periodic", "quasi_periodic", "period_doubling", "quasi_periodic", "non_periodic"]))
    lines = {ln.get_label(): list(ln.get_ydata()) for ln in ax.get_lines()}
    assert lines[STABILITY_MARKS["quasi_periodic"][2]] == [1000.0, 3000.0]
    assert lines[STABILITY_MARKS["period_doubling"][2]] == [2000.0]
    assert lines[STABILITY_MARKS["non_periodic"][2]] == [4000.0]
    assert STABILITY_MARKS["unstable_fold"][2] not in lines and len(lines) == 3   # nothing for stable speeds
    assert [t.get_text() for t in ax.get_legend().get_texts()] == list(lines)
    plt.close(fig)


def test_transient_points_draw_nothing():
    plt = pyplot()
    fig, ax = plt.subplots()
    mark_stability(ax, _points([None, None]))
    assert ax.get_lines() == [] and ax.get_legend() is None
    plt.close(fig)
