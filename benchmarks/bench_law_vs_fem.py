"""Speed against error: the analytic laws, the calibrated law and the 2D FEM on one frontier.

Run::

    .venv/bin/python benchmarks/bench_law_vs_fem.py                # writes reports/published/perf-law-vs-fem.*
    .venv/bin/python benchmarks/bench_law_vs_fem.py --repeats 3 --out /tmp/perf

Reference: the committed 2D dataset (``fem_reference/data/fem2d-reference.json``), scene
``clamped`` (the reference scene), its 12 points Δr = 0.001 … 0.05 mm; the reference value of
each point is the dataset's Richardson-extrapolated force. Error of a method = relative force
error ``|P/P_ref − 1|``, maximum and RMS over those points (Johnson: over the points where it
has a solution, the others counted separately).

Speed, measured side by side in one run (repeats interleaved round-robin, medians reported):

* laws: one scalar call (a Python float in, the public numpy function) and vectorized
  (10^5 penetrations in one call, time per point); the calibrated law also through the compiled
  loose-support kernel (``contact.loose_support.loose_support_force``), which is what the rotor uses;
* FEM (``fem_reference``): the same scene solved on each mesh level h = 4, 2, 1, 0.5 mm at the
  five Table 2 penetrations: time per evaluation = median contact solve on the ready model
  (mesh + factorisation once per level, reported separately), error against the reference value
  over those five points.
"""
from __future__ import annotations

import argparse
import csv
import io
import math
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from contact import calibrate as cal
from contact import laws
from contact.dataset import read_dataset
from contact.files import atomic_write_bytes, atomic_write_text
from contact.loose_support import loose_support_force

ROOT = Path(__file__).resolve().parents[1]
SCENE = "clamped"
FEM_LEVELS_M = (4e-3, 2e-3, 1e-3, 0.5e-3)
TABLE2_PEN_M = (1e-5, 2e-5, 3e-5, 4e-5, 5e-5)
N_VECTOR = 100_000


def reference(scene=SCENE):
    ds = read_dataset(cal.DATASET_2D)
    pts = sorted((p for p in ds.select(scene=scene) if p["penetration_m"] > 0), key=lambda p: p["penetration_m"])
    pen = np.array([p["penetration_m"] for p in pts])
    ref = np.array([p["force_extrapolated_n"] for p in pts])
    return ds, pen, ref


def law_methods(ds, scene=SCENE):
    """name -> (scalar callable, vector callable); every callable maps penetration (m) to force (N)."""
    geo = cal.scene_geometry(ds, scene)
    kw = dict(clearance_m=geo.clearance_m, width_m=geo.width_m, bearing_E_Pa=geo.bearing_E_Pa, bearing_nu=geo.bearing_nu,
              support_E_Pa=geo.support_E_Pa, support_nu=geo.support_nu)
    law = cal.load_calibrated(scene)
    params = law.loose_support_params()

    def via(fn, **extra):
        def f(x):
            r = fn(x, **kw, **extra)
            return np.where(r.in_domain, r.force_N, np.nan)
        return f

    def kernel(x):
        return -loose_support_force(params, geo.clearance_m + np.asarray(x), 0.0).Fy_N

    def calibrated(x):
        return law.force(x).force_N

    return {
        "conformal (paper, plane stress)": via(laws.conformal_force, modulus="plane_stress"),
        "Johnson": via(laws.johnson_force),
        "Pereira 2015": via(laws.pereira_force),
        f"calibrated {law.name} (numpy)": calibrated,
        f"calibrated {law.name} (compiled kernel)": kernel,
    }


def errors(pred, ref):
    rel = pred / ref - 1.0
    ok = np.isfinite(rel)
    if not ok.any():
        return np.nan, np.nan, 0
    return float(np.max(np.abs(rel[ok]))), float(np.sqrt(np.mean(rel[ok] ** 2))), int((~ok).sum())


