"""Gravity and static loads, anisotropic and cross-coupled bearings, disks from geometry.

Expected values: closed forms named in each test (Euler–Bernoulli and Timoshenko beams under their
own weight; rigid rotors on anisotropic and cross-coupled springs), and the published frequencies of
Friswell, Penny, Garvey & Lees (2010), Dynamics of Rotating Machines, Example 5.9.1.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from contact.errors import InputError
from rotor.linear.modes import modes
from rotor.linear.static import static_deflection
from rotor.model import elements as el
from rotor.model.assembly import assemble
from rotor.model.scene import loads_scene
from rotor.model.static_load import static_load

HEAD = 'schema = "ringcontact.rotor-scene/1"\nname = "t"\ntitle = "t"\n'
STEEL = ('[[materials]]\nname = "steel"\ndensity_kg_m3 = 7810\nyoungs_modulus_gpa = 211\npoisson_ratio = 0.3\n'
         '[[materials]]\nname = "rigid"\ndensity_kg_m3 = 0\nyoungs_modulus_gpa = 1000\npoisson_ratio = 0.3\n')


def _stations(*xs_mm):
    return "".join(f'[[stations]]\nname = "s{i}"\nx_mm = {x}\n' for i, x in enumerate(xs_mm))


def _shaft(a, b, d_mm, material="steel", elements=1):
    return (f'[[shafts]]\nfrom = "{a}"\nto = "{b}"\nouter_diameter_mm = {d_mm}\nmaterial = "{material}"\n'
            f'elements = {elements}\n')


def _pinned_beam(extra: str = "", elements: int = 8) -> str:
    return (HEAD + STEEL + _stations(0, 1000) + _shaft("s0", "s1", 50, elements=elements)
            + '[[boundaries]]\nstation = "s0"\nfixed = ["y", "z"]\n[[boundaries]]\nstation = "s1"\nfixed = ["y", "z"]\n'
            + extra)


def _midspan(model, st) -> float:
    x = model.node_x_m
    i = int(np.argmin(abs(x - 0.5)))
    return st.displacement_m(model.node_names[i])[0]


def test_beam_under_own_weight_euler_bernoulli_exact():
    """Pinned–pinned uniform beam under its weight w: midspan deflection 5 w L⁴ / (384 E I) (Timoshenko &
    Gere 1961); cubic elements with the consistent load are nodally exact, so 1e-10 holds; the load
    adds up to the beam's weight ρ A L g, fixed ends included."""
    g = 9.81
    s = loads_scene(_pinned_beam(f"[gravity]\nacceleration_y_m_per_s2 = {-g}\n"))
    m = assemble(s, shear=False, rotary_inertia=False)
    st = static_deflection(m)
    E, d, L = 211e9, 0.05, 1.0
    A, I = math.pi * d * d / 4, math.pi * d ** 4 / 64
    w = 7810 * A * g
    assert _midspan(m, st) == pytest.approx(-5 * w * L ** 4 / (384 * E * I), rel=1e-10)
    assert m.unit_acceleration_load[:, 0].sum() + 2 * w / g * L / 16 == pytest.approx(7810 * A * L, rel=1e-12)
    assert st.displacement_m("s0") == (0.0, 0.0)


def test_beam_under_own_weight_with_shear():
    """Timoshenko beam: midspan deflection 5wL⁴/(384EI) + wL²/(8κGA) (Timoshenko & Gere 1961, shear term of a
    uniformly loaded simply supported beam), κ the element's Cowper (1966) coefficient; to 1e-6."""
    g = 9.81
    s = loads_scene(_pinned_beam(f"[gravity]\nacceleration_z_m_per_s2 = {g}\n", elements=16))
    m = assemble(s)
    st = static_deflection(m)
    E, nu, d, L = 211e9, 0.3, 0.05, 1.0
    A, I = math.pi * d * d / 4, math.pi * d ** 4 / 64
    kappa = el.cowper_shear_coefficient(d, 0.0, nu)
    w = 7810 * A * g
    exact = 5 * w * L ** 4 / (384 * E * I) + w * L ** 2 / (8 * kappa * E / (2 * (1 + nu)) * A)
    i = int(np.argmin(abs(m.node_x_m - 0.5)))
    assert st.displacement_m(m.node_names[i])[1] == pytest.approx(exact, rel=1e-6)
    assert st.displacement_m(m.node_names[i])[0] == 0.0


