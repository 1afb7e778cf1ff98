"""Topology checks (rotor.model.topology): one line naming the station, where the run needs it.

Each case is a scene text that differs from a held two-bearing rotor in one respect. Expected
behaviour: a station no shaft reaches and a support nothing joins are refused by every analysis
(at assembly); a rotor free to move as a rigid body is refused by time integration and the forced
response, and only warned about by the modal jobs, whose free-free elastic modes are the textbook
ones (Euler–Bernoulli free-free beam: β₁L = 4.7300, e.g. Blevins 1979, Formulas for Natural
Frequency and Mode Shape, Table 8-1).
"""
from __future__ import annotations

import math

import pytest

from contact.errors import InputError
from reports.cli import rotor as rotor_cli
from reports.cli import simulate as simulate_cli
from rotor.dynamics.build import system_from_model
from rotor.linear.unbalance import forced_response
from rotor.model.assembly import assemble
from rotor.model.scene import loads_scene
from rotor.model.topology import ground_problem

HEAD = """
schema = "ringcontact.rotor-scene/1"
name = "topo"
title = "topology test rotor"
[[materials]]
name = "steel"
density_kg_m3 = 7800
youngs_modulus_gpa = 200
poisson_ratio = 0.3
[[stations]]
name = "A"
x_mm = 0
[[stations]]
name = "M"
x_mm = 500
[[stations]]
name = "B"
x_mm = 1000
[[shafts]]
from = "A"
to = "M"
outer_diameter_mm = 40
material = "steel"
elements = 4
[[shafts]]
from = "M"
to = "B"
outer_diameter_mm = 40
material = "steel"
elements = 4
[[disks]]
name = "d"
station = "M"
mass_kg = 10
polar_inertia_kg_m2 = 0.05
diametral_inertia_kg_m2 = 0.03
unbalance_g_mm = 100
"""
BEARING = """
[[bearings]]
name = "b{st}"
station = "{st}"
stiffness_n_per_m = 1e7
damping_n_s_per_m = 100
"""
HELD = HEAD + BEARING.format(st="A") + BEARING.format(st="B")
EXTRA_STATION = '[[stations]]\nname = "C"\nx_mm = 1200\n'


def _model(text: str):
    return assemble(loads_scene(text, origin="topo.toml"))


def test_held_rotor_passes():
    assert ground_problem(_model(HELD)) is None


@pytest.mark.parametrize("extra, what", [
    ('[[disks]]\nname = "d2"\nstation = "C"\nmass_kg = 1\npolar_inertia_kg_m2 = 0\ndiametral_inertia_kg_m2 = 0\n',
     "disk 'd2'"),
    (BEARING.format(st="C"), "bearing 'bC'"),
    ("", ""),
])
def test_station_no_shaft_reaches_is_refused_naming_it(extra, what):
    text = HELD.replace('[[shafts]]', EXTRA_STATION + '[[shafts]]', 1) + extra
    with pytest.raises(InputError) as exc:
        _model(text)
    msg = str(exc.value)
    assert msg.startswith("topo.toml: station 'C'") and "no shaft or coupling reaches it" in msg
    assert what in msg and "\n" not in msg


SUPPORT = """
[[supports]]
name = "s"
station = "{st}"
mass_kg = 5
inertia_kg_m2 = 0.1
stiffness_n_per_m = 1e7
damping_n_s_per_m = 100
angular_stiffness_n_m_per_rad = 1e4
angular_damping_n_m_s_per_rad = 1
"""


def test_support_without_loose_support_is_refused_naming_it():
    with pytest.raises(InputError, match=r"^topo.toml: supports 's' on station 'B': not the \[loose_support\] "
                                         r"support, so nothing joins it to the rotor"):
        _model(HELD + SUPPORT.format(st="B"))


def test_support_on_a_station_no_shaft_reaches_is_refused_naming_the_station():
    text = HELD.replace('[[shafts]]', EXTRA_STATION + '[[shafts]]', 1) + SUPPORT.format(st="C")
    with pytest.raises(InputError, match=r"station 'C' \(support 's'\): no shaft or coupling reaches it"):
        _model(text)


