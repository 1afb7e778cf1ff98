"""A short transient of the paper's rotor with its loose support

The Table 4 rotor of Dai et al. (2025) at point B (10 500 rpm), started at rest from the aligned
position (not from its misaligned static offset, so the bearing is thrown against its support) and
integrated for 12 revolutions by the compiled production scheme (Newmark average
acceleration with the stick/slip end faces and the conformal contact law; 256 steps a revolution,
the command line's default). The bearing hits its support within the first revolutions.

The test checks the energy balance of the run: input work minus viscous, friction and impact
losses equals the change of kinetic, strain, contact and coupling energy, to 1 % of the input work
(the bound the integrator verification ``tests/rotor/dynamics/test_dynamics_verification.py`` holds
the scheme to), and that contact, impact damping and stick and slip all happened.
Same as ``ringcontact simulate --speed-rpm 10500 --revolutions 12 --out DIR``.
"""
from __future__ import annotations

import math

import numpy as np

from rotor.dynamics import constraints as cons
from rotor.dynamics.build import system_from_model
from rotor.dynamics.energy import energy_balance
from rotor.dynamics.production import simulate_production
from rotor.model.assembly import assemble
from rotor.model.scene import load_scene

SPEED_RPM = 10500.0
REVOLUTIONS = 12
STEPS_PER_REV = 256


def run():
    """``(system, trajectory)`` of the run (every step recorded)."""
    scene = load_scene("paper-table4")
    omega = SPEED_RPM * math.pi / 30
    system = system_from_model(assemble(scene), scene, omega)
    dt = 2 * math.pi / omega / STEPS_PER_REV
    return system, simulate_production(system, dt, REVOLUTIONS * STEPS_PER_REV)


def main():
    """Print the run's summary; return the figure (edge offsets and contact force against time)."""
    import matplotlib.pyplot as plt
    system, tr = run()
    r1, r2 = cons.edge_offsets(tr.u, system.support.width_m)
    clearance = system.support.law.clearance_m
    eb = energy_balance(system, tr)
    print(f"{tr.t.size - 1} steps over {tr.t[-1] * 1e3:.1f} ms ({tr.scheme} scheme)")
    print(f"largest edge offset {max(r1.max(), r2.max()) * 1e3:.4f} mm against a clearance of {clearance * 1e3:g} mm; "
          f"in contact {np.mean((r1 > clearance) | (r2 > clearance)):.0%} of the time")
    print(f"right / left face stuck {tr.modes[:, 0].mean():.0%} / {tr.modes[:, 1].mean():.0%} of the time")
    print(f"largest contact force {np.hypot(tr.f_contact[:, 0], tr.f_contact[:, 1]).max() / 1e3:.1f} kN")
    print(f"energy (J): input {eb.input[-1]:.4g}, viscous {eb.damping[-1]:.4g}, friction {eb.friction[-1]:.4g}, "
          f"impact {eb.impact[-1]:.4g}; balance closes to {eb.relative_closure():.1e} of the input work")
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 4.8), sharex=True, layout="constrained")
    ms = tr.t * 1e3
    ax1.plot(ms, r1 * 1e3, lw=0.8, label="edge 1 offset r1")
    ax1.plot(ms, r2 * 1e3, lw=0.8, label="edge 2 offset r2")
    ax1.axhline(clearance * 1e3, color="k", ls="--", lw=0.8, label="clearance δ0")
    ax1.set(ylabel="offset (mm)", title=f"paper-table4 at {SPEED_RPM:g} rpm, from rest")
    ax1.legend(loc="lower right", fontsize=8)
    ax2.plot(ms, np.hypot(tr.f_contact[:, 0], tr.f_contact[:, 1]) / 1e3, lw=0.8)
    ax2.set(xlabel="time (ms)", ylabel="contact force (kN)")
    return fig


if __name__ == "__main__":
    main()
