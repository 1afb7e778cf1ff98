"""A blind check of the 20 mm ring's tilt-corrected law: points drawn from a seed at run time, solved on the cached 3D
levels, and the committed law checked at each (``bench_tilt_correction.py --blind N [--seed S]``; issue 37, must-show 3).

The smoothing rule of the committed law (one weight along ξ, one along ψ) was adopted after the verification grid had
shown a miss, so for the 20 mm ring that grid is no longer blind. This module draws a new set:

- ``N`` tilted points, the mid-plane penetration log-uniform over :data:`PENETRATION_RANGE_M` (0.5-30 µm, the law's
  range) and the tilt uniform over :data:`TILT_RANGE_RAD` (0-8′), and ``N // 8`` zero-tilt points, log-uniform over
  the same penetrations, from ``numpy.random.default_rng(seed)`` (tilted first, then zero tilt); a draw that coincides
  with a training or verification grid point or a committed 3D point of the ring (keyed to 1e-12 m / rad) is drawn
  again;
- solved by :func:`fem3d_tilt_grid.solve_points` (the grids' machinery: Q0-Q2 and the Q3 check level from the 3D
  cache, never built here: the cache's files are listed before and after), kept in :data:`POINTS_FILE` with the seed;
- checked against the law file :data:`LAW_FILE` as committed (not refitted) through the compiled kernel, as the held-out
  tables are (:func:`contact.calibrate.tilt_fit.held_out`; zero tilt: the law's force), each error against
  :func:`contact.calibrate.fit.within_accuracy` (2 x the FEM point's stated error + 0.2 %), force and moment.

The section it writes replaces the one of an earlier ``--blind`` run in ``law-tilt-correction.md``; a full run of the
benchmark, which refits the law file, recomputes the section from the kept points with the law it wrote (no point
solved again; :func:`section_lines`).
"""
from __future__ import annotations

import hashlib
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import fem3d_tilt_grid  # noqa: E402
from contact import calibrate as cal  # noqa: E402
from contact.calibrate import tilt_fit  # noqa: E402
from contact.calibrate.fit import ACCURACY_ADD_REL, ACCURACY_FEM_FACTOR, ACCURACY_RULE, within_accuracy  # noqa: E402
from contact.dataset import read_dataset, write_dataset  # noqa: E402
from contact.units import ARCMIN  # noqa: E402

PUBLISHED = ROOT / "reports" / "published"
RING = "newcomer-20mm"
#: under the report's folder (``--out``, default reports/published): the ring's run folder, its ring-pair file, its
#: committed 3D points (the dataset's metadata and columns), its published (slices') law
RUN = "law-family-newcomer-20mm"
RING_FILE, REFERENCE, SLICES_LAW = "newcomer-20mm.toml", "fem3d-newcomer-20mm.json", "newcomer-20mm-law.json"
#: in ``law-tilt-correction/``: the grids, the committed law with its correction, the blind points
GRIDS = ("fem3d-tilt-train-newcomer-20mm.json", "fem3d-tilt-verify-newcomer-20mm.json")
LAW_FILE = "newcomer-20mm-3d-foundation-spline-tilt-law.json"
POINTS_FILE = "fem3d-tilt-blind-newcomer-20mm.json"
#: the law's range (m, rad): issue 37's must-show 3 for the 20 mm ring, the training grid's ends
PENETRATION_RANGE_M = (0.5e-6, 30e-6)
TILT_RANGE_RAD = (0.0, 8 * ARCMIN)
HEADING = "## Blind check: a new seeded sample of the 20 mm ring"
NEXT_HEADING = "## Kernel cost against today's foundation law"


def key(penetration_m: float, tilt_rad: float) -> tuple[int, int]:
    """A point's key: penetration and tilt to 1e-12 m and rad (as the grids key them)."""
    return round(penetration_m * 1e12), round(tilt_rad * 1e12)


def new_seed() -> int:
    """A seed from the operating system's entropy, 0 <= seed < 2**32."""
    return int(np.random.SeedSequence().entropy % 2 ** 32)


def grid_keys(out: Path = PUBLISHED) -> set[tuple[int, int]]:
    """The keys of the training and verification grids' points and of the ring's committed 3D points."""
    files = [out / "law-tilt-correction" / g for g in GRIDS] + [out / RUN / REFERENCE]
    return {key(p["penetration_m"], p["tilt_rad"]) for f in files for p in read_dataset(f).points}


