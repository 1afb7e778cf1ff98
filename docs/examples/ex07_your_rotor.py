"""Your own rotor, written from scratch in Python, with one bearing made loose

The rotor of Friswell, Penny, Garvey & Lees (2010), *Dynamics of Rotating Machines*, Example 5.9.1: a
1.5 m steel shaft of 50 mm diameter in six elements (E = 211 GPa, G = 81.2 GPa, ρ = 7810 kg/m³), two
70 mm wide disks keyed at 0.5 m (280 mm diameter) and 1.0 m (350 mm), bored to the shaft's 50 mm, and
two isotropic 1 MN/m bearings at its ends, undamped. Its whirl frequencies are the book's: 86.66,
274.31 and 716.78 rad/s (each twice) at rest; 85.39, 87.80, 251.78, 294.71 and 600.18 rad/s at
4 000 rpm.

Then the right bearing is made loose, as Dai et al. (2025) model an aero-engine bearing: its outer
ring sits in a support through a 20 µm radial clearance and is clamped axially by a nut (20 N per end
face, friction coefficient 0.1, the paper's conformal contact law); the support (5 kg) rests on the
bearing's 1 MN/m spring. Not in the book, and chosen here only to make the loose support work: an
unbalance of 1 000 g·mm on each disk and 1 000 N·s/m of damping in each bearing. The walkthrough
runs every analysis of ``import ringcontact`` on it (unbalance response, a time history, the
periodic orbit, a short branch of orbits and a small steady-state cascade) and prints the contact
force each one reports. Everything is SI, with the unit in each name.
"""
from __future__ import annotations

import dataclasses

import ringcontact as rc

E_PA, G_PA = 211e9, 81.2e9
BOOK_AT_REST_RAD_S = (86.66, 86.66, 274.31, 274.31, 716.78, 716.78)
BOOK_AT_4000_RPM_RAD_S = (85.39, 87.80, 251.78, 294.71, 600.18)
SPEED_RPM = 2500.0


def book_rotor() -> rc.Scene:
    """Friswell et al. (2010), Example 5.9.1, element by element (linear, undamped)."""
    steel = rc.Material("steel", density_kg_m3=7810.0, youngs_modulus_pa=E_PA, poisson_ratio=E_PA / (2 * G_PA) - 1)
    stations = tuple(rc.Station(f"N{i}", 0.25 * i) for i in range(7))
    shafts = tuple(rc.Shaft(f"N{i}", f"N{i + 1}", outer_diameter_m=0.05, inner_diameter_m=0.0, material=steel)
                   for i in range(6))
    disks = (rc.disk_from_geometry("disk1", "N2", steel, outer_diameter_m=0.28, inner_diameter_m=0.05, width_m=0.07),
             rc.disk_from_geometry("disk2", "N4", steel, outer_diameter_m=0.35, inner_diameter_m=0.05, width_m=0.07))
    bearings = (rc.Bearing("left", "N0", stiffness_n_m=1e6), rc.Bearing("right", "N6", stiffness_n_m=1e6))
    return rc.Scene(name="friswell-5-9-1", title="Friswell et al. (2010) Example 5.9.1", source="Friswell et al. 2010",
                    materials=(steel,), stations=stations, shafts=shafts, disks=disks, bearings=bearings,
                    analysis=rc.Analysis(modes=6)).checked()


def loose_rotor(book: rc.Scene) -> rc.Scene:
    """The book's rotor with unbalance, bearing damping, and the right bearing loose in its support."""
    rotor = book.replace(
        disks=tuple(dataclasses.replace(d, unbalance_kg_m=1e-3) for d in book.disks),
        bearings=tuple(dataclasses.replace(b, damping_n_s_m=1000.0) for b in book.bearings))
    return rotor.with_loose_bearing(
        "right", support_mass_kg=5.0, support_inertia_kg_m2=0.01, support_angular_stiffness_n_m_rad=1e4,
        clearance_m=20e-6, ring_width_m=0.02, bearing_modulus_pa=E_PA, bearing_poisson=0.3,
        support_modulus_pa=E_PA, support_poisson=0.3, friction_coefficient=0.1, preload_n=20.0,
        collision_factor_s_m=1.0, law="conformal")


