"""The per-process scene cache of rotor/studies/steady_state.py (``_scene_model``): a scene file written again at the
same path is read again. Measured before the fix: the slow ten-rotor test of test_grazing_family.py, each rotor's
scene written to the same file, followed its second rotor with the first one's model (grazing 16.5 % off)."""
from pathlib import Path

from rotor.studies.steady_state import _scene_model

SCENE = Path(__file__).parents[1] / "scenes" / "friswell-591-loose-aluminium.toml"


def test_a_scene_file_rewritten_at_the_same_path_is_read_again(tmp_path):
    path = tmp_path / "scene.toml"
    text = SCENE.read_text(encoding="utf-8")
    path.write_text(text, encoding="utf-8")
    first = _scene_model(str(path))[0]
    assert _scene_model(str(path))[0] is first                       # unchanged file: the cached model
    path.write_text(text.replace('name = "friswell-591-loose-aluminium"', 'name = "rewritten"', 1), encoding="utf-8")
    second = _scene_model(str(path))[0]
    assert first.name == "friswell-591-loose-aluminium" and second.name == "rewritten"
