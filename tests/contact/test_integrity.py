"""Whole-file checksums: an edited dataset (metadata included) or calibrated law is refused, never used."""
from __future__ import annotations

import json

import pytest

from contact.calibrate import CALIBRATED_DIR, available, load_calibrated
from contact.dataset import read_dataset
from contact.errors import DatasetError
from fem_reference.plane.sweep import DATASET_PATH


def test_committed_files_carry_a_valid_whole_file_checksum():
    assert read_dataset(DATASET_PATH, kind="2d").points
    for name in available():
        assert load_calibrated(name).parameters


def test_edited_dataset_metadata_is_refused(tmp_path):
    doc = json.loads(DATASET_PATH.read_text())
    scene = next(iter(doc["metadata"]["scenes"]))
    doc["metadata"]["scenes"][scene] = "clearance edited by hand"       # points untouched
    bad = tmp_path / "edited.json"
    bad.write_text(json.dumps(doc))
    with pytest.raises(DatasetError, match="checksum mismatch"):
        read_dataset(bad)
    del doc["sha256"]
    bad.write_text(json.dumps(doc))
    with pytest.raises(DatasetError, match="no whole-file checksum"):
        read_dataset(bad)


def test_a_dataset_of_the_other_kind_is_refused():
    with pytest.raises(DatasetError, match="a 2D dataset; this job needs a 3D one"):
        read_dataset(DATASET_PATH, kind="3d")


def test_edited_calibrated_law_is_refused(tmp_path):
    name = available()[0]
    text = (CALIBRATED_DIR / f"{name}.json").read_text()
    doc = json.loads(text)
    doc["geometry"]["bearing_E_Pa"] *= 0.5                                # an edited modulus
    (tmp_path / f"{name}.json").write_text(json.dumps(doc, indent=1))
    with pytest.raises(DatasetError, match="checksum mismatch"):
        load_calibrated(name, tmp_path)
    (tmp_path / f"{name}.json").write_text(text)                          # the original loads
    assert load_calibrated(name, tmp_path).geometry.bearing_E_Pa == doc["geometry"]["bearing_E_Pa"] * 2
