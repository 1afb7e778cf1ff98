"""Integrator benchmark: reference (paper) vs production scheme on the Table 4 rotor.

Writes ``reports/published/perf-integrators.md`` (+ ``.csv``, ``.png``, ``-agreement.png``):

1. One steady-state point at 10 500 rpm with :func:`rotor.studies.steady_state.steady_state` (the studies'
   Poincaré detector, tol 1e-4 with the projected tail of the decay), then 64 revolutions;
   1X–5X velocity amplitudes at exact DFT bins of y at disk 1, disk 2 and the support, for
   steps T/128 … T/2048 (T = one revolution), each run from rest, and again with every step
   restarted from the finest run's steady state (same stuck position). The coarsest step whose
   15 amplitudes are all within 1 % of the step-halved run, and the wall time of the whole
   point at that step (numba compiled; the compile time is reported separately), are the figures.
2. Agreement of the two schemes over one revolution from that steady state (same step).
3. Error against a T/2048 production run vs wall time, both schemes, steps T/64…T/512.
4. Hard cases: chatter runs and least-residual steps with and without the two fixes (edge
   transition of the law, consistent stick onset), and the steady-state amplitude change they cause.

Run: ``nice -n 0 .venv/bin/python benchmarks/bench_integrators.py`` (a few minutes); ``--section4-only``
recomputes section 4 alone (about a minute) and splices it into the existing report.
"""
from __future__ import annotations

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

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_bytes, atomic_write_text  # noqa: E402
from rotor.dynamics.build import system_from_model  # noqa: E402
from rotor.dynamics.reference import simulate_reference  # noqa: E402
from rotor.model.assembly import assemble  # noqa: E402
from rotor.dynamics.production import prepare, simulate_production  # noqa: E402
from rotor.model.scene import load_scene  # noqa: E402
from rotor.studies.steady_state import SteadyStateOptions  # noqa: E402
from rotor.studies.steady_state import harmonic_amplitudes  # noqa: E402
from rotor.studies.steady_state import steady_state as study_steady_state  # noqa: E402

OUT = ROOT / "reports" / "published"
RPM = 10500.0
NAMES = ("disk1.y", "disk2.y", "s.y")
DECIM = 64     # samples/rev of rotor.studies.steady_state's default record, to show its aliasing
REPEATS = 3    # repeated whole points (median wall time) for the steps up to T/512
STEPS = (128, 256, 512, 1024, 2048)


