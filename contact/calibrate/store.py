"""The stored calibrations: one JSON file per law in ``contact/calibrated/``, loaded by name, rewritten by a refit;
and a law file anywhere, loaded by path (:func:`load_law_file`, :func:`law_file_record`)."""
from __future__ import annotations

import json
import os
import re
import stat
from dataclasses import dataclass
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


#: largest law file read by path (bytes): a calibrated law is a few kB (``contact/calibrated/*.json``)
LAW_FILE_MAX_BYTES = 1_000_000


@dataclass(frozen=True)
class LawFile:
    """A calibrated law with where it was read from.

    Attributes
    ----------
    law : CalibratedLaw
        The law.
    path : str
        The file as resolved (absolute for a user's file; the shipped entry for ``calibrated:<name>``).
    sha256 : str
        The file's whole-document checksum (its ``"sha256"`` key, verified on load:
        :func:`contact.dataset.check_document_sha256`).
    """

    law: CalibratedLaw
    path: str
    sha256: str


def law_file_record(path) -> LawFile:
    """Read, verify and parse a calibrated-law file given by path (schema ``ringcontact/calibrated-law`` v1).

    Only a regular file of at most :data:`LAW_FILE_MAX_BYTES` bytes is read; unknown extra keys are
    ignored (:meth:`CalibratedLaw.from_json`).

    Raises
    ------
    DatasetError
        one line naming the file: missing, not a regular file, too large, unreadable, not JSON,
        checksum mismatch (an edited value), wrong schema or malformed.
    """
    p = Path(path)
    try:
        st = p.stat()
    except OSError as exc:
        raise DatasetError(f"law file {str(p)!r}: cannot read: {exc.strerror or exc}") from None
    if not stat.S_ISREG(st.st_mode):
        raise DatasetError(f"law file {str(p)!r}: not a regular file (name a calibrated-law .json file)")
    if st.st_size > LAW_FILE_MAX_BYTES:
        raise DatasetError(f"law file {str(p)!r}: {st.st_size} bytes, more than the {LAW_FILE_MAX_BYTES} bytes a "
                           "calibrated law can take (not a law file?)")
    try:
        with open(p, "rb") as fh:        # bounded read: the file may have grown since stat
            data = fh.read(LAW_FILE_MAX_BYTES + 1)
    except OSError as exc:
        raise DatasetError(f"law file {str(p)!r}: cannot read: {exc.strerror or exc}") from None
    if len(data) > LAW_FILE_MAX_BYTES:
        raise DatasetError(f"law file {str(p)!r}: more than {LAW_FILE_MAX_BYTES} bytes (not a law file?)")
    return _record(data, str(p.resolve()), f"law file {str(p)!r}")


def load_law_file(path) -> CalibratedLaw:
    """The calibrated law in the file at ``path`` (see :func:`law_file_record` for the checks)."""
    return law_file_record(path).law


def _record(data: bytes, where: str, source: str) -> LawFile:
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise DatasetError(f"{source}: not UTF-8 text (not a law file)") from None
    law = CalibratedLaw.from_json(text, source)         # checksum, schema, version, fields: one-line DatasetError
    return LawFile(law, where, json.loads(text)["sha256"])


def shipped_record(name: str, directory=CALIBRATED_DIR) -> LawFile:
    """:func:`load_calibrated` with where the law was read from and its checksum (a :class:`LawFile`)."""
    path = _stored_path(name, directory)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise DatasetError(f"{path}: cannot read calibrated law ({exc})") from exc
    return _record(data, os.fspath(path) if isinstance(path, os.PathLike) else str(path), str(path))


#: what a stored law's name may hold: it names a file inside the calibrated folder, never a path
NAME_PATTERN = re.compile(r"[A-Za-z0-9][A-Za-z0-9._-]{0,199}")


def check_law_name(name) -> str:
    """``name`` if it can only name a file inside the calibrated folder (no path separator, no ``..``).

    Raises
    ------
    DatasetError
        a name with a path separator, ``..``, a leading dot or anything but letters, digits, ``.``, ``-``, ``_``.
    """
    if not isinstance(name, str) or not NAME_PATTERN.fullmatch(name) or ".." in name:
        raise DatasetError(f"calibrated law {name!r}: a law's name, not a path (letters, digits, '.', '-', '_'; "
                           f"no '/' or '..'; available: {', '.join(available()) or 'none'}); give a law file "
                           "elsewhere by its path (.json)")
    return name


def _stored_path(name: str, directory):
    check_law_name(name)
    directory = location(directory)
    path = directory.joinpath(f"{name}.json")
    if not path.is_file():
        matches = [n for n in available(directory) if any(n == f"{name}-{fam}" for fam in FAMILIES)]
        if len(matches) != 1:
            raise DatasetError(f"calibrated law {name!r} not found in {directory} (available: "
                               f"{', '.join(available(directory)) or 'none'})")
        path = directory.joinpath(f"{matches[0]}.json")
    return path


def load_calibrated(name: str, directory=CALIBRATED_DIR) -> CalibratedLaw:
    """Load a stored calibrated law by name, e.g. ``load_calibrated("clamped-foundation")``.

    A bare scene name (``"clamped"``) is accepted when exactly one law is stored for it.

    Raises
    ------
    DatasetError
        unknown name (listing the available ones) or an unreadable/malformed file.
    """
    path = _stored_path(name, directory)
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
