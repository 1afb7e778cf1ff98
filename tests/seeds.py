"""The seed of the tests that draw their cases at random: the commit's hash (each commit checks other cases), or
``RINGCONTACT_TEST_SEED`` to rerun a failure's draw; the tests print it."""
from __future__ import annotations

import os
import subprocess
from pathlib import Path

#: the seed outside a git checkout (an installed wheel's tests)
FALLBACK_SEED = 20261129


def commit_seed() -> int:
    """``RINGCONTACT_TEST_SEED`` if set, else the first 8 hex digits of ``git rev-parse HEAD``."""
    if os.environ.get("RINGCONTACT_TEST_SEED"):
        return int(os.environ["RINGCONTACT_TEST_SEED"])
    head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=Path(__file__).parent, capture_output=True, text=True)
    return int(head.stdout.strip()[:8], 16) if head.returncode == 0 and head.stdout.strip() else FALLBACK_SEED


def checked_speeds(errors, n_speeds: int, rng, converged: float, tries_per_speed: int,
                   rpm_range=(6000.0, 18000.0)) -> tuple[list, list]:
    """Draw speeds (rpm, 0.1 rpm) uniformly over ``rpm_range`` from ``rng`` until ``n_speeds`` have a reference:
    ``errors(rpm)`` gives ``(error, reference convergence)`` or None (the transient left the law's domain); a draw
    whose reference did not converge to ``converged`` is skipped. Returns ``(checked [(rpm, error)], skipped
    [(rpm, why)])``, both printed."""
    checked, skipped = [], []
    for _ in range(tries_per_speed * n_speeds):
        if len(checked) == n_speeds:
            break
        rpm = round(float(rng.uniform(*rpm_range)), 1)
        got = errors(rpm)
        if got is None or got[1] > converged:
            skipped.append((rpm, "transient beyond the law's domain" if got is None else f"reference {got[1]:.1e}"))
            continue
        checked.append((rpm, got[0]))
    print("checked", [(r, f"{e:.1e}") for r, e in checked], "skipped", skipped)
    return checked, skipped
