"""ringcontact analyses of a loose support: the numbers of the jobs for the same input, a stuck ring's orbit
against the linear response, and the contact-force summary in every result.

The rotor is the Jeffcott verification rotor (rotor/scenes/verify-jeffcott.toml) with a steel shaft (the
contact step limit, rotor.dynamics.system.largest_stable_step, needs mass at every DOF: a massless shaft makes
it fail on a singular mass matrix), 200 N·s/m in each bearing and its bearing ``bB`` made loose (a 1 kg support
on the bearing's 2e6 N/m, 20 µm clearance).
"""
from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

import ringcontact as rc
from reports.cli import main as cli

UNBALANCE_KG_M = 5e-3          # 5 000 g·mm: enough to throw the ring across its clearance within a few revolutions


def _loose_jeffcott(*, preload_n: float, mu: float) -> rc.Scene:
    s = rc.load_scene("verify-jeffcott")
    steel = rc.Material("steel", density_kg_m3=7800.0, youngs_modulus_pa=200e9, poisson_ratio=0.3)
    s = s.replace(materials=(steel,), shafts=tuple(dataclasses.replace(sh, material=steel) for sh in s.shafts),
                  bearings=tuple(dataclasses.replace(b, damping_n_s_m=200.0) for b in s.bearings),
                  disks=tuple(dataclasses.replace(d, unbalance_kg_m=UNBALANCE_KG_M) for d in s.disks))
    return s.with_loose_bearing("bB", support_mass_kg=1.0, support_inertia_kg_m2=1e-3,
                                support_angular_stiffness_n_m_rad=1e3, clearance_m=20e-6, ring_width_m=0.02,
                                bearing_modulus_pa=208e9, bearing_poisson=0.3, support_modulus_pa=208e9,
                                support_poisson=0.3, friction_coefficient=mu, preload_n=preload_n,
                                collision_factor_s_m=1.0)


@pytest.fixture(scope="module")
def slipping():
    return _loose_jeffcott(preload_n=20.0, mu=0.1)


@pytest.fixture(scope="module")
def stuck():
    """μN = 3 kN a face against a few hundred newtons of bearing load: the ring never slips."""
    return _loose_jeffcott(preload_n=1e4, mu=0.3)


def test_simulate_gives_the_numbers_of_ringcontact_simulate(slipping, tmp_path):
    r = rc.simulate(slipping, 1500.0, revolutions=4)
    path = slipping.save(tmp_path / "loose.toml")
    assert cli(["simulate", "--scene", str(path), "--speed-rpm", "1500", "--revolutions", "4",
                "--out", str(tmp_path / "run")]) == 0
    d = json.loads((tmp_path / "run" / "simulate-summary.json").read_text())
    for key in ("peak_contact_force_N", "mean_contact_force_N", "contact_share", "stick_share_right_face",
                "stick_share_left_face", "peak_face_force_N"):
        assert r.contact[key] == d[key], key
    assert (r.peak_contact_force_N, r.contact_share, r.steps_per_rev) == (d["peak_contact_force_N"],
                                                                          d["contact_share"], d["steps_per_rev"])
    assert r.peak_contact_force_N > 0 and 0 < r.contact_share < 1          # the ring hit its support
    assert r.peak_contact_force_N == pytest.approx(r.contact_force_N.max(), rel=0)
    assert np.all(np.isfinite(r.displacement_m)) and r.channels == ("d.y", "d.z", "B.y", "B.z", "support.y", "support.z")
    ax = r.plot()
    assert ax.get_lines()[0].get_ydata().max() == pytest.approx(r.peak_contact_force_N)
    back = rc.load_result(r.save(tmp_path / "sim.npz"))
    assert np.array_equal(back["contact_force_N"], r.contact_force_N)
    header, *rows = r.to_csv(tmp_path / "sim.csv").read_text().splitlines()
    assert header.split(",")[:2] == ["t_s", "d.y_m"] and "contact_force_N" in header and len(rows) == len(r.t_s)
    import matplotlib.pyplot as plt
    plt.close("all")


def test_a_stuck_rings_orbit_is_the_linear_unbalance_response(stuck):
    """Both end faces stuck all period: the loose support is the locked one of the linear model, so the orbit's
    1X velocity amplitude at the disk is ω times the linear unbalance response (to Newmark's amplitude error,
    of order (ω Δt)² / 12 = 5e-5 at 256 steps a revolution); no contact, no higher harmonics."""
    o = rc.orbit(stuck, 1500.0)
    assert o.converged and o.period_revs == 1 and o.stable
    assert (o.contact_share, o.stick_share_right_face, o.stick_share_left_face) == (0.0, 1.0, 1.0)
    assert o.peak_contact_force_N == 0.0
    u = rc.unbalance_response(stuck, [1500.0], stations=["d"])
    w = 1500.0 * math.pi / 30
    d = o.channels.index("d.y")
    assert o.velocity_amplitude_m_s[d, 0] == pytest.approx(w * u.amplitude_y_m[0, 0], rel=1e-3)
    assert o.velocity_amplitude_m_s[d, 1:].max() < 1e-6 * o.velocity_amplitude_m_s[d, 0]
    assert o.to_dict()["contact"]["contact_share"] == 0.0
    assert o.unique is False               # both faces stuck: one member of a family held by friction (neutral multipliers)