def time_laws(methods, repeats: int):
    x_scalar = 2.0e-5
    x_vec = np.random.default_rng(0).uniform(1e-6, 5e-5, N_VECTOR)
    for f in methods.values():            # warm-up (numba compile, imports)
        f(x_scalar)
        f(x_vec[:10])
    res = {k: {"scalar": [], "vector": []} for k in methods}
    for _ in range(repeats):
        for name, f in methods.items():
            n = 200
            t0 = time.perf_counter()
            for _ in range(n):
                f(x_scalar)
            res[name]["scalar"].append((time.perf_counter() - t0) / n)
            t0 = time.perf_counter()
            f(x_vec)
            res[name]["vector"].append((time.perf_counter() - t0) / N_VECTOR)
    return {k: {m: statistics.median(v[m]) for m in v} for k, v in res.items()}


def time_fem(ref_by_pen: dict, repeats: int):
    from fem_reference.scenes import by_name
    from fem_reference.plane.sweep import SOLVER_TOL, spec_for
    from fem_reference.plane.solve import ContactModel

    scene = by_name(SCENE)
    rows = []
    for h in FEM_LEVELS_M:
        t0 = time.perf_counter()
        model = ContactModel.build(scene, spec_for(scene, h))
        build_s = time.perf_counter() - t0
        model.solve(TABLE2_PEN_M[0], tol=SOLVER_TOL)      # warm-up
        times, forces = [], []
        for pen in TABLE2_PEN_M:
            ts = []
            for _ in range(repeats):
                t0 = time.perf_counter()
                sol = model.solve(pen, tol=SOLVER_TOL)
                ts.append(time.perf_counter() - t0)
            times.append(statistics.median(ts))
            forces.append(sol.force_n)
        ref = np.array([ref_by_pen[min(ref_by_pen, key=lambda k: abs(k - p))] for p in TABLE2_PEN_M])
        mx, rms, _ = errors(np.array(forces), ref)
        rows.append({"method": f"FEM 2D, h = {h * 1e3:g} mm ({model.ndofs} DOFs)", "kind": "fem",
                     "scalar_s": statistics.median(times), "vector_s_per_point": statistics.median(times),
                     "build_s": build_s, "max_err": mx, "rms_err": rms, "n_outside": 0, "n_points": len(TABLE2_PEN_M),
                     "max_err_full_range": None, "n_outside_full_range": None, "n_points_full_range": None})
    return rows


FEM2D_TABLE = ROOT / "reports" / "published" / "fem2d-benchmark.csv"


def committed_fem_table(path=FEM2D_TABLE) -> list[dict]:
    """Rows of the 2D FEM benchmark's committed table (``benchmarks/bench_fem2d.py``), or [] if absent."""
    if not Path(path).exists():
        return []
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    out = []
    for r in rows:
        try:
            out.append({"order": int(r["order"]), "h_mm": float(r["h_contact_mm"]), "ndofs": int(r["ndofs"]),
                        "max_err": float(r["max_rel_error"]), "one_point_s": float(r["wall_one_point_s"]),
                        "solve_s": float(r["solve_s"])})
        except (KeyError, ValueError):
            continue
    return out


