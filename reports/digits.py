"""The precision of the published reports: every number a demo report writes or draws is rounded here first.

Round-off differs between machines of one kind (numpy's SIMD kernels and the BLAS path change the 10th
significant digit of a calibrated law's force), so a report written at full precision is byte-identical only
on the machine that wrote it. Rounded to :data:`DIGITS` significant digits, before a value is written to a CSV
or handed to matplotlib, the rebuilt files are the committed ones on any machine of the kind, unless a value
lies within round-off of a rounding boundary (a chance of about 1e-10 / 1e-7 per value).
"""
from __future__ import annotations

import numpy as np

#: significant digits of every published value (forces to 1e-7 relative, far below the FEM's 1e-5-1e-3 error)
DIGITS = 7
#: decimals of a published percentage (1e-6 of a force, the same precision as ``DIGITS`` near 100 %)
PCT_DECIMALS = 4


def rounded(values, digits: int = DIGITS) -> np.ndarray:
    """``values`` (any shape) rounded to ``digits`` significant digits, as :func:`cell` writes them;
    NaN and inf pass through."""
    a = np.asarray(values, dtype=float)
    return np.array([float(f"{v:.{digits}g}") for v in a.ravel()]).reshape(a.shape)


def rounded_pct(values) -> np.ndarray:
    """Percentages rounded to :data:`PCT_DECIMALS` decimals, as :func:`pct` writes them. A percentage that is a
    small difference of two large numbers (a held-out error of 0.05 %) keeps the round-off of those numbers
    relative to itself, so it is rounded in absolute terms, never to significant digits."""
    return np.round(np.asarray(values, dtype=float), PCT_DECIMALS)


def cell(value: float, digits: int = DIGITS) -> str:
    """One published number as text: ``digits`` significant digits."""
    return f"{value:.{digits}g}"


def pct(value: float) -> str:
    """One published percentage as text: :data:`PCT_DECIMALS` decimals."""
    return f"{value:.{PCT_DECIMALS}f}"