OPTIONS = {"clearance_m", "misalignment_m", "mu", "preload_n", "tilt_ignored", "elements"}


def test_every_analysis_of_the_loose_rotor_takes_the_same_options(slipping):
    """The same loose-support overrides for simulate, orbit, branch and cascade, and they reach the rotor: with the
    scene's 20 N preload the ring slips and hits (above), with 10 kN and μ 0.3 given to simulate it stays stuck."""
    import inspect
    for f in (rc.simulate, rc.orbit, rc.branch, rc.cascade):
        assert OPTIONS <= set(inspect.signature(f).parameters), f.__name__
    r = rc.simulate(slipping, 1500.0, revolutions=4, preload_n=1e4, mu=0.3)
    assert (r.contact_share, r.stick_share_right_face, r.stick_share_left_face) == (0.0, 1.0, 1.0)
    pereira = slipping.with_law("pereira")
    assert pereira.loose_support.law == "pereira" and pereira.loose_support.clearance_m == 20e-6


@pytest.mark.slow
def test_branch_and_cascade_of_a_stuck_ring(stuck, tmp_path):
    """A stuck ring stays linear along the branch and in the cascade: no contact, both faces stuck; the cascade
    marks a speed whose transient did not settle within ``max_revs`` (here 60 revolutions) on its figure and in
    its table. About 40 s: the contact step limit asks for some 9 000 steps a revolution on this rotor."""
    b = rc.branch(stuck, 1500.0, 1600.0, max_points=8)
    assert len(b.speeds_rpm) >= 2 and np.all(b.contact_share == 0) and np.all(b.stick_share_right_face == 1)
    assert not b.unique.any()
    assert b.plot().get_xlabel() == "rotor speed (rpm)"
    c = rc.cascade(stuck, [1500.0], max_revs=60)
    assert c.transient_revs.tolist() == [60] and not c.converged[0]
    assert (c.contact_share[0], c.stick_share_right_face[0], c.regime) == (0.0, 1.0, ("stick",))
    ax = c.plot()
    assert [ln.get_label() for ln in ax.get_lines()][-1] == "not converged"
    assert rc.load_result(c.save(tmp_path / "cascade.json"))["converged"] == [False]
    assert c.rows()[0]["converged"] is False
    ds = c.to_xarray()
    assert dict(ds.sizes) == {"speed_rpm": 1, "order": 5, "channel": len(c.channels)}
    assert np.array_equal(ds["velocity_amplitude_m_s"].values, c.velocity_amplitude_m_s)
    import matplotlib.pyplot as plt
    plt.close("all")


def test_simulate_steady_gives_the_numbers_of_simulate_steady(tmp_path):
    """``simulate(..., steady=True)`` is ``ringcontact simulate --steady``: the same detected transient, the same
    kept record (whole periods) and contact summary. At the paper's point B (10 500 rpm, Dai et al. 2025 §5.1) the
    ring hits its support part of each revolution (section5-readings.md: 56 % contact on the paper's mesh), and
    the kept record repeats itself from one revolution to the next (the detector found period 1)."""
    r = rc.simulate("paper-table4", 10500.0, revolutions=3, steady=True)
    assert cli(["simulate", "--scene", "paper-table4", "--speed-rpm", "10500", "--revolutions", "3", "--steady",
                "--out", str(tmp_path / "run")]) == 0
    d = json.loads((tmp_path / "run" / "simulate-summary.json").read_text())
    assert r.steady_state["converged"] and d["steady_converged"]
    assert (r.steady_state["transient_revs"], r.steady_state["period_revs"], r.duration_revs) == (
        d["transient_revs"], d["period_revs"], d["record_revs"])
    for key in ("peak_contact_force_N", "mean_contact_force_N", "contact_share", "stick_share_right_face"):
        assert r.contact[key] == d[key], key
    assert 0.05 < r.contact_share < 0.95                      # contact and separation in each revolution
    per_rev = (len(r.t_s) - 1) // int(r.duration_revs)
    x = r.displacement_m
    assert np.max(np.abs(x[per_rev:] - x[:-per_rev])) < 1e-3 * np.ptp(x)
    assert r.to_dict()["steady_state"]["period_revs"] == 1
    plain = rc.simulate("paper-table4", 10500.0, revolutions=3)
    assert plain.steady_state is None


def test_simulate_steady_refuses_a_record_that_cannot_resolve_5x():
    """The detector resolves 1X-5X (rotor.studies.steady_state.SAMPLES_FOR_5X); a plain run has no such need."""
    with pytest.raises(rc.InputError, match="record_per_rev >= 12"):
        rc.simulate("paper-table4", 10500.0, revolutions=3, steady=True, record_per_rev=4)
    for bad in (float("nan"), -1, 2.5):
        with pytest.raises(rc.InputError, match="record_per_rev"):
            rc.simulate("paper-table4", 4500.0, revolutions=2, record_per_rev=bad)
    r = rc.simulate("paper-table4", 4500.0, revolutions=2, record_per_rev=4)     # a plain run may sample coarsely
    assert len(r.t_s) == 9 and r.steady_state is None