def write_outputs(rows, out: Path, meta: dict, fem_table: list[dict] | None = None):
    fem_table = fem_table or []
    out.mkdir(parents=True, exist_ok=True)
    cols = ("method", "kind", "scalar_s", "vector_s_per_point", "build_s", "max_err", "rms_err", "n_outside", "n_points",
            "max_err_full_range", "n_outside_full_range", "n_points_full_range")
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(cols)
    for r in rows:
        w.writerow([f"{r[c]:.6g}" if isinstance(r[c], float) else ("" if r[c] is None else r[c]) for c in cols])
    files = [atomic_write_text(out / "perf-law-vs-fem.csv", buf.getvalue())]

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8.6, 6.6))
    fem = [r for r in rows if r["kind"] == "fem"]
    ax.plot([r["scalar_s"] for r in fem], [100 * r["max_err"] for r in fem], "ks-", label="2D FEM (per solve; mesh levels)")
    for order, mk in ((1, "v"), (2, "D")):
        ft = sorted((r for r in fem_table if r["order"] == order), key=lambda r: r["one_point_s"])
        if ft:
            ax.plot([r["one_point_s"] for r in ft], [100 * r["max_err"] for r in ft], color="0.5", marker=mk, ms=4, lw=1,
                    label=f"2D FEM P{order}, committed benchmark table (one point from scratch)")
    for r in fem:
        ax.annotate(r["method"].split(",")[1].split("(")[0].strip(), (r["scalar_s"], 100 * r["max_err"]),
                    textcoords="offset points", xytext=(5, 4), fontsize=7)
    for k, r in enumerate(x for x in rows if x["kind"] == "law"):
        c = f"C{k}"
        ax.plot(r["scalar_s"], 100 * r["max_err"], "o", color=c, label=f"{r['method']}: scalar (o) / vectorized (^)")
        ax.plot(r["vector_s_per_point"], 100 * r["max_err"], "^", color=c)
        ax.plot([r["vector_s_per_point"], r["scalar_s"]], [100 * r["max_err"]] * 2, color=c, lw=0.8, alpha=0.6)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per evaluation (s)")
    ax.set_ylabel("max |force error| at Δr = 0.01 … 0.05 mm (%)")
    ax.set_title(f"Speed against error, scene '{SCENE}' (reference: 2D FEM, Richardson-extrapolated)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    fig.tight_layout()
    png, svg = io.BytesIO(), io.BytesIO()
    fig.savefig(png, format="png", dpi=110, metadata={"Software": None})
    with plt.rc_context({"svg.hashsalt": "ringcontact-perf-law-vs-fem"}):
        fig.savefig(svg, format="svg", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    files += [atomic_write_bytes(out / "perf-law-vs-fem.png", png.getvalue()),
              atomic_write_bytes(out / "perf-law-vs-fem.svg", svg.getvalue())]

    def t(s):
        if not math.isfinite(s):
            return "–"
        if s >= 1.0:
            return f"{s:.3g} s"
        if s >= 1e-3:
            return f"{s * 1e3:.3g} ms"
        return f"{s * 1e6:.3g} µs" if s >= 1e-6 else f"{s * 1e9:.3g} ns"

    lines = [
        "# Speed against error: analytic laws, calibrated law and 2D FEM",
        "",
        "Generated by `benchmarks/bench_law_vs_fem.py` (timings: not part of `ringcontact report`). "
        f"Machine: {meta['machine']}; load average at start {meta['load']}; {meta['repeats']} interleaved repeats, medians.",
        "",
        f"Reference: committed 2D dataset, scene `{SCENE}`, Richardson-extrapolated FEM force. Errors over the five "
        "Table 2 points Δr = 0.01 … 0.05 mm for every method; for the laws also the maximum over all "
        f"{rows[0]['n_points_full_range']} dataset points 0.001 … 0.05 mm. FEM time = one contact solve on a ready model "
        "(mesh + factorisation once per level: last column). FEM errors near 1e-3 % are at the level of the reference's "
        "own Richardson uncertainty (the reference is extrapolated from the same meshes).",
        "",
        "| method | scalar call | vectorized, per point | max error | RMS error | max error, full range | points without a value | one-off set-up |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(f"| {r['method']} | {t(r['scalar_s'])} | {t(r['vector_s_per_point']) if r['kind'] == 'law' else '–'} "
                     f"| {100 * r['max_err']:.3g} % | {100 * r['rms_err']:.3g} % "
                     f"| {'–' if r['max_err_full_range'] is None else format(100 * r['max_err_full_range'], '.3g') + ' %'} "
                     f"| {r['n_outside']} of {r['n_points']} "
                     f"| {'' if r['build_s'] is None else format(r['build_s'], '.2f') + ' s'} |")
    if fem_table:
        lines += ["", "The 2D FEM's own speed-vs-error from its committed benchmark table "
                  "(`reports/published/fem2d-benchmark.csv`, `benchmarks/bench_fem2d.py`, another run: clamped scene, "
                  "Δr = 0.002, 0.01, 0.05 mm, error against P2 h = 0.5 mm, time = one point from scratch):", "",
                  "| FEM setting | DOFs | one point from scratch | contact solve only | max error |", "|---|---|---|---|---|"]
        lines += [f"| P{r['order']}, h = {r['h_mm']:g} mm | {r['ndofs']} | {t(r['one_point_s'])} | {t(r['solve_s'])} "
                  f"| {100 * r['max_err']:.2g} % |" for r in fem_table]
    else:
        lines += ["", "The 2D FEM benchmark table (`reports/published/fem2d-benchmark.csv`) is not committed; only the "
                  "FEM levels timed in this run are shown."]
    law_cal = [r for r in rows if r["kind"] == "law" and "compiled" in r["method"]][0]
    uncal = [r for r in rows if r["kind"] == "law" and not r["method"].startswith("calibrated")]
    fine = fem[-1] if fem else {"scalar_s": math.nan, "max_err": math.nan}
    lines += [
        "",
        f"Reading: the calibrated law (compiled kernel) costs {t(law_cal['vector_s_per_point'])} per point vectorized, "
        f"{fine['scalar_s'] / law_cal['vector_s_per_point']:.2g}× less than one fine-mesh FEM solve, at a maximum "
        f"error of {100 * law_cal['max_err']:.2f} % (fine FEM: {100 * fine['max_err']:.2g} %). The uncalibrated laws "
        f"are as cheap but miss this scene by {100 * min(r['max_err'] for r in uncal):.0f}–"
        f"{100 * max(r['max_err'] for r in uncal):.0f} % (maximum error): their error is the boundary-condition "
        "model, not the numerics.",
    ]
    match = sorted((r for r in fem_table if r["max_err"] <= law_cal["max_err"]), key=lambda r: r["one_point_s"])
    if match:
        m = match[0]
        lines += ["", f"Cheapest FEM setting of the committed table at least as accurate as the calibrated law "
                  f"(≤ {100 * law_cal['max_err']:.2g} %): P{m['order']}, h = {m['h_mm']:g} mm, {t(m['one_point_s'])} per point "
                  f"from scratch ({t(m['solve_s'])} per contact solve on a ready model): the calibrated law is "
                  f"{m['solve_s'] / law_cal['vector_s_per_point']:.1e}× faster than that solve (vectorized) and "
                  f"{m['solve_s'] / law_cal['scalar_s']:.0f}× faster as a single scalar call (times from two runs)."]
    lines += [
        "",
        "![speed vs error](perf-law-vs-fem.png)",
        "",
        "Data: [perf-law-vs-fem.csv](perf-law-vs-fem.csv).",
        "",
    ]
    files.append(atomic_write_text(out / "perf-law-vs-fem.md", "\n".join(lines)))
    return files


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--out", type=Path, default=ROOT / "reports" / "published")
    ap.add_argument("--no-fem", action="store_true", help="skip the FEM timings (laws only)")
    args = ap.parse_args(argv)
    load = " / ".join(f"{v:.2f}" for v in os.getloadavg())
    ds, pen, ref = reference()
    methods = law_methods(ds)
    timings = time_laws(methods, args.repeats)
    rows = []
    t2 = np.array([int(np.argmin(np.abs(pen - p))) for p in TABLE2_PEN_M])
    for name, f in methods.items():
        mx, rms, nout = errors(f(pen[t2]), ref[t2])
        mx_all, _, nout_all = errors(f(pen), ref)
        rows.append({"method": name, "kind": "law", "scalar_s": timings[name]["scalar"],
                     "vector_s_per_point": timings[name]["vector"], "build_s": None, "max_err": mx, "rms_err": rms,
                     "n_outside": nout, "n_points": len(t2), "max_err_full_range": mx_all,
                     "n_outside_full_range": nout_all, "n_points_full_range": len(pen)})
    if not args.no_fem:
        rows += time_fem({float(p): float(r) for p, r in zip(pen, ref)}, max(1, args.repeats // 2))
    meta = {"machine": f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
            "load": load, "repeats": args.repeats}
    for f in write_outputs(rows, args.out, meta, committed_fem_table()):
        print(f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