def _rigid_rotor(bearings: str, extra: str = "") -> str:
    """A rigid, massless shaft (E 1000 GPa, d 300 mm over 200 mm: 1e-6 of the bearing flexibility) with a
    10 kg disk at midspan (Id 0.05 kg·m², Ip 0) on two bearings 200 mm apart."""
    return (HEAD + STEEL + _stations(0, 100, 200) + _shaft("s0", "s1", 300, "rigid") + _shaft("s1", "s2", 300, "rigid")
            + '[[disks]]\nname = "d"\nstation = "s1"\nmass_kg = 10\npolar_inertia_kg_m2 = 0\n'
              'diametral_inertia_kg_m2 = 0.05\n' + bearings + extra)


def _bearing(name, station, **keys):
    return f'[[bearings]]\nname = "{name}"\nstation = "{station}"\n' + "".join(f"{k} = {v}\n" for k, v in keys.items())


def test_static_load_reactions_and_point_loads():
    """A 100 N load and gravity on the rigid rotor: each bearing carries half of (load + weight) by symmetry,
    the deflection is that reaction over its stiffness (statics of a rigid beam on two springs)."""
    k = 1e6
    extra = ('[[static_loads]]\nname = "gear"\nstation = "s1"\nforce_y_n = -100\n'
             '[gravity]\nacceleration_y_m_per_s2 = -9.81\n')
    s = loads_scene(_rigid_rotor(_bearing("b0", "s0", stiffness_n_per_m=k) + _bearing("b2", "s2", stiffness_n_per_m=k),
                                 extra))
    m = assemble(s)
    st = static_deflection(m)
    half = (100 + 10 * 9.81) / 2
    for b in ("b0", "b2"):
        assert st.reactions_N[b][0] == pytest.approx(-half, rel=1e-5)
        assert st.reactions_N[b][1] == pytest.approx(0.0, abs=1e-9)
    assert st.displacement_m("s1")[0] == pytest.approx(-half / k, rel=1e-5)
    assert static_load(m).sum() == pytest.approx(-(100 + 10 * 9.81), rel=1e-12)


def test_anisotropic_bearings_rigid_rotor_frequencies():
    """Rigid rotor (mass m, diametral inertia Id, bearings at ±a) on bearings k_yy ≠ k_zz, at rest:
    bounce sqrt(2k/m) and rock sqrt(2k a²/Id) in each plane (rigid-body closed form), to 1e-5."""
    kyy, kzz = 1.0e6, 0.8e6            # Friswell et al. (2010) Example 5.9.2's bearing stiffnesses
    b = "".join(_bearing(n, st, stiffness_yy_n_per_m=kyy, stiffness_zz_n_per_m=kzz) for n, st in (("b0", "s0"), ("b2", "s2")))
    m = assemble(loads_scene(_rigid_rotor(b)))
    f = np.sort(modes(m, 0.0).frequency_hz) * 2 * math.pi
    exact = np.sort([math.sqrt(2 * kyy / 10), math.sqrt(2 * kzz / 10), math.sqrt(2 * kyy * 0.1 ** 2 / 0.05),
                     math.sqrt(2 * kzz * 0.1 ** 2 / 0.05)])
    assert f[:4] == pytest.approx(exact, rel=1e-5)


def test_cross_coupled_bearings_destabilise_forward_whirl():
    """Bearings with K = [[k, q], [−q, k]] (a follower cross-coupling, as of a fluid film): the bounce mode
    solves m s² + 2(k ∓ i q) = 0 in complex coordinates, s = ±i sqrt(2(k ∓ iq)/m): one whirl grows
    (negative damping ratio), one decays, with equal |Re s| (closed form); 1e-5."""
    k, q = 1.0e6, 0.5e6                # Friswell et al. (2010) Example 5.9.4's direct and cross stiffness
    b = "".join(_bearing(n, st, stiffness_n_per_m=k, stiffness_yz_n_per_m=q, stiffness_zy_n_per_m=-q)
                for n, st in (("b0", "s0"), ("b2", "s2")))
    m = assemble(loads_scene(_rigid_rotor(b)))
    res = modes(m, 0.0, damped=True)
    s = 1j * np.sqrt(2 * (k + 1j * q) / 10)          # the other root is its mirror −conj(s): same frequency
    wd = res.frequency_hz * 2 * math.pi
    bounce = np.flatnonzero(abs(wd - abs(s.imag)) < 1e-3 * abs(s.imag))
    assert len(bounce) == 2 and wd[bounce] == pytest.approx([abs(s.imag)] * 2, rel=1e-5)
    zeta = abs(s.real) / abs(s)
    assert np.sort(res.damping_ratio[bounce]) == pytest.approx([-zeta, zeta], rel=1e-4)


