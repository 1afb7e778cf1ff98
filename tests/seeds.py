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
