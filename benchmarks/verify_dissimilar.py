"""The FEM references against closed forms on dissimilar materials and other sizes: the report.

Run::

    .venv/bin/python benchmarks/verify_dissimilar.py            # writes reports/published/fem-verification-dissimilar.md
    .venv/bin/python benchmarks/verify_dissimilar.py --out /tmp/v --quick   # cheap 3D levels only

Every number is computed here by :mod:`fem_reference.verify_dissimilar` (the same studies the tests
in tests/fem_reference/test_dissimilar_verification.py assert on); nothing is typed by hand.
Columns: the closed form (or, for the 3D/2D and scaling checks, the value it must equal), the FE
value, the FE point's stated error estimate, the difference, and whether the difference is within
the stated error ("yes"), or within a stated model tolerance instead ("tol", see the section).
"""
from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from contact.files import atomic_write_text  # noqa: E402
from contact.units import MM  # noqa: E402
from fem_reference import verify_dissimilar as vd  # noqa: E402

OUT = ROOT / "reports" / "published"
PERSSON_TOL = 0.01


def _fmt(v: float) -> str:
    return f"{v:.6g}"


def table(rows: list[dict], unit: str, tol: float | None = None, law_key: str = "closed_form",
          limit: bool = False) -> list[str]:
    """Markdown rows: check, closed form, FEM, stated error, difference (abs, rel), verdict.

    ``limit``: the closed form is a limit the FE tends to, not an exact value (verdict "limit")."""
    out = [f"| check | closed form [{unit}] | FEM [{unit}] | stated error [{unit}] | difference [{unit}] | "
           "difference [-] | within |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        ref = r[law_key]
        diff = r["fem"] - ref
        if limit:
            verdict = "limit"
        elif abs(diff) <= r["fem_error_abs"]:
            verdict = "yes"
        elif tol is not None and abs(diff / ref) <= tol + r["fem_error_rel"]:
            verdict = "tol"
        else:
            verdict = "**no**"
        extra = "".join(f", {k} {_fmt(r[k])}" for k in ("penetration_m", "half_angle_deg") if k in r)
        out.append(f"| {r['check']}{extra} | {_fmt(ref)} | {_fmt(r['fem'])} | {_fmt(r['fem_error_abs'])} | "
                   f"{_fmt(diff)} | {diff / ref:+.2e} | {verdict} |")
    return out


def sections(quick: bool) -> tuple[list[str], dict]:
    """Run every study; the report's body and the wall time of each study [s]."""
    lv3 = vd.cheap_levels_3d() if quick else ("Q0", "Q1", "Q2")
    names3 = ", ".join(lv if isinstance(lv, str) else lv.name for lv in lv3)
    timings: dict[str, float] = {}

    def timed(name, fn, *a, **k):
        t0 = time.perf_counter()
        r = fn(*a, **k)
        timings[name] = time.perf_counter() - t0
        return r

    shrink = timed("1 shrink fit", vd.shrink_fit_study)
    wink = timed("2 Winkler, 24 deg", vd.winkler_study, (0.1, 0.05, 0.025))
    wink60 = timed("2 Winkler, 60 deg", vd.winkler_study, (0.2, 0.1, 0.05, 0.025), penetration_m=0.03 * MM)
    nobeta = timed("3 Persson, beta = 0", vd.persson_study, vd.beta_free_support())
    alu = timed("3 Persson, steel in aluminium", vd.persson_study, vd.ALUMINIUM)
    sc2 = timed("4 scaling 2D", lambda: [vd.scaling_2d(plane=p) for p in ("strain", "stress")])
    sc3 = timed("4 scaling 3D", vd.scaling_3d, lv3)
    ps3 = timed("5 3D fixed ends vs 2D", vd.plane_strain_3d_study, lv3)
    a0, b0 = nobeta[0]["alpha"], nobeta[0]["beta"]
    a1, b1 = alu[0]["alpha"], alu[0]["beta"]
    L = ["## 1. Lamé shrink fit (steel 48/55 mm in aluminium to 75 mm, interference 0.03 mm)", "",
         "Closed form: Lamé (1852) with the scenes' boundary conditions (bearing inner face fixed, housing outer "
         "face clamped), `fem_reference.verify.shrink_fit_pressure`; its free/free plane-stress case is Shigley's "
         "press-fit formula (Budynas & Nisbett 2015, Eq. 3-57). FEM: `shrink_fit_fem`, a neat-fit mesh with the "
         "interference in the mortar gap, h = 4-2-1 mm, Richardson estimate. Pressure in Pa.", ""]
    L += table(shrink, "Pa")
    L += ["", "Pressure spread over the bore (max − min)/mean on the finest level: "
          + ", ".join(f"plane {r['plane']} {r['pressure_spread_rel']:.1e}" for r in shrink) + ".", "",
          "## 2. Thin-ring limit: Winkler foundation (steel in aluminium, R = 55 mm, δ0 = 0.03 mm)", "",
          "Closed form: `P = k_f R l e (ε − sin ε cos ε)`, `k_f = 1/(h_b/M_b + h_s/M_s)` (Winkler 1867; constrained "
          "moduli, Johnson 1985 §5.9). Both rings of thickness h = (h/R)·R, scene 'clamped', levels h/2 … h/16. "
          "The Winkler law is the thin limit, not exact: the difference is the model error, expected to fall "
          "with h/R (the test asserts it falls at every halving and at least linearly). Force in N.", "",
          "Δr = 0.003 mm (rigid-overlap angle 24.6°):", ""]
    L += table(wink, "N", limit=True)
    dev = [abs(r["difference_rel"]) for r in wink]
    q = [r["thickness_ratio"] for r in wink]
    L += ["", "Deviation ratio per halving of h/R: " + ", ".join(f"{a / b:.2f}" for a, b in zip(dev, dev[1:]))
          + f" (≥ 1: falls at every halving: {'yes' if all(a > b for a, b in zip(dev, dev[1:])) else 'no'}); "
          f"thinnest vs linear extrapolation from the thickest: {dev[-1]:.2e} ≤ {dev[0] * q[-1] / q[0]:.2e} "
          f"+ stated errors: {'yes' if dev[-1] <= dev[0] * q[-1] / q[0] + wink[0]['fem_error_rel'] + wink[-1]['fem_error_rel'] else 'no'}."]
    L += ["", "Δr = 0.03 mm (60°):", ""] + table(wink60, "N", limit=True)
    L += ["", "## 3. Persson pin in a plate, dissimilar materials (R_b = 100 mm, δ0 = 0.05 mm)", "",
          "Closed form: the conformal law at the measured half-angle, `P = 2πE*δ0 l b²(1+b²)/D`, "
          "`D = 2 − (1−α)(ln(1+b²) + 2b⁴)` (Persson 1964; Ciavarella & Decuzzi 2001), plane strain E* and "
          "Dundurs α. Exact only for β = 0 (docs/reference/contact-laws.md §3.3); tolerance 1 % (the stated "
          "accuracy of the measured-angle check, tests/fem_reference/plane/test_fem_solver.py) plus the force's "
          "stated error: verdict 'tol'.", "",
          f"Steel pin (208 GPa, 0.30) in a support of 72 GPa with ν = {vd.beta_free_support().poisson_ratio:.4f} "
          f"(β = 0): α = {a0:.4f}, β = {b0:.1e}.", ""]
    L += table(nobeta, "N", PERSSON_TOL)
    L += ["", "Without α the law would be off by "
          + ", ".join(f"{r['fem'] / r['law_alpha0_n'] - 1:+.2%}" for r in nobeta) + " (same rows).", "",
          f"Steel pin in aluminium (72 GPa, 0.33): α = {a1:.4f}, β = {b1:.4f}. The law with α alone:", ""]
    L += table(alu, "N", PERSSON_TOL)
    L += ["", "The same FE values against Persson's problem solved numerically with α and β "
          "(`fem_reference.verify.conformal_force_beta`: equals the closed form within 2e-5 at β = 0 and "
          "reproduces the ∂D/∂β table of docs/reference/contact-laws.md §3.5; tested):", ""]
    L += table(alu, "N", PERSSON_TOL, law_key="law_beta_n")
    wide = [r for r in alu if r["penetration_m"] == max(q["penetration_m"] for q in alu)]
    L += ["", "At the larger penetration the difference falls as the plate grows (the law is for an infinite plate): "
          + ", ".join(f"ratio {r['plate_ratio']:g} {r['fem'] / r['law_beta_n'] - 1:+.2%}" for r in wide)
          + "; the tests assert the 1 % tolerance from plate ratio 20 on."]
    L += ["", "## 4. Scaling: every length times 2", "",
          "2D: force at 2Δr on the doubled rings against 4 × the force at Δr = 0.01 mm (engineers' rings); "
          "absolute mesh levels, so the bound is the sum of both stated errors. N.", ""]
    L += table(sc2, "N")
    L += ["", f"3D, scene 'clamped', Δr = 0.01 mm, tilt 1' (levels {names3}, element counts: similar meshes): "
          "force × 4 (N), moment × 8 (N·m).", ""]
    L += table(sc3, "N or N·m")
    L += ["", f"## 5. 3D 'clamped-axially-fixed-ends' at zero tilt = 2D plane strain (levels {names3})", "",
          "Engineers' rings, steel in aluminium. 'closed form' column: the 2D plane-strain reference point; "
          "stated error: the sum of the 3D and 2D estimates. N.", ""]
    L += table(ps3, "N")
    return L, timings


def main(argv=None) -> Path:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--quick", action="store_true", help="cheap 3D levels (C0, C1, Q0) instead of Q0-Q2")
    args = ap.parse_args(argv)
    load0 = os.getloadavg()
    t0 = time.perf_counter()
    body, timings = sections(args.quick)
    total = time.perf_counter() - t0
    load1 = os.getloadavg()
    r = vd.engineer_rings()
    head = ["# FEM references on dissimilar materials and other sizes: closed-form checks", "",
            f"Generated by `benchmarks/verify_dissimilar.py{' --quick' if args.quick else ''}` on "
            f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; {platform.machine()}, {os.cpu_count()} cores, "
            f"Python {platform.python_version()}. Load average (1, 5, 15 min) at start "
            f"{', '.join(f'{v:.2f}' for v in load0)}, at end {', '.join(f'{v:.2f}' for v in load1)}. "
            f"Total {total:.0f} s: " + ", ".join(f"{k} {v:.1f} s" for k, v in timings.items()) + ".", "",
            f"Engineers' rings (`fem_reference.verify_dissimilar.engineer_rings`, radii): bearing "
            f"{r.inner_radius_m / MM:g}/{r.outer_radius_m / MM:g} mm, E {r.bearing.youngs_modulus_pa / 1e9:g} GPa, "
            f"ν {r.bearing.poisson_ratio:g}; housing bore +{r.clearance_m / MM:g} mm to {r.support_outer_radius_m / MM:g} mm, "
            f"E {r.support.youngs_modulus_pa / 1e9:g} GPa, ν {r.support.poisson_ratio:g}; width {r.width_m / MM:g} mm.", "",
            "Within: 'yes' = |difference| ≤ stated error; 'tol' = within the stated model tolerance of the "
            "section instead; 'limit' = the closed form is a limit (section 2); '**no**' = neither (read the section).", ""]
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / "fem-verification-dissimilar.md"
    atomic_write_text(path, "\n".join(head + body) + "\n")
    print(path)
    return path


if __name__ == "__main__":
    main()