def test_no_bearing_at_all_refused_in_time_and_forced_response_allowed_in_modes(capsys, tmp_path):
    model = _model(HEAD)
    msg = ground_problem(model)
    assert msg.startswith("topo.toml: no bearing at all") and "station 'A'" in msg
    with pytest.raises(InputError, match="no bearing at all.*time integration needs a rotor held to ground"):
        system_from_model(model, model.scene, 100.0)
    with pytest.raises(InputError, match="no bearing at all.*the forced response needs"):
        forced_response(model, [100.0])
    scene = tmp_path / "free.toml"
    scene.write_text(HEAD)
    assert rotor_cli.main(["unbalance", str(scene), "--points", "2"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "station 'A'" in err and "Traceback" not in err
    assert simulate_cli.main(["--scene", str(scene), "--speed-rpm", "1000", "--revolutions", "1",
                              "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no bearing at all" in err
    # modal analysis of the free-free rotor is legitimate: a warning, and the elastic modes
    assert rotor_cli.main(["modes", str(scene), "--json"]) == 0
    out = capsys.readouterr()
    assert "warning" in out.err and "rigid-body (0 Hz) modes are left out" in out.err
    import json
    first = json.loads(out.out)["modes"][0]["frequency_hz"]
    assert first > 1.0                                   # no 0 Hz rigid-body mode among them


def test_free_free_beam_modes_are_the_textbook_ones():
    """Uniform free-free beam (no disk): ω₁ = (4.7300/L)² √(EI/ρA) (Blevins Table 8-1), Euler–Bernoulli."""
    from rotor.linear.modes import modes
    head = HEAD.split("[[disks]]")[0].replace("elements = 4", "elements = 16")
    model = assemble(loads_scene(head), shear=False, rotary_inertia=False, gyroscopic=False)
    assert ground_problem(model).startswith("<string>: no bearing at all")
    d, L, E, rho = 0.04, 1.0, 200e9, 7800.0
    A, I = math.pi * d * d / 4, math.pi * d ** 4 / 64
    f1 = (4.7300 / L) ** 2 * math.sqrt(E * I / (rho * A)) / (2 * math.pi)
    assert modes(model, 0.0).frequency_hz[0] == pytest.approx(f1, rel=1e-4)


def test_group_of_stations_without_ground_is_named():
    """Two shaft lines in one scene, bearings on the first only: the second floats."""
    text = HELD.replace('[[shafts]]', EXTRA_STATION + '[[stations]]\nname = "E"\nx_mm = 1500\n[[shafts]]', 1)
    text += '[[shafts]]\nfrom = "C"\nto = "E"\nouter_diameter_mm = 20\nmaterial = "steel"\n'
    model = _model(text)
    msg = ground_problem(model)
    assert msg == ("topo.toml: station 'C': no connection to ground (no bearing with stiffness, support or boundary "
                   "condition on it or on the stations joined to it ('E'))")
    with pytest.raises(InputError, match="station 'C': no connection to ground"):
        system_from_model(model, model.scene, 100.0)


def test_single_bearing_without_angular_stiffness_pivots():
    """One bearing at A: the rotor turns about A as a rigid body, most at the far end B."""
    model = _model(HEAD + BEARING.format(st="A"))
    msg = ground_problem(model)
    assert msg.startswith("topo.toml: station 'B': the rotor can move there as a rigid body")
    with pytest.raises(InputError, match="station 'B'.*the forced response needs"):
        forced_response(model, [100.0])
    # an angular stiffness on the one bearing holds it
    held = HEAD + BEARING.format(st="A") + "angular_stiffness_n_m_per_rad = 1e5\n"
    assert ground_problem(_model(held)) is None


def test_damper_only_is_no_connection_to_ground():
    """A bearing with damping but no stiffness holds nothing statically."""
    text = HEAD + BEARING.format(st="A").replace("1e7", "0")
    msg = ground_problem(_model(text))
    assert msg is not None and "station 'A': no connection to ground" in msg