FRISWELL_591 = HEAD + (
    '[[materials]]\nname = "steel"\ndensity_kg_m3 = 7810\nyoungs_modulus_gpa = 211\npoisson_ratio = 0.29926108\n'
    + _stations(0, 250, 500, 750, 1000, 1250, 1500)
    + "".join(_shaft(f"s{i}", f"s{i + 1}", 50) for i in range(6))
    + '[[disks]]\nname = "d1"\nstation = "s2"\nouter_diameter_mm = 280\ninner_diameter_mm = 50\nthickness_mm = 70\n'
      'material = "steel"\n'
    + '[[disks]]\nname = "d2"\nstation = "s4"\nouter_diameter_mm = 350\ninner_diameter_mm = 50\nthickness_mm = 70\n'
      'material = "steel"\n'
    + _bearing("b0", "s0", stiffness_n_per_m=1e6) + _bearing("b6", "s6", stiffness_n_per_m=1e6))


@pytest.mark.parametrize("speed_rpm, published_rad_s", [
    (0.0, [86.66, 86.66, 274.31, 274.31, 716.78, 716.78]),
    (4000.0, [85.39, 87.80, 251.78, 294.71, 600.18]),
])
def test_friswell_5_9_1_with_disks_from_geometry(speed_rpm, published_rad_s):
    """Friswell et al. (2010) Example 5.9.1: 1.5 m, 50 mm steel shaft in six elements (E 211 GPa, G 81.2 GPa:
    ν = E/2G − 1), disks of 280 and 350 mm diameter, 70 mm thick, bored to the shaft (their mass and
    inertias from the geometry here), bearings 1 MN/m: the published natural frequencies (rad/s), to 0.01."""
    m = assemble(loads_scene(FRISWELL_591))
    w = np.sort(modes(m, speed_rpm * math.pi / 30).frequency_hz * 2 * math.pi)
    assert w[:len(published_rad_s)] == pytest.approx(published_rad_s, abs=0.01)


def test_disk_geometry_matches_hand_values_and_refuses_both():
    """``disk_properties``: m = ρπ(D²−d²)w/4, Ip = m(D²+d²)/8, Id = Ip/2 + m w²/12 (annulus); a disk with both
    a mass and a geometry, or a geometry without material, is refused in one line."""
    s = loads_scene(FRISWELL_591)
    d1 = s.disks[0]
    m = 7810 * math.pi * (0.28 ** 2 - 0.05 ** 2) * 0.07 / 4
    assert d1.mass_kg == pytest.approx(m, rel=1e-14)
    assert d1.polar_inertia_kg_m2 == pytest.approx(m * (0.28 ** 2 + 0.05 ** 2) / 8, rel=1e-14)
    assert d1.diametral_inertia_kg_m2 == pytest.approx(m * (0.28 ** 2 + 0.05 ** 2) / 16 + m * 0.07 ** 2 / 12, rel=1e-14)
    bad = FRISWELL_591.replace('thickness_mm = 70\nmaterial = "steel"\n', 'thickness_mm = 70\nmaterial = "steel"\nmass_kg = 3\n', 1)
    with pytest.raises(InputError, match=r"disks\[0\]\.mass_kg: give either the mass and inertias or the geometry"):
        loads_scene(bad)
    with pytest.raises(InputError, match=r"disks\[0\]: missing field 'material'"):
        loads_scene(FRISWELL_591.replace('thickness_mm = 70\nmaterial = "steel"\n', 'thickness_mm = 70\n', 1))


