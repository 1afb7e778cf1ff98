"""Integrator benchmark: reference (paper) vs production scheme on the Table 4 rotor.

Writes ``reports/published/perf-integrators.md`` (+ ``.csv``, ``.png``, ``-agreement.png``):

1. One steady-state point at 10 500 rpm (:func:`rotor.production.steady_state`: start from the
   locked linear periodic solution, run until the once-per-revolution velocity samples change
   by < 1e-3 per revolution, then 64 revolutions; 1X–5X velocity amplitudes at exact DFT bins of
   y at disk 1, disk 2 and the support) for steps T/128 … T/2048 (T = one revolution); the
   coarsest step whose amplitudes are within 1 % of the step-halved run is the production
   step, and the wall time of the whole point at that step (after compilation) is the figure.
2. Agreement of the two schemes over one revolution from that steady state (same step).
3. Error against a T/2048 production run vs wall time, both schemes, steps T/64…T/512.

Run: ``.venv/bin/python benchmarks/bench_integrators.py`` (a few minutes).
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
from rotor.integrate import simulate_reference, system_from_model  # noqa: E402
from rotor.model import assemble  # noqa: E402
from rotor.production import prepare, simulate_production, steady_state  # noqa: E402
from rotor.scene import load_scene  # noqa: E402

OUT = ROOT / "reports" / "published"
RPM = 10500.0
NAMES = ("disk1.y", "disk2.y", "s.y")
FLOOR = 1e-3   # harmonics below FLOOR x the 1X amplitude are reported but not used to pick the step
STEPS = (128, 256, 512, 1024, 2048)


def main() -> int:
    scene = load_scene("paper-table4")
    model = assemble(scene)
    omega = RPM * 2 * math.pi / 60
    T = 2 * math.pi / omega
    system = system_from_model(model, scene, omega)
    load = os.getloadavg()
    # warm-up: compile once
    simulate_production(system, T / 256, 64, q0=system.offset, check_step=False)

    # 1. steady state at several steps
    idx = [model.dof_index(n) for n in NAMES]
    steady_state(system, 64, idx, max_revs=16, keep_revs=1)  # compile
    rows = []
    amps = {}
    for nper in STEPS:
        t0 = time.perf_counter()
        ss = steady_state(system, nper, idx)
        wall = time.perf_counter() - t0
        amps[nper] = ss.amplitudes
        rows.append((nper, T / nper, ss.transient_revs + 64, wall, ss.converged, ss.trajectory.unconverged_steps))
        if nper == 256:
            tr256 = ss.trajectory
            start = (tr256.q[-1], tr256.v[-1], float(tr256.t[-1]), tuple(int(m) for m in tr256.modes[-1]))
    # run-length sensitivity at a fixed step: tighter steady-state tolerance, longer transient
    ss_tight = steady_state(system, 256, idx, tol=1e-4)
    rel_len = np.abs(ss_tight.amplitudes - amps[256]) / ss_tight.amplitudes
    rel = {n: np.abs(amps[n] - amps[2 * n]) / amps[2 * n] for n in STEPS[:-1]}
    big = {n: amps[2 * n] >= FLOOR * amps[2 * n][:, :1] for n in STEPS[:-1]}
    strict = next((n for n in STEPS[:-1] if rel[n].max() < 0.01), None)
    floor = next((n for n in STEPS[:-1] if rel[n][big[n]].max() < 0.01), None)
    chosen = floor if floor is not None else STEPS[-1]
    chosen_wall = [r[3] for r in rows if r[0] == chosen][0]
    chosen_revs = [r[2] for r in rows if r[0] == chosen][0]

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
    from rotor import constraints as cons
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
        "`rotor.production.steady_state`: start from the periodic solution of the linear rotor with the loose "
        "support locked; every 16 revolutions compare the velocities of "
        f"{', '.join(NAMES)} sampled once per revolution; steady when they change by less than 1e-3 of their "
        "magnitude between consecutive revolutions; then 64 revolutions, 1X–5X amplitudes of the y-velocity "
        "(as the paper's spectra) at exact DFT bins.",
        "",
        "| step | Δt (s) | revolutions | wall (s) | steady | least-residual steps |",
        "|---|---|---|---|---|---|",
    ]
    for nper, d, revs, wall, conv, unc in rows:
        lines.append(f"| T/{nper} | {d:.3e} | {revs} | {wall:.2f} | {conv} | {unc} |")
    lines += ["", "1X–5X velocity amplitudes (mm/s) and their relative change when the step is halved "
              f"(values below {FLOOR:g} × 1X in brackets: not used to pick the step):", "",
              "| step | location | 1X | 2X | 3X | 4X | 5X | max rel. change vs half step (all / above floor) |",
              "|---|---|---|---|---|---|---|---|"]
    for nper in STEPS:
        for i, nm in enumerate(NAMES):
            cells = []
            for k, a in enumerate(amps[nper][i]):
                small = a < FLOOR * amps[nper][i, 0]
                cells.append(f"({a * 1e3:.3g})" if small else f"{a * 1e3:.4g}")
            rc = (f"{rel[nper][i].max() * 100:.2f} % / {rel[nper][i][big[nper][i]].max() * 100:.2f} %"
                  if nper in rel else "–")
            lines.append(f"| T/{nper} | {nm} | " + " | ".join(cells) + f" | {rc} |")
    lines += ["",
              "Run-length sensitivity at a fixed step (T/256): a tighter steady-state tolerance (1e-4, "
              f"{ss_tight.transient_revs} instead of {[r[2] for r in rows if r[0] == 256][0] - 64} transient "
              f"revolutions) changes the amplitudes by up to {rel_len.max() * 100:.1f} % (max over harmonics above the "
              f"floor: {rel_len[amps[256] >= FLOOR * amps[256][:, :1]].max() * 100:.2f} %). The harmonics below the floor "
              "are not steady to 1 % at all: stuck end faces let the bearing's relative position drift slowly "
              "(friction leaves a continuum of stuck positions), and that drift, not the step, sets their value.",
              "",
              f"- Strict reading (every harmonic within 1 % of the step-halved run): "
              f"{'T/' + str(strict) if strict else 'not met at any step tested'}.",
              f"- Harmonics above {FLOOR:g} × 1X within 1 %: **T/{chosen} (Δt = {T / chosen:.3e} s)**. "
              f"**Wall time of the whole steady-state point at that step: {chosen_wall:.2f} s** ({chosen_revs} "
              "revolutions; target ≤ 5 s). Wall times at the finer steps are in the table above.", ""]
    lines += ["## 2. Agreement and speed (one revolution of the start-up transient, Δt = T/256)", "",
              f"Window: steps 700–956 from rest at q = 0 (the misalignment offset acts as a sudden load and "
              f"presses the bearing into the support), with radial contact in {contact_frac * 100:.0f} % of the "
              f"steps (largest edge penetration {pen_max * 1e6:.2f} µm) and {switches} stick/slip switches "
              "(`perf-integrators-agreement.png`).", "",
              f"- max over time of ‖q_ref − q_prod‖₂ / max ‖q_prod − Δq_m‖₂ = **{diff2:.2e}**; "
              f"max |q_ref − q_prod| = {diff:.2e} (m or rad) against a dynamic amplitude of {dyn:.2e}.",
              f"- steps per second: reference {sps_ref:.0f}, production {sps_prod:.0f} (median of 5) → "
              f"**production {sps_prod / sps_ref:.0f}× faster** at the same step, hence equal accuracy (section 3).",
              f"- Newton steps accepted at the least residual (discontinuous one-edge selection of the law): "
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
    atomic_write_text(OUT / "perf-integrators.md", "\n".join(lines))
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
