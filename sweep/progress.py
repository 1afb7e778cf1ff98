"""One progress line for a sweep: count, rate and time left on a terminal; silent otherwise.

Used by :func:`sweep.run.run_sweep` and by the FEM dataset sweeps. It writes only when its
stream is a terminal and the ``CI`` environment variable is unset, so piped output, log files
and CI runs stay clean.
"""
from __future__ import annotations

import math
import os
import sys
import time


class Progress:
    """Count, rate and time left on one terminal line; silent under CI or when not a terminal.

    ``enabled=None`` decides from the stream (``isatty``) and the ``CI`` environment variable.
    Call :meth:`update` once per finished point and :meth:`close` at the end (or use it as a
    context manager).
    """

    def __init__(self, total: int, *, label: str = "sweep", stream=None, enabled: bool | None = None):
        self.total = int(total)
        self.label = label
        self.stream = stream if stream is not None else sys.stderr
        if enabled is None:
            isatty = getattr(self.stream, "isatty", lambda: False)
            enabled = bool(isatty()) and not os.environ.get("CI")
        self.enabled = enabled
        self.done = 0
        self.t0 = time.monotonic()

    def update(self, n: int = 1, note: str = "") -> None:
        """``n`` more points finished; ``note`` names the last one."""
        self.done += n
        if not self.enabled:
            return
        el = time.monotonic() - self.t0
        rate = self.done / el if el > 0 else 0.0
        left = (self.total - self.done) / rate if rate > 0 else math.inf
        eta = f"{int(left // 60)}m{int(left % 60):02d}s" if math.isfinite(left) else "?"
        self.stream.write(f"\r{self.label}: {self.done}/{self.total}  {rate:.2f} pt/s  ~{eta} left  {note[:40]:40s}")
        self.stream.flush()

    def close(self) -> None:
        """End the line (nothing when silent)."""
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()

    def __enter__(self) -> "Progress":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