@pytest.mark.parametrize("snippet, message", [
    ('[[bearings]]\nname = "bx"\nstation = "s1"\nstiffness_yy_n_per_m = 1e6\n',
     r"bearings\[2\]: missing field 'stiffness_n_per_m' \(N/m\) \(or give both"),
    ('[[bearings]]\nname = "bx"\nstation = "s1"\nstiffness_n_per_m = 1e6\nstiffness_zz_n_per_m = -5\n',
     r"bearings\[2\]\.stiffness_zz_n_per_m = -5 N/m: must be >= 0"),
    ('[gravity]\nacceleration_y_m_per_s2 = 1e9\n', r"gravity\.acceleration_y_m_per_s2 = 1e\+09 m/s\^2: must be in"),
    ('[[static_loads]]\nname = "L"\nstation = "nowhere"\nforce_y_n = 1\n', r"static_loads\[0\]\.station = 'nowhere': no such station"),
    ('[[static_loads]]\nname = "L"\nstation = "s1"\nforce_y_n = nan\n', r"static_loads\[0\]\.force_y_n = nan N: must be finite"),
])
def test_bad_new_keys_one_line(snippet, message):
    base = _rigid_rotor(_bearing("b0", "s0", stiffness_n_per_m=1e6) + _bearing("b2", "s2", stiffness_n_per_m=1e6))
    with pytest.raises(InputError, match=message):
        loads_scene(base + snippet)


def _table_rotor(extra_keys: str = "") -> str:
    """The rigid rotor on two bearings whose direct stiffness follows a speed table (a fluid-film bearing's
    stiffening with speed, linear in the speed here: k(Ω) = k0 + k1 Ω on 0–6 000 rpm)."""
    b = "".join(f'[[bearings]]\nname = "{n}"\nstation = "{st}"\nspeed_table_rpm = [0, 3000, 6000]\n'
                f'stiffness_yy_n_per_m = [{K0}, {K0 + K1 * 100 * math.pi}, {K0 + K1 * 200 * math.pi}]\n'
                f'stiffness_zz_n_per_m = [{K0}, {K0 + K1 * 100 * math.pi}, {K0 + K1 * 200 * math.pi}]\n' + extra_keys
                for n, st in (("b0", "s0"), ("b2", "s2")))
    return _rigid_rotor(b)


K0, K1 = 2.0e5, 400.0        # N/m and N·s/m (k at 6000 rpm: 2.0e5 + 400 × 628.3 = 4.5e5 N/m)


@pytest.mark.parametrize("speed_rpm", [0.0, 1500.0, 4500.0, 9000.0])
def test_speed_table_bearings_follow_the_speed(speed_rpm):
    """Bounce frequency sqrt(2 k(Ω)/m) of the rigid rotor (closed form) with k interpolated in the table,
    held at its last value beyond it (9 000 rpm); to 5e-6, the rigid-shaft idealisation's own error."""
    m = assemble(loads_scene(_table_rotor()))
    w = speed_rpm * math.pi / 30
    k = K0 + K1 * min(w, 200 * math.pi)
    f = np.sort(modes(m, w).frequency_hz) * 2 * math.pi
    assert f[0] == pytest.approx(math.sqrt(2 * k / 10), rel=5e-6)    # the shaft's own flexibility: ~1e-6 of k


def test_speed_table_critical_speed_and_forced_response():
    """The 1X critical speed solves m Ω² = 2 (k0 + k1 Ω) (closed form, inside the table); the unbalance
    response of the table rotor peaks there, not at the rest frequency sqrt(2 k0/m)."""
    from rotor.linear.modes import critical_speeds
    from rotor.linear.unbalance import forced_response
    text = _table_rotor().replace('diametral_inertia_kg_m2 = 0.05\n', 'diametral_inertia_kg_m2 = 0.05\nunbalance_g_mm = 100\n')
    m = assemble(loads_scene(text))
    exact = (2 * K1 + math.sqrt(4 * K1 ** 2 + 8 * 10 * K0)) / (2 * 10)
    crit = [c for c in critical_speeds(m, 600.0, orders=(1,), families=("forward",)) if c.branch == 0]
    assert crit and crit[0].speed_rad_s == pytest.approx(exact, rel=1e-6)
    speeds = np.linspace(100, 400, 601)
    resp = forced_response(m, speeds)
    peak = speeds[np.argmax(abs(resp.amplitudes[:, m.dof_index("s1.y")]))]
    assert peak == pytest.approx(exact, abs=0.5) and abs(peak - math.sqrt(2 * K0 / 10)) > 20


