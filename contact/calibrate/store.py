"""The stored calibrations: one JSON file per law in ``contact/calibrated/``, loaded by name, rewritten by a refit."""
from __future__ import annotations

from pathlib import Path

from contact.calibrate.families import FAMILIES
from contact.calibrate.fit import calibrate_dataset, committed_datasets
from contact.calibrate.law import CalibratedLaw
from contact.errors import DatasetError
from contact.files import atomic_write_text
from contact.package_data import entries, location, shipped, stem

#: the calibrated laws shipped in the package (read through importlib.resources, see contact.package_data)
CALIBRATED_DIR = shipped("contact", "calibrated")


def available(directory=CALIBRATED_DIR) -> list[str]:
    """Names of the stored calibrated laws (in ``directory``: the shipped ones by default)."""
    return [stem(e) for e in entries(directory, ".json")]


def load_calibrated(name: str, directory=CALIBRATED_DIR) -> CalibratedLaw:
    """Load a stored calibrated law by name, e.g. ``load_calibrated("clamped-foundation")``.

    A bare scene name (``"clamped"``) is accepted when exactly one law is stored for it.

    Raises
    ------
    DatasetError
        unknown name (listing the available ones) or an unreadable/malformed file.
    """
    directory = location(directory)
    path = directory.joinpath(f"{name}.json")
    if not path.is_file():
        matches = [n for n in available(directory) if any(n == f"{name}-{fam}" for fam in FAMILIES)]
        if len(matches) != 1:
            raise DatasetError(f"calibrated law {name!r} not found in {directory} (available: "
                               f"{', '.join(available(directory)) or 'none'})")
        path = directory.joinpath(f"{matches[0]}.json")
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise DatasetError(f"{path}: cannot read calibrated law ({exc})") from exc
    return CalibratedLaw.from_json(text, str(path))


def _calibrate_all(paths) -> list[CalibratedLaw]:
    paths = committed_datasets() if paths is None else [paths] if isinstance(paths, (str, Path)) else list(paths)
    return [law for p in paths for law in calibrate_dataset(p)]


def write_calibrations(paths, directory) -> list[Path]:
    """Refit every scene of the datasets (``None``: all committed) and write ``<directory>/<name>.json``.

    ``directory`` has no default: the shipped folder is read-only data (``ringcontact calibrate``
    writes ``contact/calibrated`` relative to the working directory, the package's copy when run
    from the repository root). A stored file of the same scene and dataset kind but another family
    is removed.
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
