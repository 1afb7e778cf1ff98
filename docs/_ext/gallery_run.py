"""Run the gallery's worked examples for the documentation build: their printed output and figure.

Each worked example of ``docs/examples/`` is run in its own Python process (matplotlib's Agg backend, the
repository on the path): its ``main()`` (or ``gallery()``, where ``main()`` runs longer than a build should
wait) prints the walk-through and returns a matplotlib figure,
saved as ``docs/_generated/gallery/<stem>.png`` beside ``<stem>.txt`` (the printed output). A run is
kept while nothing it depends on changed: the key is the SHA-256 of the example and of every
``.py`` and ``.json`` file of the packages (``<stem>.key``), so a second build costs nothing and a
changed law or integrator runs the examples again. A failing example fails the build (the
directive reports it as an error). ``docs/_generated/`` is not committed. :func:`run_examples` runs
the examples that are not up to date side by side, one process each on up to as many cores as the machine
has (they ran one after the other: the seven took 17 s of processor time with numba's cache warm, 69 s
of wall time at load 14, waited for one by one).
"""
from __future__ import annotations

import hashlib
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
OUT = DOCS / "_generated" / "gallery"
PACKAGES = ("contact", "sweep", "fem_reference", "rotor", "reports", "ringcontact")
RUNNER = r"""
import sys, runpy
import matplotlib
matplotlib.use("Agg")
mod = runpy.run_path(sys.argv[1], run_name="gallery")
fig = mod["gallery"]() if "gallery" in mod else mod["main"]()
if fig is not None:
    fig.savefig(sys.argv[2], dpi=100)
"""


def _key(example: Path) -> str:
    h = hashlib.sha256(example.read_bytes())
    for pkg in PACKAGES:
        base = ROOT / pkg
        if not base.is_dir():
            continue
        for path in sorted(base.rglob("*")):
            if path.suffix in (".py", ".json") and "__pycache__" not in path.parts:
                h.update(str(path.relative_to(ROOT)).encode())
                h.update(path.read_bytes())
    return h.hexdigest()


def run_example(example: Path, timeout_s: float = 900.0) -> tuple[str, Path | None]:
    """``(printed output, figure PNG or None)`` of one example, from the cache when up to date.

    Raises ``RuntimeError`` with the example's error output when it fails.
    """
    OUT.mkdir(parents=True, exist_ok=True)
    key_file, text_file, png = (OUT / f"{example.stem}{s}" for s in (".key", ".txt", ".png"))
    key = _key(example)
    if key_file.is_file() and key_file.read_text() == key and text_file.is_file():
        return text_file.read_text(encoding="utf-8"), (png if png.is_file() else None)
    png.unlink(missing_ok=True)
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run([sys.executable, "-c", RUNNER, str(example), str(png)], cwd=ROOT, env=env,
                         capture_output=True, text=True, timeout=timeout_s)
    if run.returncode != 0:
        raise RuntimeError(f"{example.name} failed (exit {run.returncode}):\n{run.stderr[-3000:]}")
    text_file.write_text(run.stdout, encoding="utf-8")
    key_file.write_text(key)
    return run.stdout, (png if png.is_file() else None)


def run_examples(examples, workers: int | None = None) -> dict:
    """``{example: (printed output, figure PNG or None) or the exception it raised}`` of every example, each run
    by :func:`run_example` in a process of its own, up to ``workers`` at a time (default: the machine's cores,
    at most 4). The examples' processes share nothing but numba's disk cache, whose entries numba writes
    atomically."""
    examples = list(examples)
    workers = max(1, min(workers or min(os.cpu_count() or 1, 4), len(examples) or 1))

    def one(example):
        try:
            return run_example(example)
        except Exception as exc:             # reported by the directive, as a single run's error
            return exc

    with ThreadPoolExecutor(max_workers=workers) as pool:
        return dict(zip(examples, pool.map(one, examples)))
