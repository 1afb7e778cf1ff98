"""Where the support sticks, slips and impacts over (speed, clearance), beyond the paper: map and note."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import integrator_text, load_points, pyplot, save, write_csv


#: the regimes of rotor.studies.steady_state (SteadyResult.regime), and "beyond law": a point whose load drives the
#: ring past the conformal law's neat-fit limit has no record (rotor.studies.steady_state.beyond_law_record)
REGIMES = ("stick", "slip", "impact", "contact", "beyond law")


def map_figures(out, figs, *, tasks=None, prefix: str = "study-map") -> list[Path]:
    """Where the support sticks, slips and impacts over (speed, clearance); contact fraction as number."""
    plt = pyplot()
    from matplotlib.colors import ListedColormap

    figs = Path(figs)
    pts = load_points(out, tasks)
    rpms = sorted({p.params["speed_rpm"] for p in pts})
    cls = sorted({p.params["clearance_m"] for p in pts})
    grid = np.full((len(cls), len(rpms)), np.nan)
    frac = np.full_like(grid, np.nan)
    conv = np.ones_like(grid, dtype=bool)
    for p in pts:
        i, j = cls.index(p.params["clearance_m"]), rpms.index(p.params["speed_rpm"])
        grid[i, j] = REGIMES.index(p.info["label"])
        frac[i, j] = p.info.get("contact_fraction", np.nan)
        conv[i, j] = p.info["converged"]
    fig, ax = plt.subplots(figsize=(11, 4.2), constrained_layout=True)
    cmap = ListedColormap(["#4c72b0", "#dd8452", "#c44e52", "#8172b2", "#7f7f7f"])
    ax.imshow(grid, origin="lower", aspect="auto", cmap=cmap, vmin=-0.5, vmax=len(REGIMES) - 0.5,
              extent=(-0.5, len(rpms) - 0.5, -0.5, len(cls) - 0.5))
    for i in range(len(cls)):
        for j in range(len(rpms)):
            if np.isfinite(frac[i, j]):
                ax.text(j, i, f"{100 * frac[i, j]:.0f}%" + ("" if conv[i, j] else "*"), ha="center", va="center",
                        fontsize=7, color="w")
            elif grid[i, j] == REGIMES.index("beyond law"):
                ax.text(j, i, "×", ha="center", va="center", fontsize=9, color="w")
    ax.set_xticks(range(len(rpms)), [f"{r:.0f}" for r in rpms], rotation=45, fontsize=8)
    ax.set_yticks(range(len(cls)), [f"{c * 1e3:g}" for c in cls])
    ax.set_xlabel("rotor speed (rpm)")
    ax.set_ylabel("radial clearance δ0 (mm)")
    from matplotlib.patches import Patch
    ax.legend(handles=[Patch(color=cmap(k), label=r) for k, r in enumerate(REGIMES)], loc="upper left",
              bbox_to_anchor=(1.0, 1.0), fontsize=8)
    ax.set_title("Loose-support regime (numbers: % of time in radial contact; * = no periodic steady state; "
                 "×: beyond the contact law's neat-fit limit, no record)",
                 fontsize=9)
    files = save(fig, figs / prefix)
    rows = [[p.params["speed_rpm"], p.params["clearance_m"] * 1e3, p.info["label"], p.info.get("contact_fraction"),
             p.info.get("stick_fraction"), p.info.get("max_r_over_clearance"), int(p.info["converged"]),
             p.info["period_revs"]] for p in pts]      # a point beyond the law: empty cells, no record
    files.append(write_csv(figs / f"{prefix}.csv", ["speed_rpm", "clearance_mm", "regime", "contact_fraction",
                                                    "stick_fraction", "max_r_over_clearance", "converged",
                                                    "period_revs"], rows))
    return files


def map_note(points) -> str:
    lines = ["# Where the support sticks, slips and impacts (beyond the paper)", "",
             "`ringcontact study map`: steady state over a (speed, clearance) grid; regime from the recorded "
             "revolutions: *stick* (both end faces stuck, no radial contact), *slip* (faces slide, no contact), "
             "*impact* (radial contact part of the time), *contact* (contact all the time). "
             "`study-map.csv` has the fractions.", ""]
    from collections import Counter
    c = Counter(p.info["label"] for p in points)
    lines.append("Counts: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())) + f" of {len(points)} points; "
                 f"{sum(not p.info['converged'] for p in points)} without a periodic steady state.")
    caps = sorted({int((p.info.get("options") or {}).get("max_revs", 0)) for p in points} - {0})
    lines += ["", model_text(points) + (f" Transient cap {', '.join(map(str, caps))} revolutions a point (a point "
                                        "not periodic by then is counted as such)." if caps else ""),
              integrator_text([p.info for p in points]), ""]
    return "\n".join(lines)


def model_text(points) -> str:
    """The scene and its reading of Eq. 34 the points were computed with (from their params; the scene's
    reading as the scene file has it now, rotor.studies.readings.scene_reading)."""
    from rotor.model.scene import load_scene
    from rotor.studies.readings import scene_reading

    names = sorted({str(p.params.get("scene", "?")) for p in points})
    try:
        readings = sorted({scene_reading(load_scene(n)) or "none of rotor.studies.readings" for n in names})
    except Exception:      # a scene that no longer loads: name it only
        readings = ["unknown (the scene no longer loads)"]
    digest = sorted({str(p.params["scene_sha256"]) for p in points if "scene_sha256" in p.params})
    return (f"Model: scene {', '.join(names)}, misalignment excitation read as {', '.join(readings)} "
            f"(section5-readings.md)" + (f"; scene digest {', '.join(digest)}" if digest else "") + ".")
