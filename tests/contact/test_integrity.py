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


def test_written_files_respect_the_umask(tmp_path):
    """Results are 0644 under the usual umask 022 (not the 0600 of a temporary file), and follow the umask."""
    import os

    from contact.files import atomic_write_text

    old = os.umask(0o022)
    try:
        assert (atomic_write_text(tmp_path / "a.txt", "x").stat().st_mode & 0o777) == 0o644
        os.umask(0o077)
        assert (atomic_write_text(tmp_path / "b.txt", "x").stat().st_mode & 0o777) == 0o600
    finally:
        os.umask(old)
    assert not list(tmp_path.glob(".*.tmp"))
