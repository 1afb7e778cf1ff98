"""A stored study point is keyed by the scene it was computed with, not by the scene's name.

The sweep store (sweep/store.py) reuses a point whose stored parameters equal the task's. Before
rotor/studies/scene_digest.py the parameters named the scene file only ("paper-table4" or its path), so a
point computed before the file changed (here: the reading of Eq. 34, the clearance) was reused as current:
the published sensitivity study could mix the former default reading's points with the new one's. Each
test stores a point made from one scene file, edits the file and asks the store about the rebuilt task.
"""
import numpy as np
import pytest

from contact.errors import InputError
from contact.package_data import shipped
from rotor.studies import readings as rd
from rotor.studies import sensitivity as sens
from rotor.studies import steady_state as ss
from rotor.studies.scene_digest import scene_digest
from sweep.store import ResultStore


@pytest.fixture
def scene_file(tmp_path):
    """A copy of the bundled paper-table4 scene that a test may edit."""
    src = shipped("rotor", "scenes", "paper-table4.toml").read_text(encoding="utf-8")
    p = tmp_path / "table4.toml"
    p.write_text(src, encoding="utf-8")
    return p


def _edit(path, old: str, new: str):
    text = path.read_text(encoding="utf-8")
    assert old in text
    path.write_text(text.replace(old, new), encoding="utf-8")
    ss._MODEL_CACHE.clear()
    sens._MODELS.clear()
    rd._MODELS.clear()


def _store_point(store, task):
    store.save(task.key, task.params, {"x": np.zeros(1)}, {"converged": True})


def test_a_sensitivity_point_of_another_reading_is_stale_not_reused(scene_file, tmp_path):
    """The base variant's point stored under the file's reading; the file then names the inertial reading
    (the former default): the same key and the same name-based parameters, but the store must call it stale."""
    store = ResultStore(tmp_path / "sens")
    before = sens.variant_tasks(str(scene_file), sens.Variant("base"), [10500.0])[0]
    _store_point(store, before)
    assert store.check(before.key, before.params)[0] == "done"
    _edit(scene_file, 'excitation = "opposed-at-joint"', 'excitation = "inertial-at-joint"')
    after = sens.variant_tasks(str(scene_file), sens.Variant("base"), [10500.0])[0]
    assert after.key == before.key
    assert {k: v for k, v in after.params.items() if k != "scene_sha256"} == \
        {k: v for k, v in before.params.items() if k != "scene_sha256"}     # the old key: equal, reused
    assert store.check(after.key, after.params)[0] == "stale"


def test_a_cascade_point_of_another_clearance_is_stale(scene_file, tmp_path):
    store = ResultStore(tmp_path / "cascade")
    before = ss.sweep_tasks(str(scene_file), [9000.0], options={"max_revs": 10})[0]
    _store_point(store, before)
    _edit(scene_file, "clearance_mm = 0.05", "clearance_mm = 0.06")
    after = ss.sweep_tasks(str(scene_file), [9000.0], options={"max_revs": 10})[0]
    assert store.check(after.key, after.params)[0] == "stale"
    again = ss.sweep_tasks(str(scene_file), [9000.0], options={"max_revs": 10})[0]
    assert again.params == after.params                   # deterministic: an unchanged scene is reused


def test_a_readings_point_follows_its_mesh_and_scene(scene_file):
    a = rd.reading_tasks(str(scene_file), ["inertial-at-joint"], [10500.0], meshes=(None, 2))
    assert a[0].params["scene_sha256"] != a[1].params["scene_sha256"]      # the mesh enters the digest
    _edit(scene_file, "clearance_mm = 0.05", "clearance_mm = 0.06")
    b = rd.reading_tasks(str(scene_file), ["inertial-at-joint"], [10500.0], meshes=(None, 2))
    assert [t.params["scene_sha256"] for t in a] != [t.params["scene_sha256"] for t in b]


def test_the_digest_ignores_where_the_file_lives_and_its_title(scene_file, tmp_path):
    from rotor.model.scene import load_scene

    other = tmp_path / "elsewhere.toml"
    other.write_text(scene_file.read_text(encoding="utf-8").replace('title = "', 'title = "copy of '),
                     encoding="utf-8")
    assert scene_digest(load_scene(str(scene_file))) == scene_digest(load_scene(str(other)))
    assert scene_digest(load_scene(str(scene_file))) != scene_digest(load_scene(str(scene_file)), 2)


def test_a_point_whose_scene_changed_after_its_task_was_made_is_refused(scene_file):
    """The point function checks the digest before computing: one line naming the digests."""
    task = sens.variant_tasks(str(scene_file), sens.Variant("base"), [10500.0])[0]
    _edit(scene_file, "clearance_mm = 0.05", "clearance_mm = 0.06")
    with pytest.raises(InputError, match="scene_sha256 = .* now digests to"):
        task.func(**task.params)
    task = ss.sweep_tasks(str(scene_file), [9000.0])[0]
    _edit(scene_file, "clearance_mm = 0.06", "clearance_mm = 0.07")
    with pytest.raises(InputError, match="changed since the task was made"):
        task.func(**task.params)


def test_shooting_points_and_blocks_carry_the_digest_too(scene_file, tmp_path):
    """`study cascade --method shooting`: its point and block tasks are stale after a scene edit as well."""
    from rotor.studies.shooting_block import shooting_block_tasks
    from rotor.studies.shooting_point import shooting_sweep_tasks

    store = ResultStore(tmp_path / "shoot")
    point = shooting_sweep_tasks(str(scene_file), [9000.0])[0]
    block = shooting_block_tasks(str(scene_file), [9000.0, 9300.0])[0]
    assert block.outputs[0][1]["scene_sha256"] == point.params["scene_sha256"] == block.params["scene_sha256"]
    _store_point(store, point)
    _edit(scene_file, "clearance_mm = 0.05", "clearance_mm = 0.06")
    again = shooting_sweep_tasks(str(scene_file), [9000.0])[0]
    assert store.check(again.key, again.params)[0] == "stale"
    with pytest.raises(InputError, match="now digests to"):
        point.func(**point.params)
    with pytest.raises(InputError, match="now digests to"):
        block.func(**block.params)
