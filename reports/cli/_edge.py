"""What every job's command line shares: one error format, typed-input checks, output checks.

* :class:`Parser`: an ``argparse`` parser whose errors are ONE line on stderr and exit status 2:
  ``ringcontact JOB: error: --flag = VALUE UNIT: what is allowed``.
* :func:`quantity` / :func:`count`: ``type=`` callables that parse a number, refuse NaN/inf and
  values outside its plausible range (:mod:`contact.plausible`), and echo the value as typed.
* :func:`out_dir` / :func:`out_file` / :func:`in_file` / :func:`in_dir`: outputs are checked before
  any computing (a probe file is created and removed), inputs must exist and be of the right kind.
* :func:`fail`: the one line for a :class:`~contact.errors.RingContactError` (exit status from the
  exception class: 2 for bad input, 1 for a failed computation).
"""
from __future__ import annotations

import argparse
import math
import os
import re
import sys
import tempfile
from pathlib import Path

from contact import plausible
from contact.errors import RingContactError

#: where the report jobs write by default, relative to the working directory (the committed copy when run
#: from the repository root; never the installed package's folder): ``report``, ``study publish``,
#: ``fem-report``, ``fem-paper``, ``fem3d report`` share it
PUBLISHED = "reports/published"

_ARG = re.compile(r"^argument ([^:]+): (.*)$", re.S)


class Parser(argparse.ArgumentParser):
    """``argparse.ArgumentParser`` with one-line errors (exit 2) and ``--help`` unchanged."""

    def error(self, message: str):   # noqa: D401 - argparse hook
        m = _ARG.match(message)
        if m:
            flag, rest = m.group(1).split("/")[0], m.group(2)
            message = f"{flag} = {rest[1:]}" if rest.startswith("=") else f"{flag}: {rest}"
        message = " ".join(message.split())
        self.exit(2, f"{self.prog}: error: {message}\n")


def fail(prog: str, exc: BaseException) -> int:
    """Print ``PROG: error: MESSAGE`` (one line) and return the exception's exit status."""
    print(f"{prog}: error: {' '.join(str(exc).split())}", file=sys.stderr)
    return int(getattr(exc, "exit_status", 2))


def quantity(name: str, low: float | None = None, high: float | None = None, why: str = ""):
    """A ``type=`` for a physical input whose plausible range is ``contact.plausible.RANGES[name]``, narrowed
    to ``[low, high]`` where the job itself accepts less (``why`` says why; the job imports the same bound).
    The callable carries its bounds (``.name``, ``.low``, ``.high``, ``.unit``) for tests that walk parsers."""
    lo, hi, unit, lo_in, hi_in, _ = plausible.RANGES[name]
    u = "" if unit == "-" else f" {unit}"

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"= {text}{u}: not a number") from None
        if not plausible.inside(name, value):
            why_ = "must be finite" if not math.isfinite(value) else f"must be {plausible.range_text(name)}"
            raise argparse.ArgumentTypeError(f"= {text}{u}: {why_}")
        if (low is not None and value < low) or (high is not None and value > high):
            a, b = (lo if low is None else low), (hi if high is None else high)
            raise argparse.ArgumentTypeError(f"= {text}{u}: must be in [{a:g}, {b:g}]{u}" + (f" ({why})" if why else ""))
        return value
    parse.__name__ = name
    parse.name, parse.unit = name, unit
    parse.low = (lo, lo_in) if low is None or low < lo else (low, True)
    parse.high = (hi, hi_in) if high is None or high > hi else (high, True)
    return parse


def count(lo: int, hi: int, what: str = ""):
    """A ``type=`` for a whole number in ``[lo, hi]`` (``what`` names the unit, e.g. 'points')."""
    w = f" {what}" if what else ""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"= {text}{w}: not a whole number") from None
        if not lo <= value <= hi:
            raise argparse.ArgumentTypeError(f"= {text}{w}: must be in [{lo}, {hi}]")
        return value
    parse.__name__ = "count"
    parse.name, parse.unit, parse.low, parse.high = "count", what, (lo, True), (hi, True)
    return parse


#: the whole-number options the jobs share, ``(low, high, unit)`` as :func:`count` takes them: the command line's
#: ``type=count(*COUNTS[key])`` and the Python API (ringcontact/_checks.py) read the same bounds
COUNTS = {
    "steps_per_rev": (16, 100000, ""),          # Newmark steps per revolution (simulate, rotor response, orbit, study)
    "record_per_rev": (1, 100000, ""),          # recorded samples per revolution (simulate, rotor response)
    "period_revs": (1, 8, "revolutions"),       # the period an orbit is looked for at (orbit)
    "max_points": (2, 5000, "points"),          # most orbits of a branch (branch)
    "modes": (1, 200, ""),                      # modes of a rotor model (rotor modes, campbell …)
    "elements": (1, 64, ""),                    # elements per shaft segment (every rotor job)
    "speeds": (2, 2000, ""),                    # speeds of a Campbell diagram or an unbalance response (--points)
    "study_speeds": (1, 2000, ""),              # speeds of a study's cascade (study cascade --points)
    "max_revs": (24, 100000, "revolutions"),    # transient cap of a steady state (SteadyStateOptions.min_revs up)
}


#: bytes a written name may grow by: a temporary ``.NAME.PID.XXXXXXXX.tmp`` (contact.files) or a prefix's
#: longest suffix (``-misalignment.png``)
NAME_GROWTH = 32