def main(argv=None) -> int:
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--section4-only", action="store_true",
                    help="recompute section 4 only and splice it into the existing report")
    args = ap.parse_args(argv)
    scene = load_scene("paper-table4")
    model = assemble(scene)
    if args.section4_only:
        old = (OUT / "perf-integrators.md").read_text()
        head = old[:old.index("## 4. Hard cases")]
        note = (f"*Section 4 regenerated alone ({time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load "
                f"{os.getloadavg()[0]:.2f}); sections 1–3 are from the last full run.*")
        sec = hard_cases(model, scene)
        sec[1:1] = ["", note]
        atomic_write_text(OUT / "perf-integrators.md", head + "\n".join(sec))
        print("\n".join(sec))
        return 0
    omega = RPM * 2 * math.pi / 60
    T = 2 * math.pi / omega
    system = system_from_model(model, scene, omega)
    load = os.getloadavg()
    # one-off compilation (numba; the loop taking the law kernel is compiled per process):
    # time a tiny steady-state call cold, then the same call warm
    tiny = SteadyStateOptions(steps_per_rev=64, min_revs=8, max_revs=16, spectrum_revs=2)
    t0 = time.perf_counter()
    study_steady_state(system, model, options=tiny)
    cold = time.perf_counter() - t0
    t0 = time.perf_counter()
    study_steady_state(system, model, options=tiny)
    compile_s = cold - (time.perf_counter() - t0)
    simulate_production(system, T / 256, 64, q0=system.offset, check_step=False)

    # 1. steady state at several steps, with rotor.studies.steady_state's detector (Poincaré sampling of the
    #    displacements of disk1/disk2/5/s, relative change < 1e-4 of the peak-to-peak amplitude
    #    with the geometric tail of the decay, subharmonic periods), then 64 revolutions
    def point(nper, q0=None, v0=None):
        # every step recorded (samples_per_rev = steps_per_rev): a record decimated to 64 samples/rev
        # aliases orders 64k ± h onto hX (the impacts excite high orders), measured below
        opts = SteadyStateOptions(steps_per_rev=nper, spectrum_revs=64, samples_per_rev=nper)
        t0 = time.perf_counter()
        res = study_steady_state(system, model, options=opts, q0=q0, v0=v0)
        wall = time.perf_counter() - t0
        sel = [res.channel(c) for c in NAMES]
        x = res.v[::nper // DECIM][:, sel]
        alias = np.abs(harmonic_amplitudes(x - x.mean(axis=0), res.revolutions)).T
        return res, wall, res.harmonics("v")[:, sel].T, alias   # (3 locations, 5 harmonics), m/s

    rows = []
    amps = {}
    amps_d = {}
    wall_range = {}
    results = {}
    for nper in STEPS:
        walls = []
        for rep in range(REPEATS if nper <= 512 else 1):
            res, wall, a, al = point(nper)
            walls.append(wall)
        amps[nper] = a
        amps_d[nper] = al
        results[nper] = res
        wall_range[nper] = (min(walls), max(walls))
        rows.append((nper, T / nper, res.transient_revs + res.revolutions, statistics.median(walls), len(walls),
                     res.convergence, res.unconverged_steps, res.steps_per_rev))
        if nper == 256:
            start = (res.q_end, res.v_end, 0.0, tuple(int(m) for m in res.modes[-1]))
    # same steady state continued at every step: start all steps from the state the finest run ended in
    fine = results[STEPS[-1]]
    amps_c = {}
    res_c = {}
    for nper in STEPS:
        res, wall, a, _ = point(nper, q0=fine.q_end, v0=fine.v_end)
        amps_c[nper] = a
        res_c[nper] = (res, wall)
    rel = {n: np.abs(amps[n] - amps[2 * n]) / amps[2 * n] for n in STEPS[:-1]}
    rel_d = {n: np.abs(amps_d[n] - amps_d[2 * n]) / amps_d[2 * n] for n in STEPS[:-1]}
    rel_c = {n: np.abs(amps_c[n] - amps_c[2 * n]) / amps_c[2 * n] for n in STEPS[:-1]}
    strict = next((n for n in STEPS[:-1] if rel[n].max() < 0.01), None)
    strict_c = next((n for n in STEPS[:-1] if rel_c[n].max() < 0.01), None)
    row_of = {r[0]: r for r in rows}
    side = former_rules_side_by_side(system, model, 512, point)

    # 2. agreement and speed at T/256 over one revolution of the transient with impacts
    dt = T / 256
    pre0 = simulate_production(system, dt, 700, q0=np.zeros(system.n), check_step=False)
    qe, ve, te, me = pre0.q[-1], pre0.v[-1], float(pre0.t[-1]), tuple(int(m) for m in pre0.modes[-1])
    t_ref = []
    t0 = time.perf_counter()
    tr_ref = simulate_reference(system, dt, 256, q0=qe, v0=ve, t0=te, modes0=me, check_step=False)
    t_ref.append(time.perf_counter() - t0)
    pre = prepare(system, dt)
    t_prod = []
    for _ in range(5):
        t0 = time.perf_counter()
        tr_prod = simulate_production(system, dt, 256, q0=qe, v0=ve, t0=te, modes0=me, prepared=pre, check_step=False)
        t_prod.append(time.perf_counter() - t0)
    dyn = np.abs(tr_prod.q - system.offset).max()
    diff = np.abs(tr_ref.q - tr_prod.q).max()
    diff2 = np.linalg.norm(tr_ref.q - tr_prod.q, axis=1).max() / np.linalg.norm(tr_prod.q - system.offset, axis=1).max()
    from rotor.dynamics import constraints as cons
    r1, r2 = cons.edge_offsets(tr_prod.u, system.support.width_m)
    pen_max = max(r1.max(), r2.max()) - system.support.law.clearance_m
    contact_frac = float(np.mean((r1 > system.support.law.clearance_m) | (r2 > system.support.law.clearance_m)))
    switches = int(np.abs(np.diff(tr_prod.modes.astype(int), axis=0)).sum())
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axs = plt.subplots(3, 1, figsize=(7, 7), sharex=True)
        tt = (tr_prod.t - tr_prod.t[0]) * 1e3
        iy5 = model.dof_index("5.y")
        for tr_, lab, st in ((tr_ref, "reference (paper, FD-Newton)", "-"), (tr_prod, "production", "--")):
            axs[0].plot(tt, (tr_.q[:, iy5] - system.offset[iy5]) * 1e6, st, label=lab)
            a1, a2 = cons.edge_offsets(tr_.u, system.support.width_m)
            axs[1].plot(tt, a1 * 1e6, st, label=f"r1 {lab}")
        axs[1].axhline(system.support.law.clearance_m * 1e6, color="k", lw=0.8)
        axs[2].semilogy(tt, np.linalg.norm(tr_ref.q - tr_prod.q, axis=1) + 1e-20)
        axs[0].set_ylabel("y5 − Δy5,m (µm)")
        axs[1].set_ylabel("r1 (µm), line: δ0")
        axs[2].set_ylabel("‖q_ref − q_prod‖₂")
        axs[2].set_xlabel("time in window (ms)")
        axs[0].legend(fontsize=7)
        axs[0].set_title(f"Table 4 rotor {RPM:.0f} rpm, Δt = T/256: reference vs production")
        b = io.BytesIO()
        fig.savefig(b, format="png", dpi=110, bbox_inches="tight")
        atomic_write_bytes(OUT / "perf-integrators-agreement.png", b.getvalue())
        plt.close(fig)
    except ImportError:  # pragma: no cover
        pass
    sps_ref = 256 / statistics.median(t_ref)
    sps_prod = 256 / statistics.median(t_prod)

    # 3. error vs step over one revolution, against T/2048, in two windows:
    #    "contact": the window of section 2; "steady": one revolution from the T/256 steady state
    curve = []
    windows = {"contact": (qe, ve, te, me), "steady": start}
    for wname, (q_s, v_s, t_s, m_s) in windows.items():
        fine = simulate_production(system, T / 2048, 2048, q0=q_s, v0=v_s, t0=t_s, modes0=m_s, check_step=False)
        q_fine = fine.q[-1]
        scale = np.linalg.norm(fine.q - system.offset, axis=1).max()
        for nper in (64, 128, 256, 512):
            d = T / nper
            p = prepare(system, d)
            ts = []
            for _ in range(3):
                t0 = time.perf_counter()
                tp = simulate_production(system, d, nper, q0=q_s, v0=v_s, t0=t_s, modes0=m_s, prepared=p,
                                         check_step=False)
                ts.append(time.perf_counter() - t0)
            err = np.linalg.norm(tp.q[-1] - q_fine) / scale
            curve.append((wname, "production", nper, d, err, statistics.median(ts), nper / statistics.median(ts)))
            if wname == "contact" and nper <= 256:
                if nper == 256:
                    tr_r, tt = tr_ref, statistics.median(t_ref)
                else:
                    t0 = time.perf_counter()
                    tr_r = simulate_reference(system, d, nper, q0=q_s, v0=v_s, t0=t_s, modes0=m_s, check_step=False)
                    tt = time.perf_counter() - t0
                err_r = np.linalg.norm(tr_r.q[-1] - q_fine) / scale
                curve.append((wname, "reference", nper, d, err_r, tt, nper / tt))

    # outputs
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(["window", "scheme", "steps_per_rev", "dt_s", "rel_error_vs_T2048", "wall_s_per_rev", "steps_per_s"])
    for r in curve:
        w.writerow([r[0], r[1], r[2], f"{r[3]:.6e}", f"{r[4]:.4e}", f"{r[5]:.4e}", f"{r[6]:.1f}"])
    atomic_write_text(OUT / "perf-integrators.csv", buf.getvalue())
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        for wname, scheme, mk in (("contact", "reference", "s-"), ("contact", "production", "o-"),
                                  ("steady", "production", "^--")):
            pts = [(r[5], r[4], r[2]) for r in curve if r[0] == wname and r[1] == scheme]
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], mk, label=f"{scheme}, {wname} window")
            for x, y, n in pts:
                ax.annotate(f"T/{n}", (x, y), fontsize=7)
        ax.set_xlabel("wall time per revolution (s)")
        ax.set_ylabel("relative state error after 1 rev (–)")
        ax.set_title(f"Table 4 rotor, {RPM:.0f} rpm: error vs cost")
        ax.legend()
        ax.grid(True, which="both", alpha=0.3)
        b = io.BytesIO()
        fig.savefig(b, format="png", dpi=120, bbox_inches="tight")
        atomic_write_bytes(OUT / "perf-integrators.png", b.getvalue())
        plt.close(fig)
    except ImportError:  # pragma: no cover
        pass

    lines = [
        "# Integrators: reference (paper) vs production, Table 4 rotor",
        "",
        f"Generated by `benchmarks/bench_integrators.py`. Machine: {platform.machine()}, {os.cpu_count()} cores, "
        f"load average at start {load[0]:.2f}/{load[1]:.2f}/{load[2]:.2f} (shared machine; medians of repeated runs).",
        f"Speed {RPM:.0f} rpm, revolution T = {T * 1e3:.4f} ms, n = {system.n} DOFs, the paper's conformal law as "
        "published, c_c = 100 s/m, μ = 0.3, N = 5000 N, δ0 = 0.05 mm, misalignment 1 mm.",
        "",
        "## 1. One steady-state point (transient decayed, then 64 revolutions)",
        "",
        "`rotor.studies.steady_state.steady_state` (the studies' detector): start from the misalignment offset at rest; "
        "integrate in chunks; once per revolution sample the lateral displacements of disk1, disk2, station 5 and "
        "the support (Poincaré section); steady with period m when |P_k − P_k−m| stays below 1e-4 of the "
        "peak-to-peak amplitude over the window *and* the geometric tail of the decay leaves less than 1e-4; "
        "then 64 revolutions with every step recorded, 1X–5X amplitudes of the y-velocity (as the paper's spectra) of "
        f"{', '.join(NAMES)} at exact DFT bins. Wall times: whole point from rest, numba already compiled "
        f"(median of {REPEATS} for T/128–T/512, single run above). One-off compilation in a fresh process: "
        f"**{compile_s:.1f} s** (not included).",
        "",
        "| step | Δt (s) | revolutions (transient + 64) | wall (s), median (min–max) | steady (period, Poincaré change) | "
        "least-residual steps | face stuck fraction (1, 2) | mean relative position y, z (µm), θy, θz (µrad) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for nper, d, revs, wall, nrep, conv, unc, nps in rows:
        res = results[nper]
        mu_ = res.u.mean(axis=0) * 1e6
        sf = res.modes.mean(axis=0)
        wr = f" ({wall_range[nper][0]:.2f}–{wall_range[nper][1]:.2f})" if nrep > 1 else ""
        lines.append(f"| T/{nper} | {d:.3e} | {revs} | {wall:.2f}{wr} | {conv.converged} ({conv.period}, "
                     f"{conv.change:.1e}) | {unc} | {sf[0]:.2f}, {sf[1]:.2f} | "
                     + ", ".join(f"{x:.3f}" for x in mu_) + " |")
    lines += ["", "1X–5X velocity amplitudes (mm/s), each run from rest, every step recorded; the largest relative "
              "change of the 15 when the step is halved (next row block), and the same from the record decimated "
              f"to {DECIM} samples/rev (rotor.studies.steady_state's default record):", "",
              "| step | location | 1X | 2X | 3X | 4X | 5X | 5X/1X | max rel. change vs half step (harmonic) | "
              f"same, {DECIM} samples/rev |",
              "|---|---|---|---|---|---|---|---|---|---|"]

    def amp_rows(A, R, Rd=None):
        out = []
        for nper in STEPS:
            for i, nm in enumerate(NAMES):
                cells = [f"{x * 1e3:.5g}" for x in A[nper][i]]
                rc = (f"{R[nper][i].max() * 100:.2f} % ({int(np.argmax(R[nper][i])) + 1}X)" if nper in R else "–")
                row = f"| T/{nper} | {nm} | " + " | ".join(cells) + f" | {A[nper][i, 4] / A[nper][i, 0]:.1e} | {rc} |"
                if Rd is not None:
                    row += (f" {Rd[nper][i].max() * 100:.2f} % ({int(np.argmax(Rd[nper][i])) + 1}X) |"
                            if nper in Rd else " – |")
                out.append(row)
        return out

    lines += amp_rows(amps, rel, rel_d)
    du = max(np.abs(results[n].u.mean(axis=0)[:2] - results[2 * n].u.mean(axis=0)[:2]).max() for n in STEPS[:-1])
    ratio_min = min(float((amps[n][:, 4] / amps[n][:, 0]).min()) for n in STEPS)
    lines += ["",
              f"All five harmonics are used (no floor): the smallest, 5X, is {ratio_min:.1e} of 1X (≈ 0.5–1 µm/s) "
              "and is a real periodic signal (the two halves of the record agree to < 1e-4), not numerical noise. "
              f"Two effects, measured here, had made it look unsettled: (a) **aliasing** — with the record decimated "
              f"to {DECIM} samples/rev, orders {DECIM}k ± h (excited by the impacts, resolved differently at every "
              "step) fold onto hX; the largest change per halving is then "
              + ", ".join(f"T/{n}: {rel_d[n].max() * 100:.2f} %" for n in STEPS[:-1])
              + " (always 5X of a small channel) against "
              + ", ".join(f"{rel[n].max() * 100:.2f} %" for n in STEPS[:-1])
              + " with every step recorded; (b) **path dependence** — one end face sticks for good (stuck fraction "
              "1.00 above) and Coulomb friction leaves a continuum of stuck positions; which one a run from rest ends "
              "in depends on the whole start-up transient (impacts, stick/slip switches), whose error does not fall "
              f"like Δt² (section 3). The mean relative position moves by up to {du * 1e6:.2f} µm between "
              "step-halved runs, and 3X–5X follow it: at the two finest halvings they change by "
              + ", ".join(f"{rel[n][:, 2:].max() * 100:.2f} %" for n in STEPS[-3:-1])
              + " from rest against "
              + ", ".join(f"{rel_c[n][:, 2:].max() * 100:.2f} %" for n in STEPS[-3:-1])
              + " from one state. Restarted from one state (same stuck "
              "position), only the step differs:", "",
              f"Same steady state at every step: each step restarted from the state the T/{STEPS[-1]} run ended "
              "in, detector and record as above:", "",
              "| step | location | 1X | 2X | 3X | 4X | 5X | 5X/1X | max rel. change vs half step (harmonic) |",
              "|---|---|---|---|---|---|---|---|---|"]
    lines += amp_rows(amps_c, rel_c)
    chosen = strict if strict is not None else strict_c
    lines += ["",
              "- Strict reading, independent runs from rest (every one of the 15 amplitudes within 1 % of the "
              f"step-halved run): {'**T/' + str(strict) + '**' if strict else '**not met at any step tested**'} "
              f"(largest change per halving: " + ", ".join(f"T/{n}: {rel[n].max() * 100:.2f} %" for n in STEPS[:-1])
              + ").",
              "- Same steady state (restarted from one state, so only the step differs): every amplitude within "
              f"1 % from {'**T/' + str(strict_c) + '**' if strict_c else '**no step tested**'} ("
              + ", ".join(f"T/{n}: {rel_c[n].max() * 100:.2f} %" for n in STEPS[:-1]) + ")."]
    if chosen is not None:
        cr = row_of[chosen]
        lines.append(f"- **Wall time of the whole point from rest at T/{chosen} (Δt = {T / chosen:.3e} s): "
                     f"{cr[3]:.2f} s** ({cr[2]} revolutions; target ≤ 5 s; compilation {compile_s:.1f} s once per "
                     "process, excluded).")
    lines.append(f"- Side by side in this run at T/512, alternating (median of {len(side['current'][0])}): current rules "
                 f"{statistics.median(side['current'][0]):.2f} s ({side['current'][1]} revolutions), former rules "
                 f"(sharp edge rule, former stick onset; section 4) {statistics.median(side['former'][0]):.2f} s "
                 f"({side['former'][1]} revolutions): per revolution the current rules cost "
                 f"{statistics.median(side['current'][0]) / side['current'][1] / (statistics.median(side['former'][0]) / side['former'][1]):.2f}× "
                 "the former; the number of revolutions the detector needs depends on the path into the stuck "
                 "position.")
    lines.append("")
    lines += ["## 2. Agreement and speed (one revolution of the start-up transient, Δt = T/256)", "",
              f"Window: steps 700–956 from rest at q = 0 (the misalignment offset acts as a sudden load and "
              f"presses the bearing into the support), with radial contact in {contact_frac * 100:.0f} % of the "
              f"steps (largest edge penetration {pen_max * 1e6:.2f} µm) and {switches} stick/slip switches "
              "(`perf-integrators-agreement.png`).", "",
              f"- max over time of ‖q_ref − q_prod‖₂ / max ‖q_prod − Δq_m‖₂ = **{diff2:.2e}**; "
              f"max |q_ref − q_prod| = {diff:.2e} (m or rad) against a dynamic amplitude of {dyn:.2e}.",
              f"- steps per second: reference {sps_ref:.0f}, production {sps_prod:.0f} (median of 5) → "
              f"**production {sps_prod / sps_ref:.0f}× faster** at the same step, hence equal accuracy (section 3).",
              f"- Newton steps accepted at the least residual (Newton not converged, least-residual iterate kept): "
              f"reference {tr_ref.unconverged_steps}, production {tr_prod.unconverged_steps} of 256.", "",
              "## 3. Error vs step and cost", "",
              "Relative state error after one revolution against a T/2048 production run from the same start "
              "(‖q − q_fine‖₂ / max ‖q_fine − Δq_m‖₂), in the contact window of section 2 and in one revolution "
              "from the T/256 steady state (`perf-integrators.csv`, `perf-integrators.png`). Impacts and stick/slip "
              "switches excite high, unresolved modes (the 3a/3b coupling tilt among them) whose phase error does not "
              "shrink like Δt², so the contact window converges slowly; the smooth steady window shows Newmark's "
              "second order.", "",
              "| window | scheme | step | rel. error | wall per rev (s) | steps/s |", "|---|---|---|---|---|---|"]
    for r in curve:
        lines.append(f"| {r[0]} | {r[1]} | T/{r[2]} | {r[4]:.3e} | {r[5]:.3e} | {r[6]:.0f} |")
    lines.append("")
    lines += hard_cases(model, scene)
    atomic_write_text(OUT / "perf-integrators.md", "\n".join(lines))
    print("\n".join(lines))
    return 0


def former_rules_side_by_side(system, model, nper, point, repeats=REPEATS):
    """Whole steady point at T/nper with the current and the former rules (edge transition 0 and
    consistent_stick_onset False), alternating in one process: wall times and revolutions.

    ``rotor.studies.steady_state.steady_state`` takes no integrator options, so the former stick onset is set
    by swapping the default ``NewmarkOptions`` that ``rotor.dynamics.production`` builds (benchmark only)."""
    import functools
    from unittest import mock

    import rotor.dynamics.production as rp
    from rotor.dynamics.system import NewmarkOptions

    eps = _with_edge(system, 0.0)
    _with_edge(system, eps)
    out = {"current": ([], 0), "former": ([], 0)}
    for _ in range(repeats):
        for name in ("current", "former"):
            if name == "former":
                _with_edge(system, 0.0)
                with mock.patch.object(rp, "NewmarkOptions",
                                       functools.partial(NewmarkOptions, consistent_stick_onset=False)):
                    res, wall, _, _ = point(nper)
                _with_edge(system, eps)
            else:
                res, wall, _, _ = point(nper)
            out[name][0].append(wall)
            out[name] = (out[name][0], res.transient_revs + res.revolutions)
    return out


HARD = (("clearance 0.001 mm", dict(clearance_m=1e-6)), ("clearance 1 mm", dict(clearance_m=1e-3)),
        ("misalignment 0", dict(misalignment_m=0.0)), ("misalignment 3 mm", dict(misalignment_m=3e-3)),
        ("μ = 0", dict(mu=0.0)), ("μ = 1", dict(mu=1.0)), ("preload 0", dict(preload_N=0.0)))
EDGE_SLOT = 13   # kernel slot of LooseSupportParams.edge_transition_m (contact._kernel)


def _with_edge(system, eps_m):
    """Set the edge-transition width of the system's law (m); returns the previous value."""
    old = float(system.support.law.params[EDGE_SLOT])
    system.support.law.params[EDGE_SLOT] = eps_m
    return old


def _hard_counts(system, dt, n, q0, opts):
    from contact.errors import OutsideDomainError
    try:
        tr = simulate_production(system, dt, n, q0=q0, check_step=False, options=opts)
    except OutsideDomainError:
        return "stops: beyond neat-fit limit", None
    d = np.diff(tr.modes.astype(int), axis=0) != 0
    ch = int((d[:-2] & d[1:-1] & d[2:]).sum())
    ok = "" if np.all(np.isfinite(tr.q)) else " NaN!"
    return f"{ch} / {tr.unconverged_steps}{ok}", (ch, tr.unconverged_steps)


def hard_cases(model, scene) -> list:
    """Section 4: chatter runs and least-residual steps of the hard cases, 10 revolutions at T/256
    (and T/512), from the centred support at rest (q = Δq_m, as tests/rotor/dynamics/test_dynamics_constraints.py) and
    from q = 0, with the current rules and with either fix undone; then the change of the 10 500 rpm
    steady-state amplitudes that each fix causes."""
    from contact.tilt import EDGE_TRANSITION_M
    from rotor.dynamics.system import NewmarkOptions

    omega = RPM * 2 * math.pi / 60
    T = 2 * math.pi / omega
    revs = 10
    eps = EDGE_TRANSITION_M
    variants = ((f"current (edge transition {eps * 1e6:g} µm, consistent stick onset)", eps, NewmarkOptions()),
                ("stick-onset fix only (ε_e = 0)", 0.0, NewmarkOptions()),
                ("edge transition only (former stick onset)", eps, NewmarkOptions(consistent_stick_onset=False)),
                ("former (ε_e = 0, former stick onset)", 0.0, NewmarkOptions(consistent_stick_onset=False)))
    out = ["## 4. Hard cases: chatter and least-residual steps", "",
           f"{revs} revolutions at {RPM:.0f} rpm, production scheme, from the centred support at rest (q = Δq_m) "
           "and from q = 0. Chatter run: three consecutive stick/slip flips of a face (step-by-step "
           "alternation). Least-residual step: Newton did not converge and the least-residual iterate was kept. "
           "Each cell: chatter runs / least-residual steps. The two fixes: the edge transition of the law "
           "(a regularisation of Dai et al. 2025 Eqs. 18–19, `LooseSupportParams.edge_transition_m`, "
           "contact/tilt.py) and the consistent stick onset (`NewmarkOptions.consistent_stick_onset`, "
           "rotor/dynamics/constraints.py).", ""]
    totals = {}
    for nper, vs in ((256, variants), (512, (variants[0], variants[3]))):
        dt = T / nper
        out += [f"Δt = T/{nper} ({revs * nper} steps):", "",
                "| case | start | " + " | ".join(v[0] for v in vs) + " |", "|---|---|" + "---|" * len(vs)]
        for label, kw in HARD:
            system = system_from_model(model, scene, omega, **kw)
            for start, q0 in (("centred (Δq_m)", system.offset), ("q = 0", np.zeros(system.n))):
                cells = []
                for name, e, opts in vs:
                    _with_edge(system, e)
                    cell, counts = _hard_counts(system, dt, revs * nper, q0, opts)
                    cells.append(cell)
                    if counts is not None:
                        tot = totals.setdefault((nper, name), [0, 0])
                        tot[0] += counts[0]
                        tot[1] += counts[1]
                out.append(f"| {label} | {start} | " + " | ".join(cells) + " |")
        out.append("| **total** | | " + " | ".join(f"**{totals[(nper, v[0])][0]} / {totals[(nper, v[0])][1]}**"
                                                   for v in vs) + " |")
        out.append("")

    # steady-state amplitudes at 10 500 rpm with and without each fix: fixed transient of 1000
    # revolutions from the centred support (the studies' detector needs 840-970), then 64 revolutions
    # recorded at every step; 1X-5X velocity amplitudes of y at disk 1, disk 2 and the support
    system = system_from_model(model, scene, omega)
    idx = [model.dof_index(c) for c in NAMES]
    amp_rows = []
    for nper in (512, 1024):
        dt = T / nper
        amps = {}
        restart_name = variants[0][0] + ", restarted from the former rules' steady state"

        def record64(q0, v0, t0, modes0, opts, pre):
            tr2 = simulate_production(system, dt, 64 * nper, q0=q0, v0=v0, t0=t0, modes0=modes0, check_step=False,
                                      options=opts, prepared=pre)
            x = tr2.v[1:, idx]
            return np.abs(harmonic_amplitudes(x - x.mean(axis=0), 64)).T   # (3 locations, 5 orders)

        for name, e, opts in (variants[3], variants[2], variants[0]):
            _with_edge(system, e)
            pre = prepare(system, dt, opts)
            tr = simulate_production(system, dt, 1000 * nper, q0=system.offset, check_step=False, options=opts,
                                     record_every=nper, prepared=pre)
            end = (tr.q[-1], tr.v[-1], float(tr.t[-1]), tuple(int(m) for m in tr.modes[-1]))
            amps[name] = record64(*end, opts, pre)
            if name == variants[3][0]:
                former_end = end
        # same 64 revolutions from the former rules' steady state with the current rules: separates
        # the effect of the rules on the steady orbit from that on the path into it
        _with_edge(system, eps)
        amps[restart_name] = record64(*former_end, variants[0][2], prepare(system, dt, variants[0][2]))
        base = amps[variants[3][0]]
        for name in (variants[2][0], variants[0][0], restart_name):
            rel = np.abs(amps[name] - base) / base
            amp_rows.append((nper, name, rel.max(axis=0), rel.max()))
    out += [f"Steady-state 1X–5X velocity amplitudes at {RPM:.0f} rpm (y at {', '.join(NAMES)}; 1000 revolutions "
            "from the centred support, then 64 recorded), largest relative change against the former rules "
            "(ε_e = 0, former stick onset):", "",
            "| Δt | rules | 1X | 2X | 3X | 4X | 5X | largest |", "|---|---|---|---|---|---|---|---|"]
    for nper, name, per_order, worst in amp_rows:
        out.append(f"| T/{nper} | {name} | " + " | ".join(f"{v * 100:.3f} %" for v in per_order)
                   + f" | {worst * 100:.3f} % |")
    out += ["",
            "Reading: the edge transition changes no amplitude at all (the steady orbit never enters the bands "
            f"|Δr1 − Δr2| < ε_e/2 or δ0 − ε_e < |r| < δ0; ε_e = {eps * 1e6:g} µm lies between the measured bounds "
            "50 nm, the smallest width that removes every least-residual step of the table, and 0.5 µm, the "
            "largest that leaves the steady state bit-identical; contact/tilt.py). The stick-onset rule does not "
            "act on the steady orbit itself (no stick/slip switch in it: one face stays stuck, the other slips; "
            "restarted from the same state both rules give identical amplitudes, last row of each step), but it "
            "changes the path of the transient and so the stuck position the orbit settles in (the path "
            "dependence of section 1): 1X moves by a few 1e-5, the small 2X–5X components by a few tenths of a "
            "percent, which does not shrink with the step. Former findings (commit history): the 25-iteration "
            "Newton cap caused friction stalls (cap now 80); a 10× friction regularisation (w_reg 10 µm/s) also "
            "removed the chatter but moved the Den Hartog stick-slip orbit outside its tested tolerance.", ""]
    return out


if __name__ == "__main__":
    sys.exit(main())
