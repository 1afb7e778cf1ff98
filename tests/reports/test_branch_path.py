"""The path a branch's work estimate predicts (reports/cli/_branch_path.py) against the closed form of a Jeffcott rotor
in a conformal ring (rotor/periodic/jeffcott_scene.py): where the free linear orbit reaches the clearance is the
closed-form grazing speed, and the predicted grazings split the path there. A seeded random sample of rotors, the seed
drawn from the commit (printed); no wall time is asserted."""
from __future__ import annotations

import numpy as np
import pytest

from reports.cli._branch_path import _sample, branch_path
from rotor.periodic.jeffcott_scene import closed_form_grazing, random_family, scene_toml
from rotor.studies.grazing_family import sweep_range
from rotor.studies.steady_state import point_system
from tests.seeds import commit_seed

TO_RPM = 30.0 / np.pi


@pytest.fixture(scope="module")
def rotors(tmp_path_factory):
    seed = commit_seed()
    print(f"random Jeffcott-ring rotors: rotor.periodic.jeffcott_scene.random_family({seed}, 3)")
    out = []
    for i, rotor in enumerate(random_family(seed, 3)):
        path = tmp_path_factory.mktemp("jr") / f"jeffcott-ring-{i}.toml"
        path.write_text(scene_toml(rotor))
        out.append((rotor, str(path)))
    return out


def test_the_free_orbit_reaches_the_clearance_at_the_closed_form_grazing_speeds(rotors):
    """At each closed-form grazing speed (continuous time, rotor/periodic/jeffcott_scene.py: closed_form_grazing) the
    free linear orbit's largest radius is the clearance to 1e-9 (measured: 1e-14)."""
    for rotor, scene in rotors:
        for w, _ in closed_form_grazing(rotor):
            reach = _sample(point_system(scene, w * TO_RPM)[2])[2]
            assert reach == pytest.approx(1.0, abs=1e-9), (w * TO_RPM, reach)


def test_the_predicted_grazings_are_the_closed_form_ones_within_a_sample_spacing(rotors):
    """Over each rotor's sweep range (rotor/studies/grazing_family.py: sweep_range), up and down: as many predicted
    grazings as closed-form ones inside the range, each within half the 17 samples' spacing of its own (measured on
    6 rotors: 0.4 to 21 rpm against spacings of 81 to 188 rpm), in the order the branch meets them; three segments,
    the middle one the contact stretch, where the deepest sample lies."""
    for rotor, scene in rotors:
        lo, hi = sweep_range(rotor)
        expected = [w * TO_RPM for w, _ in closed_form_grazing(rotor) if lo < w * TO_RPM < hi]
        assert len(expected) == 2
        spacing = (hi - lo) / 16
        for a, b in ((lo, hi), (hi, lo)):
            got = branch_path(lambda r: point_system(scene, r)[2], a, b)
            order = expected if b > a else expected[::-1]
            assert len(got.grazing_rpm) == 2
            assert np.all(np.abs(np.array(got.grazing_rpm) - order) < 0.5 * spacing), (got.grazing_rpm, order)
            assert [c for _, c in got.segments] == [False, True, False]
            assert min(expected) < got.deepest_rpm < max(expected)
            assert got.total > 10.0


def test_a_rotor_touching_throughout_is_one_smooth_segment():
    """paper-table4: gravity and misalignment keep the ring on its support at every speed (the free orbit reaches
    about 20 clearances): no grazing, one segment, nothing counted as a contact stretch."""
    got = branch_path(lambda r: point_system("paper-table4", r)[2], 600.0, 18000.0, samples=5)
    assert got.grazing_rpm == () and got.deepest_rpm is None
    assert len(got.segments) == 1 and got.segments[0][1] is False and got.total > 10.0