def frequencies() -> dict:
    """The book rotor's whirl frequencies (rad/s) at rest and at 4 000 rpm."""
    book = book_rotor()
    return {0.0: rc.modes(book, 0.0), 4000.0: rc.modes(book, 4000.0)}


def analyses(scene: rc.Scene, full: bool = True) -> dict:
    """Every analysis of the loose rotor (``full`` False: the unbalance response and the time history only)."""
    out = {"unbalance": rc.unbalance_response(scene, [1000.0, 2000.0, SPEED_RPM, 3000.0, 4000.0]),
           "simulate": rc.simulate(scene, SPEED_RPM, revolutions=40)}
    if full:
        out["orbit"] = rc.orbit(scene, SPEED_RPM)
        out["branch"] = rc.branch(scene, SPEED_RPM, SPEED_RPM + 200.0, max_points=6)
        out["cascade"] = rc.cascade(scene, [SPEED_RPM, 4000.0], max_revs=300)
    return out


def main(full: bool = True) -> dict:
    for rpm, m in frequencies().items():
        print(f"book rotor at {rpm:g} rpm: " + ", ".join(f"{w:.2f}" for w in m.frequency_rad_s) + " rad/s")
    scene = loose_rotor(book_rotor())
    print("[loose_support] " + "; ".join(scene.to_toml().split("[loose_support]\n")[1].split("\n\n")[0].splitlines()))
    res = analyses(scene, full)
    u = res["unbalance"]
    print(f"unbalance response (loose support locked) at disk2: " + ", ".join(
        f"{s:g} rpm {a * 1e6:.1f} µm" for s, a in zip(u.speeds_rpm, u.semi_major_m[:, 1])))
    s = res["simulate"]
    print(f"simulate {SPEED_RPM:g} rpm, {s.duration_revs:g} rev from {s.start['kind']}: peak contact force {s.peak_contact_force_N:.1f} N, "
          f"in contact {s.contact_share:.0%} of the time, faces stuck {s.stick_share_right_face:.0%} / "
          f"{s.stick_share_left_face:.0%}")
    if not full:
        return res
    o, b, c = res["orbit"], res["branch"], res["cascade"]
    print(f"orbit {SPEED_RPM:g} rpm: period {o.period_revs} rev, {'converged' if o.converged else 'NOT converged'}, "
          f"{'stable' if o.stable else 'unstable'} (spectral radius {o.spectral_radius:.4f}), peak contact force "
          f"{o.peak_contact_force_N:.1f} N, in contact {o.contact_share:.0%} of the period")
    print(f"branch from {b.rpm_start:g} rpm: {len(b.speeds_rpm)} orbits to {b.speeds_rpm[-1]:.1f} rpm (stopped: "
          f"{b.stop}); peak contact force " + ", ".join(f"{f:.1f}" for f in b.peak_contact_force_N) + " N")
    print("cascade: " + "; ".join(
        f"{sp:g} rpm {'converged' if ok else 'NOT converged'} peak {f:.1f} N contact {share:.0%}"
        for sp, ok, f, share in zip(c.speeds_rpm, c.converged, c.peak_contact_force_N, c.contact_share)))
    return res


def gallery():
    """What the documentation page runs and shows (the fast part of :func:`main`, ``full=False``): the printed
    frequencies, unbalance response and time history, and a figure of the last two."""
    import matplotlib.pyplot as plt
    res = main(full=False)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
    res["unbalance"].plot(ax=ax1)
    res["simulate"].plot(ax=ax2)
    return fig


if __name__ == "__main__":
    main()
