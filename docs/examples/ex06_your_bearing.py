"""Your bearing: a ring-pair file to a verified law, and that law in a rotor

An engineer's own ring pair, written as a ring-pair file (``docs/ring-scenes.rst``): a bearing-steel
outer ring 48/55 mm, 22 mm wide, in an aluminium housing to 75 mm with a 0.03 mm radial clearance,
held on its outer surface, driven through its inner surface; here straight only (``tilt_arcmin =
[0, 0]``), so the job does the 2D reference, the calibration with held-out points, the accuracy report
and the law file (``ringcontact bearing my-bearing.toml`` does the same from the command line, with
the 3D tilt sweep too when the range asks for tilt). The law file is then named by a rotor scene:
the Table 4 rotor of Dai et al. (2025) with this bearing at its loose support, whose clearance, width
and materials come from the law, run for a few revolutions at 6 000 rpm.

The test checks the law against its own FEM points (held out) within the job's bound, that the rotor
took the law's geometry, and that the bearing hit its support.
"""
from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np

from fem_reference.ring_scene import loads
from reports.bearing.pipeline import run

MY_BEARING = """
schema = "ringcontact.ring-scene/1"
name = "my-bearing"
plane = "stress"
[bearing_ring]
inner_radius_mm = 48.0
outer_radius_mm = 55.0
width_mm = 22.0
youngs_modulus_gpa = 208.0
poisson_ratio = 0.29
[housing]
radial_clearance_mm = 0.03
outer_radius_mm = 75.0
youngs_modulus_gpa = 72.0
poisson_ratio = 0.33
hold = "clamped-outer"
[drive]
bearing = "rigid-inner"
[range]
penetration_mm = [0.004, 0.04]
tilt_arcmin = [0, 0]
penetration_points_mm = [0.004, 0.007, 0.012, 0.02, 0.03, 0.04]
"""


def law_for_my_bearing(out: Path) -> dict:
    """Run every stage into ``out``; the job's summary (law file name, checks, warnings)."""
    return run(loads(MY_BEARING, "my-bearing.toml"), out, workers=1, progress=False, log=lambda msg: None)


def rotor_with_my_bearing(out: Path, speed_rpm: float = 6000.0, revolutions: int = 40):
    """The Table 4 rotor with ``out``'s law file at its loose support: ``(scene, system, trajectory)``."""
    from contact.package_data import shipped
    from rotor.dynamics.build import system_from_model
    from rotor.dynamics.production import simulate_production
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene

    text = shipped("rotor", "scenes", "table4-steel-in-aluminium.toml").read_text(encoding="utf-8")
    text = text.replace('law = "laws/steel-in-aluminium-law.json"', f'law = "{out / "my-bearing-law.json"}"').replace(
        'name = "table4-steel-in-aluminium"', 'name = "table4-my-bearing"')
    (out / "rotor.toml").write_text(text, encoding="utf-8")
    scene = load_scene(out / "rotor.toml")
    omega = speed_rpm * math.pi / 30
    system = system_from_model(assemble(scene), scene, omega)
    return scene, system, simulate_production(system, 2 * math.pi / omega / 256, revolutions * 256)


def main():
    """Print the law and the rotor run; return the figure (contact force against time in the rotor)."""
    import matplotlib.pyplot as plt

    from rotor.dynamics import constraints as cons

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        summary = law_for_my_bearing(out)
        print(f"law {summary['law_name']} ({summary['family']}): {summary['parameters']}")
        print(f"valid for {summary['validity_penetration_mm'][0]:g} ... {summary['validity_penetration_mm'][1]:g} mm; "
              f"held out {100 * summary['checks']['holdout_max_rel_2d']:.2f} % at most; warnings: {summary['warnings']}")
        scene, system, tr = rotor_with_my_bearing(out)
        r1, r2 = cons.edge_offsets(tr.u, system.support.width_m)
        d0 = system.support.law.clearance_m
        print(f"rotor {scene.name!r} with {scene.loose_support.calibrated.name}: clearance {d0 * 1e3:g} mm, "
              f"in contact {np.mean((r1 > d0) | (r2 > d0)):.0%} of the time, largest contact force "
              f"{np.hypot(tr.f_contact[:, 0], tr.f_contact[:, 1]).max() / 1e3:.2f} kN")
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6), layout="constrained")
        pen = np.linspace(*summary["validity_penetration_mm"], 40) * 1e-3
        law = scene.loose_support.calibrated
        ax1.plot(pen * 1e3, law.force(pen).force_N / 1e3)
        ax1.set(xlabel="penetration Δr (mm)", ylabel="contact force (kN)", title=f"law {summary['law_name']}")
        ax2.plot(tr.t * 1e3, np.hypot(tr.f_contact[:, 0], tr.f_contact[:, 1]) / 1e3, lw=0.8)
        ax2.set(xlabel="time (ms)", ylabel="contact force (kN)", title=f"{scene.name} at 6000 rpm")
    return fig


if __name__ == "__main__":
    main()
