"""Cascade of any scene by its own station names: 1X–5X velocity amplitudes against speed.

The paper's cascade figures (:mod:`reports.studies.cascade`) read the Table 4 stations (disk1, disk2,
s). A ``study cascade`` on another scene gets this report instead: one CSV row per speed with the
1X–5X y and z velocity amplitudes (mm/s) of every recorded station, keyed by the scene's names
(``rotor.model.assembly.RotorModel.response_stations``), and one figure of the y amplitudes. A speed whose
transient did not reach a steady state within the cap (``converged`` 0 in the CSV: its amplitudes are those
of the last revolutions, not of a steady state) is drawn with a hollow red ring round each of its dots.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import load_points, pyplot, save, write_csv

ORDERS = (1, 2, 3, 4, 5)


def station_cascade(out: Path, figs: Path, tasks=None) -> list[Path]:
    """``cascade-stations.csv`` in ``figs`` and ``cascade-stations.{png,svg}`` from the sweep in ``out``.

    Returns the written paths (none if no point finished)."""
    points = load_points(out, tasks)
    if not points:
        return []
    channels = [str(c) for c in points[0].arrays["channels"]]
    rows = []
    amps = np.zeros((len(points), len(channels), len(ORDERS)))
    for i, p in enumerate(points):
        h = np.abs(p.arrays["harm_v"])[[o - 1 for o in ORDERS]] * 1e3  # m/s -> mm/s
        amps[i] = h.T
        rows.append([p.params["speed_rpm"], p.info.get("label", ""), int(bool(p.info.get("converged", True)))]
                    + [float(h[k, j]) for j in range(len(channels)) for k in range(len(ORDERS))])
    header = ["speed_rpm", "regime", "converged"] + [f"{c}_v{o}X_mm_s" for c in channels for o in ORDERS]
    figs = Path(figs)
    written = [write_csv(figs / "cascade-stations.csv", header, rows)]
    plt = pyplot()
    ys = [j for j, c in enumerate(channels) if c.endswith(".y")]
    fig, axes = plt.subplots(1, len(ys), figsize=(3.2 * len(ys), 3.0), squeeze=False, sharey=True)
    rpm = np.array([p.params["speed_rpm"] for p in points])
    unsettled = np.array([not p.info.get("converged", True) for p in points])
    for ax, j in zip(axes[0], ys):
        for k, o in enumerate(ORDERS):
            ax.semilogy(rpm, np.maximum(amps[:, j, k], 1e-9), "o-", ms=3, label=f"{o}X")
        if unsettled.any():
            ax.semilogy(np.repeat(rpm[unsettled], len(ORDERS)), np.maximum(amps[unsettled, j, :], 1e-9).ravel(), "o",
                        ms=8, mfc="none", mec="tab:red", mew=1.2,
                        label=f"not converged ({int(unsettled.sum())} of {len(rpm)})")
        ax.set_title(channels[j][:-2], fontsize=9)
        ax.set_xlabel("speed (rpm)")
    axes[0][0].set_ylabel("velocity amplitude, y (mm/s)")
    axes[0][-1].legend(fontsize=7)
    fig.suptitle("1X–5X velocity amplitudes by station")
    written += save(fig, figs / "cascade-stations")
    return written
