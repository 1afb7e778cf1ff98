"""What the accuracy report compares with: the paper's displacement columns and percentages
(Dai et al. 2025 Tables 2–3), the row labels of the laws, the cell format."""
from __future__ import annotations

import numpy as np


PENETRATIONS_MM = (0.01, 0.02, 0.03, 0.04, 0.05)


# Dai et al. (2025) Table 2: |model − FEM|/FEM in %; None = '-'.
PAPER_TABLE2_PCT = {
    "conformal-plane-stress": (12.01, 0.79, 4.37, 5.59, 5.69),
    "johnson": (28.70, 1.18, None, None, None),
    "pereira": (30.60, 29.74, 27.59, 25.59, 23.72),
}


# Dai et al. (2025) Table 3: conformal law with tilt vs its FEM, |%|; rows 0.5′, 1′, 2′.
PAPER_TABLE3_PCT = {0.5: (10.96, 4.11, 0.60, 1.14, 1.76), 1.0: (2.34, 2.87, 2.02, 1.37, 10.51),
                    2.0: (9.26, 2.94, 0.70, 2.71, 4.92)}


LAW_LABELS = {
    "conformal-plane-stress": "conformal, plane stress (paper)",
    "conformal-plane-strain": "conformal, plane strain",
    "johnson": "Johnson",
    "pereira": "Pereira 2015",
    "calibrated-fit": "calibrated (fit on all points)",
    "calibrated-holdout": "calibrated, held out",
}


def pct_cell(v: float) -> str:
    return "–" if not np.isfinite(v) else f"{v:+.2f}"
