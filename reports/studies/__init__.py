"""Figures and tables of the rotor studies (Dai et al. 2025, Sections 5–6, and beyond).

Every function reads a finished sweep directory (:mod:`sweep.store`, written by
``ringcontact study …``), writes PNG + SVG (units on every axis) and a CSV of the plotted
numbers, and returns the files written. Nothing here computes dynamics.

Quantities: as in the paper, cascades show the amplitude of the **y velocity** (mm/s; the
misalignment's static offset would swamp a displacement spectrum); Figs. 18–19 show
**displacement** amplitudes (µm). "3# bearing" is the *support* of the 3# bearing (node s), as
in the paper ("the response at 3# bearing represents the motion of the support").

Modules by report family: :mod:`~reports.studies.cascade` (Figs. 12, 16, 17),
:mod:`~reports.studies.point` (Figs. 13–15), :mod:`~reports.studies.params` (Figs. 18–19),
:mod:`~reports.studies.testrig` (Figs. 27–28), :mod:`~reports.studies.regime_map` and
:mod:`~reports.studies.runup` (beyond the paper); each has its ``*_figures`` and ``*_note``.
:mod:`~reports.studies.publish` writes them all into ``reports/published``;
:mod:`~reports.studies.common` holds what they share. Every public name is importable from
``reports.studies``.
"""
from __future__ import annotations

from reports.studies.cascade import cascade_figures, cascade_note
from reports.studies.common import LOCATIONS, channel_column, harmonic_table, load_points, pyplot, save, write_csv
from reports.studies.params import amplitude_grid, params_figures, params_note
from reports.studies.point import point_figures, point_note
from reports.studies.publish import publish
from reports.studies.regime_map import REGIMES, map_figures, map_note
from reports.studies.runup import runup_figures, runup_note
from reports.studies.testrig import testrig_figures, testrig_note

__all__ = [
    "LOCATIONS", "REGIMES", "amplitude_grid", "cascade_figures", "cascade_note", "channel_column", "harmonic_table",
    "load_points", "map_figures", "map_note", "params_figures", "params_note", "point_figures", "point_note",
    "publish", "pyplot", "runup_figures", "runup_note", "save", "testrig_figures", "testrig_note", "write_csv",
]
