"""`python3 dev.py demo` rebuilds reports/published/ byte for byte on any machine of the kind.

Measured before reports/digits.py: on another 2-core machine of the same kind (numpy without the AVX-512
kernels) the demo changed five forces of ``accuracy-table2.csv`` in the 10th significant digit and redrew
``accuracy-force-displacement.svg``; the same happened here with ``NPY_DISABLE_CPU_FEATURES`` set. This test
rebuilds the demo's reports in a fresh process with numpy's dispatched SIMD kernels switched off and OpenBLAS
on its oldest kernel (``OPENBLAS_CORETYPE=Prescott``), and compares every file with the committed one.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PUBLISHED = ROOT / "reports" / "published"
#: what the demo writes (reports/cli/report.py BUILDERS: laws, accuracy); PNGs depend on the font rasteriser
#: as well, and are compared like the rest
DEMO_PREFIXES = ("laws-vs-paper", "accuracy-")


def _dispatched_features() -> str:
    """numpy's dispatched SIMD targets this CPU has (switching them off changes the kernels numpy runs)."""
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
    return " ".join(f for f in __cpu_dispatch__ if __cpu_features__.get(f))


@pytest.mark.parametrize("path", ["other-simd-and-blas", "as-is"])
def test_the_demo_rebuilds_the_committed_reports_byte_for_byte(path, tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg", OPENBLAS_NUM_THREADS="1")
    if path == "other-simd-and-blas":
        env["OPENBLAS_CORETYPE"] = "Prescott"
        feats = _dispatched_features()
        if feats:
            env["NPY_DISABLE_CPU_FEATURES"] = feats
    proc = subprocess.run([sys.executable, "-m", "reports.cli", "report", "--out", str(tmp_path)], cwd=ROOT, env=env,
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    written = sorted(p.name for p in tmp_path.iterdir())
    committed = sorted(p.name for p in PUBLISHED.iterdir() if p.name.startswith(DEMO_PREFIXES))
    assert written == committed
    differ = [n for n in written if (tmp_path / n).read_bytes() != (PUBLISHED / n).read_bytes()]
    assert not differ, f"{differ} differ from reports/published/: not reproducible at the stated precision " \
                       "(reports/digits.py), or stale (run `python3 dev.py demo`)"
