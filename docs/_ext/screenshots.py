"""Screenshots of built documentation pages, taken by headless Chromium (Debian's ``chromium``).

``python docs/_ext/screenshots.py SITE OUT`` writes ``OUT/<page>.png`` of the gallery pages of a built
site (``SITE``: the ``sphinx-build -b html`` output), cut to the page and at half size for committing. ``tests/docs/test_docs_build.py`` takes the same
screenshots of the site it builds and checks that the figures show on the rendered page;
``python3 dev.py test`` installs Chromium with apt when it is missing (``docs/screenshots/`` holds
the committed copies).
"""
from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

PAGES = ("gallery",)
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--hide-scrollbars",
         "--disable-background-networking", "--disable-component-update", "--disable-sync")


def chromium() -> str | None:
    """The Chromium executable, or None."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def screenshot(page: Path, png: Path, width_px: int = 1400, height_px: int = 24000, timeout_s: float = 120.0) -> Path:
    """Render ``page`` (an HTML file) at ``width_px`` × ``height_px`` into ``png``."""
    exe = chromium()
    if exe is None:
        raise RuntimeError("chromium not found (Debian: apt-get install chromium; python3 dev.py test does it)")
    with tempfile.TemporaryDirectory() as profile:
        run = subprocess.run([exe, *FLAGS, f"--user-data-dir={profile}", f"--window-size={width_px},{height_px}",
                              f"--screenshot={png}", page.resolve().as_uri()],
                             capture_output=True, text=True, timeout=timeout_s)
    if run.returncode != 0 or not png.is_file():
        raise RuntimeError(f"chromium screenshot of {page} failed: {run.stderr[-2000:]}")
    return png


def committed_copy(png: Path, out: Path) -> Path:
    """A copy small enough to commit: blank rows below the page cut off, half the width and height."""
    import matplotlib.image as mpimg
    import numpy as np
    img = mpimg.imread(png)[..., :3]
    rows = np.flatnonzero((img < 0.98).any(axis=(1, 2)))
    img = img[: rows[-1] + 1 if rows.size else img.shape[0]]
    h, w = (img.shape[0] // 2) * 2, (img.shape[1] // 2) * 2
    half = img[:h, :w].reshape(h // 2, 2, w // 2, 2, 3).mean(axis=(1, 3))
    mpimg.imsave(out, half)
    return out


def main(argv: list[str]) -> int:
    site, out = Path(argv[0]), Path(argv[1])
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for page in PAGES:
            print(committed_copy(screenshot(site / f"{page}.html", Path(tmp) / f"{page}.png"), out / f"{page}.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
