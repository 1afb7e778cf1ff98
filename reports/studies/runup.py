"""Run-up through the critical speeds (beyond the paper): time–frequency cascade, time histories, note."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.studies.common import integrator_text, LOCATIONS, pyplot, save


def runup_figures(out, figs, *, prefix: str = "study-runup") -> list[Path]:
    """Time–frequency cascade of a run-up (see :mod:`rotor.studies.runup`), the orders 1X–5X dotted (in each panel's
    legend), and the time histories."""
    from rotor.studies.runup import load_runup, stft_cascade

    plt = pyplot()
    from matplotlib.colors import LogNorm

    figs = Path(figs)
    r = load_runup(out)
    files = []
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), constrained_layout=True)
    for ax, (ch, lab) in zip(axes, LOCATIONS):
        tc, fr, A, rpm_c = stft_cascade(r, ch)
        A = A * 1e3
        top = A.max()
        m = ax.pcolormesh(fr, rpm_c, A, norm=LogNorm(vmin=top * 1e-4, vmax=top), cmap="viridis", shading="auto",
                          rasterized=True)
        for k in range(1, 6):
            ax.plot(k * rpm_c / 60, rpm_c, ":", color="w", lw=0.6,
                    label="1X–5X (k × rotation frequency)" if k == 1 else None)
        ax.legend(fontsize=7, loc="lower right", facecolor="0.3", labelcolor="w", framealpha=0.8)
        ax.set_xlim(0, 5.5 * rpm_c.max() / 60)
        ax.set_xlabel("frequency (Hz)")
        ax.set_ylabel("rotor speed (rpm)")
        ax.set_title(f"{lab}: y-velocity (mm/s)", fontsize=9)
        plt.colorbar(m, ax=ax, pad=0.01)
    fig.suptitle(f"Run-up {r['rpm'][0]:.0f} → {r['rpm'][-1]:.0f} rpm in {r['t'][-1] - r['t'][0]:.1f} s: "
                 "time–frequency cascade (STFT)", fontsize=10)
    files += save(fig, figs / prefix)
    fig, axes = plt.subplots(2, 1, figsize=(11, 6), constrained_layout=True, sharex=True)
    for ch, lab in LOCATIONS:
        c = list(r["channels"]).index(ch)
        axes[0].plot(r["rpm"], r["q"][:, c] * 1e6 - np.median(r["q"][:, c]) * 1e6, lw=0.4, label=lab, rasterized=True)
    axes[0].set_ylabel("y − median (µm)")
    axes[0].legend(fontsize=8)
    axes[1].plot(r["rpm"], r["r1"] * 1e3, lw=0.4, label="r1", rasterized=True)
    axes[1].plot(r["rpm"], r["r2"] * 1e3, lw=0.4, label="r2", rasterized=True)
    axes[1].axhline(r["clearance_m"] * 1e3, color="k", ls="--", lw=0.8, label="δ0")
    axes[1].set_ylabel("relative edge offset (mm)")
    axes[1].set_xlabel("rotor speed (rpm)")
    axes[1].legend(fontsize=8)
    files += save(fig, figs / f"{prefix}-time")
    return files


def runup_note(out) -> str:
    """Markdown: what the run-up shows (first contact speed, 1X peaks), from the stored run."""
    from rotor.studies.runup import load_runup, stft_cascade

    r = load_runup(out)
    info = r["info"]
    d0 = r["clearance_m"]
    contact = (r["r1"] > d0) | (r["r2"] > d0)
    first = r["rpm"][np.argmax(contact)] if contact.any() else None
    lines = ["# Run-up through the critical speeds (beyond the paper)", "",
             f"`ringcontact study runup`: linear ramp {r['rpm'][0]:.0f} → {r['rpm'][-1]:.0f} rpm in "
             f"{r['t'][-1] - r['t'][0]:.1f} s ({info['accel_rpm_per_s']:.0f} rpm/s), Table 4 rotor, integrated in "
             f"{info['segments']} constant-speed segments with the rotation angle carried across (`rotor.studies.runup`); "
             f"{info['steps']} steps of {info['dt_s'] * 1e6:.1f} µs in {info['wall_s']:.0f} s wall. Cascade: Hann-window "
             "STFT of the y velocity, amplitude-corrected. Misalignment excitation read as "
             f"`{info.get('reading') or 'not recorded (a run before the record named it)'}` (section5-readings.md).",
             "", integrator_text([info]), ""]
    for ch, lab in LOCATIONS:
        tc, fr, A, rpm_c = stft_cascade(r, ch)
        one = np.array([A[i, np.argmin(np.abs(fr - rpm_c[i] / 60))] for i in range(len(tc))])
        k = np.argmax(one)
        lines.append(f"- {lab}: largest 1X {one[k] * 1e3:.3g} mm/s at {rpm_c[k]:.0f} rpm.")
    lines += ["", f"- First radial contact during the ramp: {first:.0f} rpm." if first is not None else
              "- No radial contact during the ramp.",
              f"- Contact during {100 * contact.mean():.1f} % of the run; end faces stuck "
              f"{100 * np.mean((r['modes'][:, 0] == 1) & (r['modes'][:, 1] == 1)):.1f} % of the time.", *_force_line(r),
              "",
              "Linear forward 1X critical speeds of this rotor (support locked, `rotor-table4.md`): 2 441, 4 271 and "
              "9 608 rpm. Compare with the steady-state cascade (`study-cascade.md`): in the ramp the harmonics and "
              "the broadband band appear at speeds close to, but not identical with, the steady-state ones, since "
              "a ramp passes through regimes with coexisting states in the order it meets them.", ""]
    return "\n".join(lines)


def _force_line(r: dict) -> list[str]:
    """The peak contact force of the ramp and its speed (a run stored before the run-up recorded the force: none)."""
    if "f_contact" not in r:
        return []
    force = np.hypot(r["f_contact"][:, 0], r["f_contact"][:, 1])
    k = int(np.argmax(force))
    if force[k] == 0:
        return ["- No contact force on the bearing during the ramp."]
    return [f"- Peak radial contact force on the bearing {force[k]:.4g} N at {r['rpm'][k]:.0f} rpm "
            f"(t = {r['t'][k]:.4g} s; mean {force[force > 0].mean():.4g} N while in contact)."]
