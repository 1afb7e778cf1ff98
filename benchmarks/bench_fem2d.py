"""Speed vs error of the 2D FEM reference over mesh levels and element orders (issue 3).

Clamped scene (Table 1 rings, plane strain), Δr = 0.002, 0.01, 0.05 mm. Error = largest relative
force error over the three points against P2 at h = 0.5 mm (whose own Richardson error is
~1e-5, see fem_reference/data). Wall time of one point from scratch = mesh + assembly +
factorisation (median of REPEATS) + one contact solve (median over points and repeats).
Settings: P1/P2 with the whole bore at size h, and "P2 graded" = the reference's per-point mesh
family (size h only on the possible contact arc, fem_reference.plane.sweep.spec_for).

Then every committed reference point (all scenes and penetrations of the default sweep) from
scratch: all its mesh levels built, factorised and solved, plus the Richardson estimate.

    .venv/bin/python benchmarks/bench_fem2d.py      # writes reports/published/fem2d-benchmark.{md,csv,png,svg}
"""
from __future__ import annotations

import csv
import io
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_bytes, atomic_write_text  # noqa: E402
from fem_reference.plane.mesh import MeshSpec  # noqa: E402
from fem_reference.plane.solve import ContactModel  # noqa: E402
from fem_reference.scenes import clamped  # noqa: E402

POINTS_M = (0.002e-3, 0.01e-3, 0.05e-3)
SETTINGS = [(1, h) for h in (8e-3, 4e-3, 2e-3, 1e-3, 0.5e-3)] + [(2, h) for h in (8e-3, 4e-3, 2e-3, 1e-3)]
REFERENCE = (2, 0.5e-3)
REPEATS = 3
OUT = ROOT / "reports" / "published"


def measure(order: int, h: float, repeats: int = REPEATS):
    builds, solves, forces = [], [], None
    for _ in range(repeats):
        t = time.perf_counter()
        m = ContactModel.build(clamped(), MeshSpec(h_contact_m=h, order=order))
        builds.append(time.perf_counter() - t)
        fs = []
        for d in POINTS_M:
            s = m.solve(d)
            solves.append(s.wall_s)
            fs.append(s.force_n)
        forces = np.array(fs)
    return {"order": order, "label": f"P{order}", "h_mm": h * 1e3, "ndofs": m.ndofs,
            "build_s": statistics.median(builds), "solve_s": statistics.median(solves), "forces": forces}


def measure_graded(h: float, repeats: int = REPEATS):
    """The reference's mesh family: one mesh per point, graded toward that point's possible arc."""
    from fem_reference.plane.sweep import arc_zone_rad, spec_for

    scene = clamped()
    builds, solves, forces, ndofs = [], [], [], []
    for _ in range(repeats):
        forces, ndofs = [], []
        for d in POINTS_M:
            t = time.perf_counter()
            m = ContactModel.build(scene, spec_for(scene, h, 2, arc_zone_rad(scene.rings, d)))
            builds.append(time.perf_counter() - t)
            s = m.solve(d)
            solves.append(s.wall_s)
            forces.append(s.force_n)
            ndofs.append(m.ndofs)
    return {"order": 2, "label": "P2 graded", "h_mm": h * 1e3, "ndofs": int(np.median(ndofs)),
            "build_s": statistics.median(builds), "solve_s": statistics.median(solves), "forces": np.array(forces)}


