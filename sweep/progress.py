"""Progress on a terminal: one line for a sweep (count, rate, time left), and the events of a long computation.

:class:`Progress` is used by :func:`sweep.run.run_sweep` and by the FEM dataset sweeps. It writes only when
its stream is a terminal and the ``CI`` environment variable is unset (or when told to, ``enabled=True``:
a job's ``--progress``), so piped output, log files and CI runs stay clean.

Long computations that are not sweeps (a first compile, a shooting orbit, a branch) say what they are doing
through :func:`report`: a call that costs nothing unless a job installed a listener with :func:`reporting`
(the command line: ``reports/cli/_scene_options.py``); :class:`Elapsed` shows the seconds spent on a step that
reports nothing (the first compile of the step loop).
"""
from __future__ import annotations

import contextlib
import contextvars
import math
import os
import sys
import threading
import time

_LISTENER: contextvars.ContextVar = contextvars.ContextVar("ringcontact_progress_listener", default=None)


def report(kind: str, **fields) -> None:
    """Tell the listener installed by :func:`reporting` (if any) that ``kind`` happened, with ``fields``:
    ``transient`` (``revs``, ``max_revs``), ``newton`` (``iteration``, ``residual``), ``attempt`` (a finished
    Newton attempt: ``period_revs``, ``transient_revs``, ``iterations``, ``residual``, ``converged``),
    ``branch_point`` (``points``, ``max_points``, ``parameter``, ``start``, ``end``: the time left is from the
    share of the range or of the points done, whichever is larger)."""
    listener = _LISTENER.get()
    if listener is not None:
        listener(kind, fields)


@contextlib.contextmanager
def reporting(listener):
    """Send :func:`report` calls made in this context (this thread) to ``listener(kind, fields)``."""
    token = _LISTENER.set(listener)
    try:
        yield listener
    finally:
        _LISTENER.reset(token)


def on_terminal(stream=None, force: bool | None = None) -> bool:
    """Whether progress goes to ``stream`` (default stderr): ``force`` True/False decides; None: a terminal and
    no ``CI`` environment variable."""
    if force is not None:
        return bool(force)
    stream = stream if stream is not None else sys.stderr
    return bool(getattr(stream, "isatty", lambda: False)()) and not os.environ.get("CI")


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
        self.enabled = on_terminal(self.stream, enabled)
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


def eta_text(seconds: float) -> str:
    """``1m05s`` (``?`` when not finite)."""
    return f"{int(seconds // 60)}m{int(seconds % 60):02d}s" if math.isfinite(seconds) and seconds >= 0 else "?"


class Line:
    """One status line rewritten in place on a terminal (``\\r``); silent when not enabled (:func:`on_terminal`).
    :meth:`show` replaces the text, :meth:`close` ends the line."""

    def __init__(self, label: str, *, stream=None, enabled: bool | None = None):
        self.label = label
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = on_terminal(self.stream, enabled)
        self.t0 = time.monotonic()
        self._width = 0
        self._lock = threading.Lock()

    def show(self, text: str) -> None:
        if not self.enabled:
            return
        line = f"{self.label}: {text}"
        with self._lock:
            self.stream.write("\r" + line.ljust(self._width))
            self.stream.flush()
            self._width = len(line)

    def close(self, text: str | None = None) -> None:
        """End the line (with a last ``text`` if given)."""
        if not self.enabled:
            return
        if text is not None:
            self.show(text)
        with self._lock:
            if self._width:
                self.stream.write("\n")
                self.stream.flush()
            self._width = 0

    def __enter__(self) -> "Line":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class Elapsed(Line):
    """A :class:`Line` that shows the seconds spent (``label: 12 s (what)``) once a second while its context
    runs, for a step that reports nothing of its own (a first compile); nothing when it ends within
    ``quiet_s`` (a compile loaded from the disk cache) or when not enabled."""

    def __init__(self, label: str, what: str = "", *, quiet_s: float = 1.0, stream=None, enabled: bool | None = None):
        super().__init__(label, stream=stream, enabled=enabled)
        self.what, self.quiet_s = what, float(quiet_s)
        self._stop = threading.Event()
        self._thread = None

    def _tick(self) -> None:
        while not self._stop.wait(0.5):
            el = time.monotonic() - self.t0
            if el >= self.quiet_s:
                self.show(f"{el:.0f} s" + (f" ({self.what})" if self.what else ""))

    def __enter__(self) -> "Elapsed":
        if self.enabled:
            self._thread = threading.Thread(target=self._tick, daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        if self._width:     # a step cut short (Ctrl-C, an error) only ends the line
            self.close(f"done in {time.monotonic() - self.t0:.0f} s" if exc[0] is None else None)


class Events(Line):
    """The listener of :func:`reporting` for a shooting orbit or a branch: shows the latest event on its
    :class:`Line` and keeps every finished Newton attempt in :attr:`attempts` (the fields of ``attempt``), so
    that a failure can say what was tried, also when nothing is shown. ``parameter_unit``: ``(unit, factor)``
    of a branch's parameter as shown (a speed in rad/s as rpm: ``("rpm", 30/π)``)."""

    def __init__(self, label: str, *, parameter_unit: tuple[str, float] = ("", 1.0), stream=None,
                 enabled: bool | None = None):
        super().__init__(label, stream=stream, enabled=enabled)
        self.unit, self.factor = parameter_unit
        self.attempts: list[dict] = []
        self.revs, self.max_revs = 0, None

    def __call__(self, kind: str, f: dict) -> None:
        if kind == "transient":
            self.revs, self.max_revs = int(f["revs"]), f.get("max_revs")
            self.show(f"transient {self.revs}/{self.max_revs} rev")
        elif kind == "newton":
            self.show(f"after {self.revs} transient rev: Newton iteration {f['iteration']}, residual "
                      f"{f['residual']:.2e}")
        elif kind == "attempt":
            self.attempts.append(dict(f))
            self.show(f"attempt {len(self.attempts)} (period {f['period_revs']} rev, after {f['transient_revs']} "
                      f"transient rev): residual {f['residual']:.2e}, "
                      f"{'converged' if f['converged'] else 'not converged'}")
        elif kind == "branch_point":
            span = f["end"] - f["start"]
            frac = min(max((f["parameter"] - f["start"]) / span, 0.0), 1.0) if span else 0.0
            done = max(frac, f["points"] / f["max_points"])     # the branch ends at the range's end or its last point
            el = time.monotonic() - self.t0
            left = el * (1.0 - done) / done if done > 0 else math.inf
            self.show(f"point {f['points']} (at most {f['max_points']}) at {f['parameter'] * self.factor:.1f} "
                      f"{self.unit}, {100 * frac:.0f} % of the range, ~{eta_text(left)} left")