def draw(seed: int, n_tilted: int, n_zero: int, taken: set | frozenset = frozenset()) -> list[tuple[float, float]]:
    """The blind points ``(mid-plane penetration (m), tilt (rad))``: ``n_tilted`` tilted (penetration log-uniform over
    :data:`PENETRATION_RANGE_M`, tilt uniform over :data:`TILT_RANGE_RAD`, a tilt of 0 drawn again), then ``n_zero``
    at zero tilt; a point whose key is in ``taken`` or already drawn is drawn again."""
    rng = np.random.default_rng(seed)
    lo, hi = np.log(PENETRATION_RANGE_M[0]), np.log(PENETRATION_RANGE_M[1])
    seen, out = set(taken), []
    for count, tilted in ((n_tilted, True), (n_zero, False)):
        got = 0
        while got < count:
            pen = float(np.exp(rng.uniform(lo, hi)))
            tilt = float(rng.uniform(*TILT_RANGE_RAD)) if tilted else 0.0
            k = key(pen, tilt)
            if (tilted and k[1] == 0) or k in seen or not PENETRATION_RANGE_M[0] <= pen <= PENETRATION_RANGE_M[1]:
                continue
            seen.add(k)
            out.append((pen, tilt))
            got += 1
    return out


def _cache_listing(paths: list[str]) -> dict:
    """Name -> (size, mtime) of every file in the folders of the 3D cache the levels live in."""
    folders = {Path(p).parent for p in paths}
    return {str(f): (f.stat().st_size, f.stat().st_mtime_ns) for d in folders for f in d.iterdir() if f.is_file()}