def main() -> int:
    load0 = os.getloadavg()[0]
    ref = measure(*REFERENCE, repeats=1)
    rows = []
    for order, h in SETTINGS + [("graded", h) for h in (4e-3, 2e-3, 1e-3, 0.5e-3)]:
        r = measure_graded(h) if order == "graded" else measure(order, h)
        r["error"] = float(np.max(np.abs(r["forces"] / ref["forces"] - 1)))
        r["wall_s"] = r["build_s"] + r["solve_s"]
        rows.append(r)
        print(f"{r['label']} h={h * 1e3:g} mm: {r['ndofs']} DOFs, error {r['error']:.2e}, "
              f"build {r['build_s']:.2f} s + solve {r['solve_s']:.2f} s", flush=True)
    # every committed reference point from scratch: all its levels built + solved + Richardson
    from fem_reference.scenes import by_name
    from fem_reference.plane.sweep import DEFAULT_PENETRATIONS_MM, DEFAULT_SCENES, Levels, reference_point

    scratch = []
    t_all = time.perf_counter()
    for name in DEFAULT_SCENES:
        for dmm in DEFAULT_PENETRATIONS_MM:
            t = time.perf_counter()
            rec = reference_point(Levels(by_name(name)), dmm * 1e-3)
            scratch.append({"scene": name, "dr_mm": dmm, "wall_s": time.perf_counter() - t,
                            "error": rec["force_error_rel"], "force_n": rec["force_n"],
                            "levels_mm": "/".join(f"{h * 1e3:g}" for h in rec["h_levels_m"]), "ndofs": rec["ndofs"]})
            print(f"{name} {dmm:g} mm from scratch: {scratch[-1]['wall_s']:.2f} s, est. error {rec['force_error_rel']:.1e}",
                  flush=True)
    total_scratch = time.perf_counter() - t_all
    load1 = os.getloadavg()[0]

    def cheapest(target):
        ok = [r for r in rows if r["error"] <= target]
        return min(ok, key=lambda r: r["wall_s"]) if ok else None

    c1, c01 = cheapest(1e-2), cheapest(1e-3)
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(["setting", "h_contact_mm", "ndofs", "max_rel_error", "build_s", "solve_s", "wall_one_point_s"])
    for r in rows:
        w.writerow([r["label"], f"{r['h_mm']:g}", r["ndofs"], f"{r['error']:.3e}", f"{r['build_s']:.3f}",
                    f"{r['solve_s']:.3f}", f"{r['wall_s']:.3f}"])
    atomic_write_text(OUT / "fem2d-benchmark.csv", buf.getvalue())

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    for label, mk in (("P1", "o-"), ("P2", "s-"), ("P2 graded", "^-")):
        rr = [r for r in rows if r["label"] == label]
        axes[0].loglog([r["wall_s"] for r in rr], [r["error"] for r in rr], mk, label=label)
        axes[1].loglog([r["ndofs"] for r in rr], [r["error"] for r in rr], mk, label=label)
        for r in rr:
            axes[0].annotate(f"{r['h_mm']:g}", (r["wall_s"], r["error"]), fontsize=7, xytext=(3, 3),
                             textcoords="offset points")
    for ax, xl in zip(axes, ("wall time of one point from scratch (s)", "degrees of freedom (-)")):
        ax.axhline(1e-2, color="grey", ls=":")
        ax.axhline(1e-3, color="grey", ls="--")
        ax.set_xlabel(xl)
        ax.set_ylabel("max relative force error (-)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("2D FEM reference: error vs cost (clamped rings, labels = h in mm)")
    for ext in ("png", "svg"):
        b = io.BytesIO()
        fig.savefig(b, format=ext, dpi=120, bbox_inches="tight", metadata={"Date": None} if ext == "svg" else None)
        atomic_write_bytes(OUT / f"fem2d-benchmark.{ext}", b.getvalue())
    plt.close(fig)

    def name(c):
        return "none" if c is None else (f"{c['label']}, h = {c['h_mm']:g} mm ({c['ndofs']} DOFs, "
                                         f"{c['wall_s']:.2f} s, error {c['error']:.1e})")

    lines = ["# 2D FEM reference: speed vs error", "",
             f"Clamped rings (Table 1, plane strain), Δr = {', '.join(f'{d * 1e3:g}' for d in POINTS_M)} mm. "
             f"Error: largest relative force error over the three points against P2, h = 0.5 mm "
             f"({ref['ndofs']} DOFs; its own Richardson estimate is ~1e-5). Times: medians of {REPEATS} repeats, "
             f"one point from scratch = mesh + assembly + factorisation + one contact solve. "
             f"Machine: {os.cpu_count()} cores shared with other jobs, load average {load0:.1f} → {load1:.1f}. "
             "Generated by `benchmarks/bench_fem2d.py`.", "",
             f"* cheapest setting within **1 %**: {name(c1)}",
             f"* cheapest setting within **0.1 %**: {name(c01)}", "",
             "| setting | h (mm) | DOFs | max rel. error | build (s) | solve (s) | one point (s) |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['label']} | {r['h_mm']:g} | {r['ndofs']} | {r['error']:.2e} | {r['build_s']:.3f} | "
                     f"{r['solve_s']:.3f} | {r['wall_s']:.3f} |")
    walls = [x["wall_s"] for x in scratch]
    errs = [x["error"] for x in scratch]
    lines += ["", "## Every committed reference point from scratch", "",
              "Each point of the default sweep (`ringcontact fem-sweep`: scenes "
              f"{', '.join(DEFAULT_SCENES)}; {len(DEFAULT_PENETRATIONS_MM)} penetrations each) solved as by "
              "`ringcontact fem-point`: its own mesh family built (graded toward its possible contact arc), every "
              "level meshed, assembled, factorised and solved, and the Richardson estimate (P2). "
              f"Run one after the other in this process (load average {load0:.1f} at start).", "",
              f"* **{sum(e <= 1e-3 for e in errs)}/{len(errs)}** points with estimated force error ≤ 0.1 % "
              f"(largest {max(errs):.1e})",
              f"* wall time per point: median {statistics.median(walls):.2f} s, max **{max(walls):.2f} s** "
              f"({sum(w <= 3.0 for w in walls)}/{len(walls)} within 3 s); all {len(walls)} points {total_scratch:.0f} s",
              "", "| scene | Δr (mm) | force (kN) | est. error | levels (mm) | finest DOFs | wall (s) |",
              "|---|---|---|---|---|---|---|"]
    for x in scratch:
        lines.append(f"| {x['scene']} | {x['dr_mm']:g} | {x['force_n'] / 1e3:.4f} | {x['error']:.1e} | {x['levels_mm']} | "
                     f"{x['ndofs']} | {x['wall_s']:.2f} |")
    lines += ["", "P2 (geometry-snapped 6-node triangles) pays: at equal cost it is one to two orders of magnitude "
              "more accurate than P1, whose observed order is ≈ 2 only below h = 2 mm (the square-root pressure "
              "edge limits both). Grading the bore toward the possible contact arc (P2 graded) costs a third to a "
              "half of the DOFs of the whole-bore mesh at the same h. A committed reference point uses the graded P2 "
              "family on three levels from the coarsest of 4, 2, 1, 0.5 mm with ≥ 3 elements across its half-arc "
              "(a finer level added while the estimate exceeds 0.1 %); see `fem_reference/data/fem2d-reference.json` "
              "for each point's own estimate and wall time.",
              "", "![error vs cost](fem2d-benchmark.png)"]
    atomic_write_text(OUT / "fem2d-benchmark.md", "\n".join(lines) + "\n")
    print("wrote", OUT / "fem2d-benchmark.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
