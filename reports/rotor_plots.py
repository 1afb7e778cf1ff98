"""Figures of the linear rotor analyses (matplotlib, written as PNG and SVG through atomic writes)."""
from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np

from contact.files import atomic_write_bytes
from rotor.linear.modes import Campbell, CriticalSpeed, Modes
from rotor.model.assembly import RotorModel
from rotor.linear.unbalance import ForcedResponse

RPM = 30 / math.pi


def _figure(width=7.0, height=4.5):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt.subplots(figsize=(width, height))


def save(fig, prefix: str | Path) -> list[Path]:
    """Write ``prefix.png`` and ``prefix.svg`` atomically; close the figure."""
    import matplotlib.pyplot as plt
    out = []
    for ext in ("png", "svg"):
        buf = io.BytesIO()
        fig.savefig(buf, format=ext, dpi=150, bbox_inches="tight", metadata={"Date": None} if ext == "svg" else None)
        out.append(atomic_write_bytes(f"{prefix}.{ext}", buf.getvalue()))
    plt.close(fig)
    return out


def _on(ax):
    """``(figure, axes)``: a new figure, or the figure of the given matplotlib Axes ``ax``."""
    return _figure() if ax is None else (ax.figure, ax)


def campbell_figure(camp: Campbell, title: str, crit: list[CriticalSpeed] = (), orders=(1, 2), ax=None):
    """Campbell diagram: forward whirl solid/red, backward dashed/blue, 1X/2X lines, critical speeds
    (on ``ax`` when given, else a new figure)."""
    fig, ax = _on(ax)
    rpm = camp.speeds_rad_s * RPM
    for fam, style, color in (("forward", "-", "tab:red"), ("backward", "--", "tab:blue")):
        # k-th lowest mode of the family as one line
        per_speed = [[f for f, lab in zip(camp.frequency_hz[i], camp.whirl[i]) if lab == fam]
                     for i in range(len(rpm))]
        kmax = max((len(p) for p in per_speed), default=0)
        for k in range(kmax):
            y = np.array([p[k] if len(p) > k else np.nan for p in per_speed])
            ax.plot(rpm, y, style, color=color, lw=1.4, label=f"{fam} whirl" if k == 0 else None)
    for n in orders:
        ax.plot(rpm, n * camp.speeds_rad_s / (2 * math.pi), ":", color="k", lw=1.0)
        ax.annotate(f"{n}X", (rpm[-1], n * camp.speeds_rad_s[-1] / (2 * math.pi)), fontsize=8,
                    xytext=(2, 0), textcoords="offset points")
    for c in crit:
        ax.plot(c.speed_rpm, c.frequency_hz, "o", mfc="none", color="k", ms=6)
    top = np.nanmax(camp.frequency_hz)
    ax.set_ylim(0, min(top, 1.1 * max(orders) * camp.speeds_rad_s[-1] / (2 * math.pi)) * 1.05)
    ax.set_xlim(0, rpm[-1])
    ax.set_xlabel("rotor speed (rpm)")
    ax.set_ylabel("whirl frequency (Hz)")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    return fig


def response_figure(model: RotorModel, resp: ForcedResponse, nodes: list[str], title: str, ax=None):
    """Semi-major axis of the orbit (µm) against speed (rpm), log scale (on ``ax`` when given)."""
    fig, ax = _on(ax)
    rpm = resp.speeds_rad_s * RPM
    for node in nodes:
        major, _ = resp.orbit(model, node)
        ax.semilogy(rpm, major * 1e6, lw=1.4, label=node)
    ax.set_xlabel("rotor speed (rpm)")
    ax.set_ylabel(f"{resp.order}X orbit semi-major axis (µm)")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    return fig


def mode_shape_figure(model: RotorModel, shapes: list[tuple[str, Modes, int]], title: str, ax=None):
    """Orbit semi-major axis ``(|ŷ + iẑ| + |ŷ − iẑ|)/2`` along the rotor for selected modes (normalised
    to 1), so forward and backward whirl show alike; a DOF fixed by a boundary condition shows as 0
    (on ``ax`` when given)."""
    fig, ax = _on(ax)
    stations = list(model.node_names)
    xs = np.array([model.node_x_m[model.node_names.index(n)] for n in stations])
    support = model.loose_pair.support_node if model.loose_pair else None
    free = set(model.dof_names)

    def lateral(m, j, n, d):
        return m.shapes[model.dof_index(f"{n}.{d}"), j] if f"{n}.{d}" in free else 0.0

    for label, m, j in shapes:
        Y = np.array([lateral(m, j, n, "y") for n in stations])
        Z = np.array([lateral(m, j, n, "z") for n in stations])
        rotor = [i for i, n in enumerate(stations) if n != support]
        order = sorted(rotor, key=lambda i: xs[i])
        amp = (np.abs(Y + 1j * Z) + np.abs(Y - 1j * Z)) / 2
        amp = amp / amp.max()
        ax.plot(xs[order] * 1e3, amp[order], "-o", ms=3, label=label)
    for d in model.scene.disks:
        ax.axvline(model.scene.station(d.station).x_m * 1e3, color="0.6", lw=0.8)
        ax.annotate(d.name, (model.scene.station(d.station).x_m * 1e3, 1.02), fontsize=8, ha="center")
    ax.set_xlabel("axial position x (mm)")
    ax.set_ylabel("orbit semi-major axis (normalised)")
    ax.set_title(title, fontsize=10)
    ax.set_ylim(0, 1.1)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig
