"""Test-session settings shared by every test module."""
import os

# One BLAS thread per process (set before numpy loads): threaded OpenBLAS on 2 shared cores
# made small dense eigenproblems ~100x slower. dev.py sets the same for every job.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MPLBACKEND", "Agg")


# --------------------------------------------------------------------------- the slow tier in groups
#: how many groups the slow tier (``-m slow``) is split into; each is meant to fit one CI run
SLOW_GROUPS = 8


def pytest_addoption(parser):
    parser.addoption("--slow-group", default=None, metavar="K/N",
                     help="run only the slow tests of group K of N (whole test files, by a hash of the file's path); "
                          "'auto' picks the group from the commit's hash (git rev-parse HEAD)")


def slow_group_of(path: str, n: int) -> int:
    """The group (0 .. n-1) of a test file's slow tests: a stable hash of its path relative to tests/."""
    import zlib
    return zlib.crc32(path.replace(os.sep, "/").encode()) % n


def _wanted_group(spec: str) -> tuple[int, int]:
    if spec == "auto":
        import subprocess
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=os.path.dirname(__file__), capture_output=True, text=True)
        k = int(head.stdout.strip()[:8], 16) if head.returncode == 0 and head.stdout.strip() else 0
        return k % SLOW_GROUPS, SLOW_GROUPS
    import pytest
    try:
        k, n = (int(x) for x in spec.split("/"))
    except ValueError:
        k = n = -1
    if not 0 <= k < n:
        raise pytest.UsageError(f"--slow-group {spec!r}: K/N with whole numbers 0 <= K < N (e.g. 3/8), or 'auto'")
    return k, n


def pytest_configure(config):
    spec = config.getoption("--slow-group")
    if spec:
        _wanted_group(spec)          # a bad value ends the run at once, in one line


def pytest_collection_modifyitems(config, items):
    spec = config.getoption("--slow-group")
    if not spec:
        return
    k, n = _wanted_group(spec)
    here = os.path.dirname(__file__)
    keep, drop = [], []
    for item in items:
        rel = os.path.relpath(str(item.path), here)
        (keep if item.get_closest_marker("slow") is None or slow_group_of(rel, n) == k else drop).append(item)
    config.hook.pytest_deselected(items=drop)
    items[:] = keep
    print(f"slow group {k}/{n}: {sum(1 for i in keep if i.get_closest_marker('slow'))} slow tests")