def _git(*args: str) -> str:
    try:
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def solve(seed: int, n_tilted: int, out: Path = PUBLISHED, log=print) -> dict:
    """Draw and solve the blind points; write :data:`POINTS_FILE` (the seed and the run in its metadata ``blind``);
    returns that metadata. CPU (s) is this process's, the load average (-) before and after."""
    pairs = draw(seed, n_tilted, n_tilted // 8, grid_keys(out))
    ring_file = str(out / RUN / RING_FILE)
    _, paths, check = fem3d_tilt_grid.level_paths(ring_file)
    before = _cache_listing(paths + [check])
    load0, cpu0, wall0 = os.getloadavg()[0], time.process_time(), time.perf_counter()
    points = fem3d_tilt_grid.solve_points(ring_file, pairs, log)
    run = {"seed": seed, "n_tilted": n_tilted, "n_zero": n_tilted // 8, "commit": _git("rev-parse", "--short", "HEAD"),
           "cpu_s": time.process_time() - cpu0, "wall_s": time.perf_counter() - wall0,
           "load_average": [load0, os.getloadavg()[0]], "cache_unchanged": _cache_listing(paths + [check]) == before,
           "command": f"benchmarks/bench_tilt_correction.py --blind {n_tilted} --seed {seed}",
           "penetration_range_m": list(PENETRATION_RANGE_M), "tilt_range_rad": list(TILT_RANGE_RAD)}
    ref = read_dataset(out / RUN / REFERENCE)
    meta = dict(ref.metadata)
    meta["title"] = meta.get("title", "") + ": a blind sample for the tilt correction (benchmarks/tilt_blind.py)"
    meta["blind"] = run
    meta.pop("sweep", None)
    columns = {k: v for k, v in ref.columns.items() if k not in fem3d_tilt_grid.DROPPED}
    write_dataset(out / "law-tilt-correction" / POINTS_FILE, meta, columns, points)
    return run


def check(law, points: list[dict]) -> dict:
    """Errors (-) of ``law`` at the points, each with its bound (-) and verdict (``within_accuracy``): ``zero_force``
    (the law's force at zero tilt), ``tilted_force`` and ``tilted_moment`` (the compiled kernel), and the tilted
    points' ``penetration_m``, ``tilt_rad``. Raises if the kernel's check leaves a tilted point out."""
    zero = [p for p in points if p["tilt_rad"] == 0]
    tilted = [p for p in points if p["tilt_rad"] > 0]
    f0 = np.array([p["force_n"] for p in zero])
    e0 = np.array([p["force_error_rel"] for p in zero], dtype=float)
    out = {"zero_force": np.asarray(law.force(np.array([p["penetration_m"] for p in zero])).force_N) / f0 - 1}
    out["zero_force_fem"] = e0
    h = tilt_fit.held_out(law, tilted)
    if h["penetration_m"].size != len(tilted):
        raise RuntimeError(f"{len(tilted) - h['penetration_m'].size} blind tilted point(s) left out of the check")
    out.update(tilted_force=h["force_error"], tilted_moment=h["moment_error"], penetration_m=h["penetration_m"],
               tilt_rad=h["tilt_rad"], zero_penetration_m=np.array([p["penetration_m"] for p in zero]),
               tilted_force_fem=np.array([p["force_error_rel"] for p in tilted], dtype=float),
               tilted_moment_fem=np.array([p["moment_error_rel"] for p in tilted], dtype=float))
    for q in ("zero_force", "tilted_force", "tilted_moment"):
        out[q + "_within"] = within_accuracy(out[q], out[q + "_fem"])
        out[q + "_bound"] = ACCURACY_FEM_FACTOR * np.abs(out[q + "_fem"]) + ACCURACY_ADD_REL
    return out


def _row(name: str, err: np.ndarray, bound: np.ndarray, within: np.ndarray) -> str:
    """A table row: within / all, holds, largest error (%), the worst point's error vs its bound (%)."""
    if not err.size:
        return f"| {name} | – | – | – | – |"
    i = int(np.argmax(np.abs(err) - bound))
    return (f"| {name} | {int(within.sum())} / {err.size} | {'yes' if within.all() else 'no'} | "
            f"{100 * np.max(np.abs(err)):.3f} | {100 * abs(err[i]):.3f} vs {100 * bound[i]:.3f} |")


QUANTITIES = (("zero_force", "force, zero tilt"), ("tilted_force", "force, tilted"), ("tilted_moment", "moment, tilted"))


def misses(e: dict) -> list[str]:
    """Every blind point outside the target, with its penetration, tilt, quantity, error and bound."""
    out = []
    for q, label in QUANTITIES:
        pen = e["zero_penetration_m"] if q == "zero_force" else e["penetration_m"]
        tilt = np.zeros_like(pen) if q == "zero_force" else e["tilt_rad"]
        out += [f"{label} at {pen[i] * 1e6:.4g} µm and {tilt[i] / ARCMIN:.3g}′: {100 * e[q][i]:+.3f} % against a "
                f"bound of {100 * e[q + '_bound'][i]:.3f} % ({abs(e[q][i]) / e[q + '_bound'][i]:.2f}x)"
                for i in np.flatnonzero(~e[q + "_within"])]
    return out


def _point_rows(e: dict) -> list[str]:
    lines = ["Every tilted blind point (the committed law with its correction), by penetration:", "",
             "| Δr (µm) | tilt (′) | force error (%) | bound (%) | moment error (%) | bound (%) | within |",
             "|---|---|---|---|---|---|---|"]
    for i in np.argsort(e["penetration_m"]):
        ok = e["tilted_force_within"][i] and e["tilted_moment_within"][i]
        lines.append(f"| {e['penetration_m'][i] * 1e6:.4g} | {e['tilt_rad'][i] / ARCMIN:.3f} | "
                     f"{100 * e['tilted_force'][i]:+.3f} | {100 * e['tilted_force_bound'][i]:.3f} | "
                     f"{100 * e['tilted_moment'][i]:+.3f} | {100 * e['tilted_moment_bound'][i]:.3f} | "
                     f"{'yes' if ok else '**no**'} |")
    return lines


def section_lines(out: Path = PUBLISHED) -> list[str]:
    """The report's blind section, from the kept points and the committed law files (no FEM solve)."""
    points_file, law_file = out / "law-tilt-correction" / POINTS_FILE, out / "law-tilt-correction" / LAW_FILE
    slices_file = out / RUN / SLICES_LAW
    ds = read_dataset(points_file)
    run = ds.metadata["blind"]
    law = cal.CalibratedLaw.from_json(law_file.read_text(encoding="utf-8"))
    slices = cal.CalibratedLaw.from_json(slices_file.read_text(encoding="utf-8"))
    after, before = check(law, ds.points), check(slices, ds.points)
    rel = law_file.relative_to(out).as_posix()
    digest = hashlib.sha256(law_file.read_bytes()).hexdigest()[:12]
    lines = [HEADING, "",
             f"Points drawn and solved by `{run['command']}` at commit {run['commit']} (seed {run['seed']}, drawn at run "
             "time unless "
             "given; `benchmarks/tilt_blind.py`). The law's smoothing rule was adopted after the verification grid had "
             "shown a miss, so this is the 20 mm ring's blind check: "
             f"{run['n_tilted']} tilted points, the mid-plane penetration log-uniform over "
             f"{run['penetration_range_m'][0] * 1e6:g}-{run['penetration_range_m'][1] * 1e6:g} µm and the tilt "
             f"uniform over 0-{run['tilt_range_rad'][1] / ARCMIN:g}′, and {run['n_zero']} zero-tilt points, none of "
             "them a training or verification grid point or a committed 3D point of the ring. Solved by `benchmarks/fem3d_tilt_grid.py`'s machinery on the "
             f"ring's cached 3D levels (Q0-Q2, Q3 check), one process: {run['cpu_s']:.1f} s CPU, {run['wall_s']:.1f} s "
             f"wall, load average {run['load_average'][0]:.2f} → {run['load_average'][1]:.2f} (2 cores shared); "
             + ("no level built (the 3D cache's files unchanged)" if run["cache_unchanged"] else
                "**the 3D cache's files changed during the run**")
             + f". Points: `{points_file.relative_to(out).as_posix()}`. Law: the committed "
             f"[{law_file.name}]({rel}) (sha256 {digest}…, fitted on the training grid alone, never on these points; "
             "a full run of the benchmark refits it and recomputes this section from the kept points) through the "
             "compiled kernel, as above; the "
             f"published slices' law `{slices.name}` beside it. Target: {ACCURACY_RULE} "
             "(`contact.calibrate.fit.within_accuracy`).", "",
             "| law | quantity | within / all | holds | largest error (%) | worst: error vs bound (%) |",
             "|---|---|---|---|---|---|"]
    for e, name in ((before, f"published `{slices.name}` (slices)"), (after, f"`{law.name}` (slices + correction)")):
        lines += [_row(f"{name} | {label}", e[q], e[q + "_bound"], e[q + "_within"]) for q, label in QUANTITIES]
    miss = misses(after)
    n = sum(after[q].size for q, _ in QUANTITIES)
    ratio = {q: float(np.max(np.abs(after[q]) / after[q + "_bound"])) for q, _ in QUANTITIES if after[q].size}
    lines += ["", f"**Blind sample, seed {run['seed']}: the committed law with its tilt correction is within the target "
              + (f"at every point, force and moment ({n} of {n} checks).**" if not miss else
                 f"at {n - len(miss)} of {n} checks; outside: {'; '.join(miss)}.**")
              + " Largest error over its bound: " + "; ".join(f"{label} {ratio[q]:.2f}" for q, label in QUANTITIES
                                                              if q in ratio) + ".", ""]
    return lines + _point_rows(after) + [""]


def spliced(text: str, lines: list[str]) -> str:
    """``law-tilt-correction.md``'s text with its blind section replaced by ``lines`` (inserted before the kernel
    cost if it has none)."""
    section = "\n".join(lines).rstrip("\n") + "\n\n"
    a = text.find(HEADING)
    if a < 0:
        b = text.find(NEXT_HEADING)
        if b < 0:
            raise ValueError(f"law-tilt-correction.md has neither {HEADING!r} nor {NEXT_HEADING!r}")
        return text[:b] + section + text[b:]
    b = text.find("\n## ", a + len(HEADING))
    return text[:a] + section + (text[b + 1:] if b >= 0 else "")


def kept_section(old_text: str) -> list[str] | None:
    """The blind section of an earlier report's text (lines), or None: a full run of the benchmark keeps it when the
    kept points are gone."""
    a = old_text.find(HEADING)
    if a < 0:
        return None
    b = old_text.find("\n## ", a + len(HEADING))
    return old_text[a:b if b >= 0 else len(old_text)].rstrip("\n").split("\n")
