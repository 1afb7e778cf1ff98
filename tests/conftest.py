"""Test-session settings shared by every test module."""
import os

# One BLAS thread per process (set before numpy loads): threaded OpenBLAS on 2 shared cores
# made small dense eigenproblems ~100x slower. dev.py sets the same for every job.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MPLBACKEND", "Agg")
