"""3D FEM points on a grid of mid-plane penetrations and tilts, to fit and to check a tilt correction (issue 37).

    .venv/bin/python benchmarks/fem3d_tilt_grid.py RING OUT.json --tilts-arcmin 0,0.5,1 --penetrations-um 1,2,4
                                                   [--append] --reference RUN/fem3d-RING.json

(negative mid-plane penetrations, the loaded edge alone in contact: ``--penetrations-um=-0.5,-1``)

RING: a ring-pair file or a bundled name (``fem_reference.ring_scene.load``). Each point is solved by
:func:`fem_reference.solid.sweep.point_task` in this process (one core, no pool) on the ring's three 3D mesh levels
and the finer check level, whose compliances must already be in the 3D cache (a ``ringcontact bearing`` run with
tilt builds them); the error estimates use the committed sweep's pooled orders (force 2, moment 2: the orders of
``fem3d-<ring>.json`` of the ring's run folder, clipped at 2 as :func:`fem_reference.solid.richardson.pooled_orders`
does). The pressure maps are left out (they are not needed here and are most of a point's size). Writes a
``ringcontact/reference-dataset`` with the points of ``OUT.json`` (``--append``: those already there are kept and not
solved again).
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.threads import set_thread_env  # noqa: E402

set_thread_env(1)     # before numpy loads: one BLAS thread per solve (a shared 2-core machine)

from contact.dataset import read_dataset, write_dataset  # noqa: E402
from contact.units import ARCMIN  # noqa: E402

ORDERS = {"force": 2.0, "moment": 2.0}
DROPPED = ("pressure_phi_rad", "pressure_x_m", "pressure_map_pa")


def _floats(text: str) -> list[float]:
    return [float(v) for v in text.split(",") if v.strip()]


def level_paths(ring: str) -> tuple[object, list[str], str]:
    """The ring-pair file loaded, its three 3D levels' and its check level's compliance files in the 3D cache; exits
    naming the missing ones (this script never builds a level)."""
    from fem_reference import ring_scene
    from fem_reference.solid import sweep as solid
    from fem_reference.solid.mesh import CHECK_LEVEL, DEFAULT_LEVELS

    rs = ring_scene.load(ring)
    geom, scene = rs.rings_3d(), rs.bc_3d
    levels = solid._mesh_levels(DEFAULT_LEVELS)
    paths = [str(solid.compliance_path(geom, lv, scene)) for lv in levels]
    check = str(solid.compliance_path(geom, solid._mesh_levels([levels[0], levels[1], CHECK_LEVEL])[2], scene))
    missing = [p for p in paths + [check] if not Path(p).exists()]
    if missing:
        raise SystemExit(f"not in the 3D cache: {missing}; run `ringcontact bearing` on the ring with tilt first")
    return rs, paths, check


def solve_points(ring: str, pairs: list[tuple[float, float]], log=print) -> list[dict]:
    """The points ``(mid-plane penetration (m), tilt (rad))`` solved in order on the cached levels, as dataset rows
    (error estimates with :data:`ORDERS`, pressure maps left out)."""
    from fem_reference.solid import sweep as solid
    from fem_reference.solid.richardson import apply_orders

    rs, paths, check = level_paths(ring)
    out = []
    for pen, t in pairs:
        t0 = time.perf_counter()
        _, info = solid.point_task(paths, pen, t, check)
        row = apply_orders(solid._row(info), ORDERS)
        row = {k: v for k, v in row.items() if k not in DROPPED}
        row["scene"] = rs.name
        out.append(row)
        log(f"{pen * 1e6:.4g} um {t / ARCMIN:g}': F {row['force_n']:.2f} N M {row['moment_nm']:.4g} N m "
            f"({time.perf_counter() - t0:.1f} s)")
    return out


def solve(ring: str, tilts_rad: list[float], penetrations_m: list[float], have: list[dict], log=print) -> list[dict]:
    """The points of the grid not in ``have`` (keyed by penetration and tilt to 1e-12 m / rad), solved in order."""
    done = {(round(p["penetration_m"] * 1e12), round(p["tilt_rad"] * 1e12)) for p in have}
    pairs = [(pen, t) for t in tilts_rad for pen in penetrations_m
             if (round(pen * 1e12), round(t * 1e12)) not in done]
    return list(have) + solve_points(ring, pairs, log)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("ring")
    ap.add_argument("out")
    ap.add_argument("--tilts-arcmin", required=True)
    ap.add_argument("--penetrations-um", required=True)
    ap.add_argument("--reference", required=True, help="the ring's committed 3D dataset, for the metadata and columns")
    ap.add_argument("--append", action="store_true")
    a = ap.parse_args(argv)
    out = Path(a.out)
    have = read_dataset(out).points if a.append and out.exists() else []
    ref = read_dataset(a.reference)
    t0 = time.perf_counter()
    points = solve(a.ring, [v * ARCMIN for v in _floats(a.tilts_arcmin)], [v * 1e-6 for v in _floats(a.penetrations_um)],
                   [dict(p) for p in have])
    meta = dict(ref.metadata)
    meta["title"] = meta.get("title", "") + ": a grid for a tilt correction (benchmarks/fem3d_tilt_grid.py)"
    meta["grid"] = {"command": " ".join(["benchmarks/fem3d_tilt_grid.py", *(argv if argv is not None else sys.argv[1:])]),
                    "error_orders": ORDERS, "left_out": list(DROPPED), "wall_s_this_run": time.perf_counter() - t0}
    meta.pop("sweep", None)
    columns = {k: v for k, v in ref.columns.items() if k not in DROPPED}
    write_dataset(out, meta, columns, points)
    print(json.dumps({"points": len(points), "out": str(out)}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
