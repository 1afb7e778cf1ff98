"""Linear rotor: modes, Campbell diagram and critical speeds of a bundled scene

Two bundled scenes (``rotor/scenes/``), loose support locked (bearing and support move together):

* ``verify-jeffcott``: a central disk on a massless shaft in two flexible bearings, whose 1X critical
  speed is Jeffcott's (1919) ``ω_c = √(k/m)`` with ``1/k = L³/(48EI) + L/(4κGA) + 1/(2k_b)``
  (1 137.3 rpm, the scene file's header);
* ``paper-table4``: the paper's rotor (Dai et al. 2025, Table 4) on its own mesh, one element per
  shaft segment, with the whirl frequencies over the speed range (the Campbell diagram) and the
  forward 1X critical speeds, committed in ``reports/published/rotor-mesh.md`` (2 441.4, 4 270.5 and
  9 608.2 rpm on this mesh).

Same as ``ringcontact rotor critical-speeds paper-table4`` and ``ringcontact rotor campbell ...``.
"""
from __future__ import annotations

import math

import numpy as np

from rotor.linear.modes import campbell, critical_speeds, modes
from rotor.model.assembly import assemble
from rotor.model.scene import load_scene

RPM = 30 / math.pi       # rad/s -> rpm


def forward_criticals_rpm(scene_name: str, max_rpm: float) -> list[float]:
    """Forward 1X critical speeds (rpm) of a bundled scene below ``max_rpm``."""
    model = assemble(load_scene(scene_name))
    found = critical_speeds(model, max_rpm / RPM, orders=(1,), families=("forward",), n_modes=8)
    return [c.speed_rad_s * RPM for c in found]


def main():
    """Print the frequencies and critical speeds; return the Campbell diagram of the Table 4 rotor."""
    import matplotlib.pyplot as plt
    print("verify-jeffcott forward 1X critical speed: "
          + ", ".join(f"{s:.1f} rpm" for s in forward_criticals_rpm("verify-jeffcott", 3000)))
    scene = load_scene("paper-table4")
    model = assemble(scene)
    rest = modes(model, 0.0, n_modes=6)
    print("paper-table4 natural frequencies at rest (Hz):", np.round(rest.frequency_hz, 2))
    speeds = np.linspace(0, 18000, 7) / RPM
    cd = campbell(model, speeds, n_modes=6)
    print("Campbell diagram, whirl frequencies (Hz) per speed:")
    for w, row in zip(speeds, cd.frequency_hz):
        print(f"  {w * RPM:7.0f} rpm: " + " ".join(f"{f:7.1f}" for f in row))
    print("paper-table4 forward 1X critical speeds: "
          + ", ".join(f"{s:.1f} rpm" for s in forward_criticals_rpm("paper-table4", 18000)))
    fine = np.linspace(0, 18000, 37) / RPM
    cf = campbell(model, fine, n_modes=6)
    fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
    for label, color in (("forward", "C0"), ("backward", "C3"), ("mixed", "0.5")):
        i, j = np.nonzero(np.array(cf.whirl) == label)
        if i.size:
            ax.plot(fine[i] * RPM, cf.frequency_hz[i, j], ".", color=color, label=f"{label} whirl")
    ax.plot(fine * RPM, fine * RPM / 60, "k--", label="1X")
    ax.set(xlabel="speed (rpm)", ylabel="whirl frequency (Hz)", title="Campbell diagram, paper-table4 (six lowest whirl frequencies)",
           ylim=(0, 1.1 * cf.frequency_hz.max()))
    ax.legend()
    return fig


if __name__ == "__main__":
    main()