def test_speed_table_reaches_the_time_integration():
    """The time integration's stiffness is the table's at the run speed: K at 4 500 rpm minus K at rest is
    the interpolated change on each bearing's y and z rows."""
    from rotor.dynamics.build import system_from_model
    scene = loads_scene(_table_rotor())
    m = assemble(scene)
    w = 4500 * math.pi / 30
    dk = system_from_model(m, scene, w).K - (m.K + m.K_c)
    i = m.dof_index("s0.y")
    assert dk[i, i] == pytest.approx(K1 * w, rel=1e-9)
    assert abs(dk).sum() == pytest.approx(4 * K1 * w, rel=1e-9)      # y and z of both bearings, nothing else


@pytest.mark.parametrize("keys, message", [
    ('speed_table_rpm = [0, 3000]\nstiffness_yy_n_per_m = [1e6, 2e6, 3e6]\nstiffness_zz_n_per_m = 1e6\n',
     r"stiffness_yy_n_per_m: 3 values for 2 speeds of speed_table_rpm"),
    ('stiffness_yy_n_per_m = [1e6, 2e6]\nstiffness_zz_n_per_m = 1e6\n', r"a list needs speed_table_rpm"),
    ('speed_table_rpm = [3000, 0]\nstiffness_yy_n_per_m = [1e6, 2e6]\nstiffness_zz_n_per_m = 1e6\n', r"must be ascending"),
    ('speed_table_rpm = [0, 3000]\nstiffness_yy_n_per_m = [1e6, -2e6]\nstiffness_zz_n_per_m = 1e6\n',
     r"stiffness_yy_n_per_m = -2e\+06 N/m: must be >= 0"),
    ('speed_table_rpm = [0, 3000]\nstiffness_n_per_m = 1e6\n', r"no coefficient is a list"),
    ('speed_table_rpm = [0, 1e9]\nstiffness_yy_n_per_m = [1e6, 2e6]\nstiffness_zz_n_per_m = 1e6\n',
     r"speed_table_rpm = 1e\+09 rpm: must be in"),
])
def test_bad_speed_tables_one_line(keys, message):
    text = _rigid_rotor(f'[[bearings]]\nname = "b0"\nstation = "s0"\n{keys}' + _bearing("b2", "s2", stiffness_n_per_m=1e6))
    with pytest.raises(InputError, match=message):
        loads_scene(text)


@pytest.mark.parametrize("text", [FRISWELL_591, _table_rotor(), _pinned_beam(
    "[gravity]\nacceleration_y_m_per_s2 = -9.81\n[[static_loads]]\nname = \"L\"\nstation = \"s1\"\nforce_z_n = 12.5\n"
    "moment_y_n_m = -3\n")])
def test_new_keys_survive_the_scene_toml(text):
    """A scene with disks from geometry, speed tables, gravity and static loads written back to TOML
    (rotor.model.scene_toml) reads as the same scene."""
    import dataclasses
    from rotor.model.scene_toml import scene_to_toml
    s = loads_scene(text)
    back = loads_scene(scene_to_toml(s))
    assert dataclasses.replace(back, path="") == dataclasses.replace(s, path="")


def test_replacing_the_isotropic_value_reaches_the_direct_terms():
    """``dataclasses.replace(bearing, damping_n_s_m=…)`` (as scripts and the Python API edit a scene) changes the
    direct terms that were left to the isotropic value, and leaves those given explicitly."""
    import dataclasses
    from rotor.model.scene import Bearing
    b = Bearing("b", "s", 1e6)
    k, c = dataclasses.replace(b, stiffness_n_m=2e6, damping_n_s_m=500.0).lateral_at(0.0)
    assert k.tolist() == [[2e6, 0.0], [0.0, 2e6]] and c.tolist() == [[500.0, 0.0], [0.0, 500.0]]
    a = Bearing("b", "s", 1e6, stiffness_zz_n_m=8e5)
    k, _ = dataclasses.replace(a, stiffness_n_m=3e6).lateral_at(0.0)
    assert k.tolist() == [[3e6, 0.0], [0.0, 8e5]]
