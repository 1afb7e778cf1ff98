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


def _signed_shape(model: RotorModel, shapes, j: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(x, w, slope, direction)`` of mode ``j``: each node's deflection (x m, w normalised to a largest
    |w| of +1) and slope along the major axis of the largest orbit, at the instant that orbit is at its
    major axis; a fixed DOF counts as 0. The sign shows the nodal points a magnitude plot hides."""
    names = list(model.node_names)

    def dof(n, d):
        key = f"{n}.{d}"
        return shapes[model.dof_index(key), j] if key in model.dof_names else 0.0

    Y, Z, TY, TZ = (np.array([dof(n, d) for n in names]) for d in ("y", "z", "θy", "θz"))
    k = _first_largest(np.abs(Y) ** 2 + np.abs(Z) ** 2)
    # phase that puts node k at the major axis of its ellipse: maximise |Re(e^{iφ}(Y_k, Z_k))|
    phi = -0.5 * np.angle(Y[k] ** 2 + Z[k] ** 2)
    u = np.array([np.real(np.exp(1j * phi) * Y[k]), np.real(np.exp(1j * phi) * Z[k])])
    u = u / (np.linalg.norm(u) or 1.0)
    rot = np.exp(1j * phi)
    w = np.real(rot * (u[0] * Y + u[1] * Z))
    slope = np.real(rot * (u[0] * TZ - u[1] * TY))          # θz = dy/dx, θy = −dz/dx
    scale = w[_first_largest(np.abs(w))] or 1.0
    return model.node_x_m, w / scale, slope / scale, u


def _first_largest(values: np.ndarray, rel: float = 1e-6) -> int:
    """Index of the first node (in the model's node order) whose value is within ``rel`` of the largest.

    The sign convention of a drawn mode: +1 at its largest deflection, and where several nodes tie (the two
    equal extrema of sin(2πx/L) on a pinned beam) at the first of them. ``np.argmax`` alone picks between tied
    extrema by round-off, so the drawn sign would depend on the machine."""
    v = np.asarray(values, float)
    return int(np.flatnonzero(v >= (1.0 - rel) * v.max())[0]) if v.size and v.max() > 0 else 0


def _hermite(x0, x1, w0, w1, s0, s1, n: int = 12):
    """Cubic through ``(x0, w0, slope s0)`` and ``(x1, w1, s1)``: the beam element's own interpolation."""
    t = np.linspace(0.0, 1.0, n)
    h = x1 - x0
    return x0 + h * t, ((2 * t ** 3 - 3 * t ** 2 + 1) * w0 + (t ** 3 - 2 * t ** 2 + t) * h * s0
                        + (-2 * t ** 3 + 3 * t ** 2) * w1 + (t ** 3 - t ** 2) * h * s1)


def mode_shape_figure(model: RotorModel, shapes: list[tuple[str, Modes, int]], title: str, ax=None):
    """Mode shapes with their sign: each mode's deflection along the major axis of its largest orbit, at the
    instant that orbit is at its major axis, normalised to +1 at the largest (``_signed_shape``), drawn
    through each shaft with the beam element's cubic interpolation between the nodes (nodes marked); a
    DOF fixed by a boundary condition is drawn at 0 (on ``ax`` when given)."""
    fig, ax = _on(ax)
    index = {n: i for i, n in enumerate(model.node_names)}
    for c, (label, m, j) in enumerate(shapes):
        x, w, slope, _ = _signed_shape(model, m.shapes, j)
        for s_i, chain in enumerate(model.shaft_nodes):
            ids = [index[n] for n in chain]
            xs, ws = [], []
            for a, b in zip(ids[:-1], ids[1:]):
                xx, ww = _hermite(x[a], x[b], w[a], w[b], slope[a], slope[b])
                xs.append(xx if not xs else xx[1:])
                ws.append(ww if not ws else ww[1:])
            ax.plot(np.concatenate(xs) * 1e3, np.concatenate(ws), "-", color=f"C{c % 10}",
                    label=label if s_i == 0 else None)
            ax.plot(x[ids] * 1e3, w[ids], "o", ms=3, color=f"C{c % 10}")
    for d in model.scene.disks:
        ax.axvline(model.scene.station(d.station).x_m * 1e3, color="0.6", lw=0.8)
        ax.annotate(d.name, (model.scene.station(d.station).x_m * 1e3, 1.04), fontsize=8, ha="center")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel("axial position x (mm)")
    ax.set_ylabel("deflection along the major axis (normalised)")
    ax.set_title(title, fontsize=10)
    ax.set_ylim(-1.15, 1.15)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig
