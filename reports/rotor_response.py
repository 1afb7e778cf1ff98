"""``ringcontact rotor response``: the linear time response of a scene's stations, written as CSV.

The rotor with the loose support locked (:mod:`rotor.dynamics.linear_response`), at one speed, by
harmonic superposition (the steady state, default) or by Newmark integration from rest. Writes
``OUT/response.csv`` (``t_s`` then ``<station>.y_m``, ``<station>.z_m`` per station) and
``OUT/response-summary.json`` (the run, and per station the largest orbit radius over the last
revolution in µm next to the semi-major axes of the 1X and 2X orbits of
:func:`rotor.linear.unbalance.forced_response`), both written atomically.
"""
from __future__ import annotations

import io
import json
import math
from pathlib import Path

import numpy as np

from contact.files import atomic_write_text

RPM = 30 / math.pi


def run_response(scene_name: str, speed_rpm: float, revolutions: float, out: str | Path, *, method: str = "harmonic",
                 stations: list[str] | None = None, steps_per_rev: int = 256, record_per_rev: int = 64,
                 elements: int | None = None) -> dict:
    """Compute the response, write the CSV and the summary, return the summary (engineer units).

    Parameters
    ----------
    scene_name : scene file or bundled name, or a loaded :class:`rotor.model.scene.Scene`.
    speed_rpm : spin speed (rpm), > 0.
    revolutions : duration (revolutions of the spin), > 0.
    out : output directory.
    method : ``"harmonic"`` or ``"newmark"`` (:func:`rotor.dynamics.linear_response.linear_response`).
    stations : list of str
        The scene's station, disk, bearing or support names (default: its response stations).
    steps_per_rev, record_per_rev : Newmark steps and recorded samples per revolution.
    elements : elements per shaft segment (override).
    """
    from rotor.dynamics.build import system_from_model
    from rotor.dynamics.linear_response import linear_response
    from rotor.linear.unbalance import forced_response
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene

    scene = load_scene(scene_name) if isinstance(scene_name, (str, Path)) else scene_name
    model = assemble(scene, elements_per_segment=elements)
    names = list(stations) if stations else list(model.response_stations())
    cols = [model.dof_index(f"{s}.{d}") for s in names for d in ("y", "z")]
    omega = speed_rpm / RPM
    res = linear_response(system_from_model(model, scene, omega), revolutions, steps_per_rev=steps_per_rev,
                          record_per_rev=record_per_rev, method=method)
    out = Path(out)
    buf = io.StringIO()
    buf.write(",".join(["t_s"] + [f"{s}.{d}_m" for s in names for d in ("y", "z")]) + "\n")
    np.savetxt(buf, np.column_stack([res.t_s, res.q[:, cols]]), delimiter=",", fmt="%.10g")
    atomic_write_text(out / "response.csv", buf.getvalue())
    last = res.t_s >= res.t_s[-1] - 2 * math.pi / omega * (1 - 1e-9)
    per = {}
    closed = {k: forced_response(model, [omega], order=k) for k in (1, 2)}
    for s in names:
        y, z = res.q[last, model.dof_index(f"{s}.y")], res.q[last, model.dof_index(f"{s}.z")]
        per[s] = {"last_rev_max_radius_um": float(np.hypot(y, z).max() * 1e6),
                  "forced_response_semi_major_um_1X": float(closed[1].orbit(model, s)[0][0] * 1e6),
                  "forced_response_semi_major_um_2X": float(closed[2].orbit(model, s)[0][0] * 1e6)}
    from rotor.linear.stability import first_unstable, stability_field
    summary = {"scene": scene.name, "speed_rpm": speed_rpm, "revolutions": revolutions, "method": method,
               "loose_support": "locked" if scene.loose_support is not None else "none",
               "dt_s": res.dt_s, "samples": len(res.t_s), "stations": per,
               "stability": stability_field(first_unstable(model, [omega])),
               "files": ["response.csv", "response-summary.json"]}
    atomic_write_text(out / "response-summary.json", json.dumps(summary, indent=2) + "\n")
    return summary


def summary_table(summary: dict) -> str:
    """The summary as a few lines of text (µm)."""
    lines = [f"{summary['scene']}: linear response at {summary['speed_rpm']:g} rpm, {summary['revolutions']:g} rev, "
             f"{summary['method']} (loose support {summary['loose_support']})",
             f"{'station':>12} {'last-rev max radius (um)':>25} {'1X semi-major (um)':>19} {'2X semi-major (um)':>19}"]
    for s, r in summary["stations"].items():
        lines.append(f"{s:>12} {r['last_rev_max_radius_um']:>25.4g} {r['forced_response_semi_major_um_1X']:>19.4g} "
                     f"{r['forced_response_semi_major_um_2X']:>19.4g}")
    return "\n".join(lines)