def _probe(path: Path, kind: str) -> Path:
    """Raise ``ArgumentTypeError`` unless ``path`` can be written as a ``kind`` ('dir' or 'file')."""
    shown = str(path)
    if not shown.strip():
        raise argparse.ArgumentTypeError(f"= '': must name a {'directory' if kind == 'dir' else 'file'}")
    grows = NAME_GROWTH if kind == "file" else 0       # the file's own name, not its folders'
    too_long = [part for part in path.parts[:-1] if len(os.fsencode(part)) > 255] + (
        [path.name] if len(os.fsencode(path.name)) + grows > 255 else [])
    if too_long or len(os.fsencode(shown)) + NAME_GROWTH > 4096:
        raise argparse.ArgumentTypeError(f"= {shown[:60]}… ({len(shown)} characters): a name longer than the file "
                                         f"system takes (255 bytes a name, {255 - NAME_GROWTH} for a file the job "
                                         "writes, 4096 a path); a shorter name")
    try:
        return _probe_kind(path, kind, shown)
    except OSError as exc:            # a path the system refuses to look at (permissions, loops)
        raise argparse.ArgumentTypeError(f"= {shown}: cannot be used ({exc.strerror or exc})") from None


def _probe_kind(path: Path, kind: str, shown: str) -> Path:
    if path.exists():
        if kind == "dir" and not path.is_dir():
            raise argparse.ArgumentTypeError(f"= {shown}: is a file, a directory is needed")
        if kind == "file" and path.is_dir():
            raise argparse.ArgumentTypeError(f"= {shown}: is a directory, a file name is needed")
        if kind == "file" and not path.is_file():    # /dev/null: the atomic rename would replace the device
            raise argparse.ArgumentTypeError(f"= {shown}: not a regular file (a device, pipe or socket); name a file")
    base = path if (kind == "dir" and path.is_dir()) else path.parent
    while not base.exists():
        base = base.parent
    if not base.is_dir():
        raise argparse.ArgumentTypeError(f"= {shown}: {base} is a file, not a directory")
    try:
        fd, tmp = tempfile.mkstemp(prefix=".ringcontact-probe-", dir=base)
        os.close(fd)
        os.unlink(tmp)
    except OSError as exc:
        raise argparse.ArgumentTypeError(f"= {shown}: cannot write in {base} ({exc.strerror or exc})") from None
    return path


def _named(text: str, what: str) -> str:
    if not str(text).strip():
        raise argparse.ArgumentTypeError(f"= '': must name a {what}")
    return str(text)


def out_dir(text: str) -> Path:
    """A ``type=`` for an output directory (created later by the job; checked writable now)."""
    return _probe(Path(_named(text, "directory")), "dir")


def out_file(text: str) -> Path:
    """A ``type=`` for an output file."""
    return _probe(Path(_named(text, "file")), "file")


def out_prefix(text: str) -> str:
    """A ``type=`` for an output PREFIX (PREFIX.png, PREFIX.svg ...)."""
    if _named(text, "file prefix").endswith(("/", ".")) or Path(text).is_dir():
        raise argparse.ArgumentTypeError(f"= {text}: a prefix needs a file name part (e.g. {text.rstrip('/')}/campbell)")
    _probe(Path(text + ".png"), "file")
    return text


def in_file(text: str) -> Path:
    """A ``type=`` for an input file that must exist and be a regular file."""
    p = Path(text)
    if not text.strip():
        raise argparse.ArgumentTypeError("= '': must name a file")
    if not p.exists():
        raise argparse.ArgumentTypeError(f"= {text}: no such file")
    if p.is_dir():
        raise argparse.ArgumentTypeError(f"= {text}: is a directory, a file is needed")
    if not p.is_file():       # a FIFO, a device (a link to /dev/zero), a socket: reading it blocks or never ends
        raise argparse.ArgumentTypeError(f"= {text}: not a regular file (a pipe, device or socket); a file is needed")
    return p


def in_dir(text: str) -> Path:
    """A ``type=`` for an input directory that must exist."""
    p = Path(text)
    if not text.strip():
        raise argparse.ArgumentTypeError("= '': must name a directory")
    if not p.is_dir():
        raise argparse.ArgumentTypeError(f"= {text}: {'is a file' if p.exists() else 'no such directory'}, "
                                         "a directory is needed")
    return p


def guard(prog: str, func, *args) -> int:
    """Run ``func(*args)`` and turn a suite error into the one-line message and its exit status."""
    try:
        return int(func(*args) or 0)
    except RingContactError as exc:
        return fail(prog, exc)


_UNIT_SUFFIX = {"_n": "_N", "_nm": "_Nm", "_pa": "_Pa", "_n_m": "_N_m"}


def unit_keys(value):
    """The JSON key convention of every job: ``force_N``, ``moment_Nm``, ``pressure_Pa`` (SI symbols' case).

    Datasets store ``force_n``/``moment_nm`` (their committed schema); the command line shows the
    same fields with the unit written as its symbol, so ``nm`` can never read as nanometres.
    """
    if isinstance(value, dict):
        out = {}
        for k, v in value.items():
            for old, new in _UNIT_SUFFIX.items():
                if isinstance(k, str) and k.endswith(old):
                    k = k[: -len(old)] + new
                    break
            out[k] = unit_keys(v)
        return out
    if isinstance(value, list):
        return [unit_keys(v) for v in value]
    return value


def check_arg(parser: argparse.ArgumentParser, flag: str, kind, text: str):
    """Apply a ``type=`` check (``out_dir`` …) after parsing, with the parser's one-line error."""
    try:
        return kind(str(text))
    except argparse.ArgumentTypeError as exc:
        parser.error(f"argument {flag}: {exc}")
