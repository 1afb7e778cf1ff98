"""Drift check: do the stored calibrations still match a fresh fit of the datasets?"""
from __future__ import annotations

import json
import math

from contact.calibrate.store import CALIBRATED_DIR, _calibrate_all, load_calibrated
from contact.errors import DatasetError


def _first_difference(a, b, where: str = "", rel: float = 1e-6) -> str | None:
    """Path of the first difference between two JSON trees (floats compared to ``rel``), or None."""
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            return f"{where or '/'} keys {sorted(set(a) ^ set(b))}"
        for k in a:
            d = _first_difference(a[k], b[k], f"{where}/{k}", rel)
            if d:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{where} length {len(a)} != {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            d = _first_difference(x, y, f"{where}/{i}", rel)
            if d:
                return d
        return None
    if isinstance(a, float) or isinstance(b, float):
        if isinstance(a, (int, float)) and isinstance(b, (int, float)) and math.isclose(a, b, rel_tol=rel, abs_tol=1e-12):
            return None
        return f"{where}: {a!r} != {b!r}"
    return None if a == b else f"{where}: {a!r} != {b!r}"


def check_calibrations(paths=None, directory=CALIBRATED_DIR) -> list[str]:
    """Differences between the stored calibrations and a fresh fit of the datasets (empty list = up to date)."""
    problems = []
    for law in _calibrate_all(paths):
        try:
            stored = load_calibrated(law.name, directory)
        except DatasetError as exc:
            problems.append(str(exc))
            continue
        # the checksums differ with any float inside the tolerance: compare the content only
        diff = _first_difference({k: v for k, v in json.loads(stored.to_json()).items() if k != "sha256"},
                                 {k: v for k, v in json.loads(law.to_json()).items() if k != "sha256"})
        if diff is not None:
            problems.append(f"{law.name}: stored file differs from a refit of {law.dataset.get('path')} at {diff} "
                            f"(dataset {law.dataset.get('points_sha256', '')[:12]}…, stored from "
                            f"{stored.dataset.get('points_sha256', '')[:12]}…)")
    return problems
