"""One exception family for the whole suite.

Messages name the parameter, its value, its unit and the allowed range, e.g.
``InputError("clearance_m = -5e-05 m: must be > 0")``.
"""
from __future__ import annotations


class RingContactError(Exception):
    """Base class of every error the suite raises on purpose.

    ``exit_status`` is what the command line returns for it: 2 for bad input (the default),
    1 for a computation that failed on good input.
    """

    exit_status = 2


class InputError(RingContactError, ValueError):
    """A parameter is out of range, not finite, or in the wrong unit."""


class ConvergenceError(RingContactError, RuntimeError):
    """A solver did not converge (names the solver, the tolerance and what was reached)."""

    exit_status = 1


class FailedPointsError(RingContactError, RuntimeError):
    """Some points of a sweep or study failed: the job stops before writing figures or reports."""

    exit_status = 1


class DatasetError(RingContactError, OSError):
    """A data or scene file is missing, unreadable, corrupted or of the wrong version."""


class OutsideDomainError(RingContactError, ValueError):
    """A law was asked for a value where it has no solution."""


class OutputError(RingContactError, OSError):
    """An output could not be written after the computing (disk full, folder removed meanwhile)."""

    exit_status = 1
