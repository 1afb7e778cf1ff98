"""The stored calibrations: one JSON file per law in ``contact/calibrated/``, loaded by name, rewritten by a refit."""
from __future__ import annotations

from pathlib import Path

from contact.calibrate.families import FAMILIES
from contact.calibrate.fit import calibrate_dataset, committed_datasets
from contact.calibrate.law import CalibratedLaw
from contact.errors import DatasetError
from contact.files import atomic_write_text

CALIBRATED_DIR = Path(__file__).resolve().parents[1] / "calibrated"


def available(directory=CALIBRATED_DIR) -> list[str]:
    """Names of the stored calibrated laws."""
    return sorted(p.stem for p in Path(directory).glob("*.json"))


def load_calibrated(name: str, directory=CALIBRATED_DIR) -> CalibratedLaw:
    """Load a stored calibrated law by name, e.g. ``load_calibrated("clamped-foundation")``.

    A bare scene name (``"clamped"``) is accepted when exactly one law is stored for it.

    Raises
    ------
    DatasetError
        unknown name (listing the available ones) or an unreadable/malformed file.
    """
    directory = Path(directory)
    path = directory / f"{name}.json"
    if not path.exists():
        matches = [n for n in available(directory) if any(n == f"{name}-{fam}" for fam in FAMILIES)]
        if len(matches) != 1:
            raise DatasetError(f"calibrated law {name!r} not found in {directory} (available: "
                               f"{', '.join(available(directory)) or 'none'})")
        path = directory / f"{matches[0]}.json"
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise DatasetError(f"{path}: cannot read calibrated law ({exc})") from exc
    return CalibratedLaw.from_json(text, str(path))


def _calibrate_all(paths) -> list[CalibratedLaw]:
    paths = committed_datasets() if paths is None else [paths] if isinstance(paths, (str, Path)) else list(paths)
    return [law for p in paths for law in calibrate_dataset(p)]


def write_calibrations(paths=None, directory=CALIBRATED_DIR) -> list[Path]:
    """Refit every scene of the datasets (default: all committed) and write ``<directory>/<name>.json``.

    A stored file of the same scene and dataset kind but another family is removed.
    """
    directory = Path(directory)
    out = []
    for law in _calibrate_all(paths):
        stem = law.name[: -len(law.family) - 1]
        for fam in FAMILIES:
            old = directory / f"{stem}-{fam}.json"
            if fam != law.family and old.exists():
                old.unlink()
        out.append(atomic_write_text(directory / f"{law.name}.json", law.to_json()))
    return out
