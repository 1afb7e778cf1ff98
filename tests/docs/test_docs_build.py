"""The documentation site builds with warnings as errors, and its generated pages are complete.

One ``sphinx-build -W --keep-going -b html docs <tmp>`` (the command of docs/conf.py and the README),
shared by the tests below: the build must succeed, and the generated pages must carry every job,
sub-command and option of the command line (read from the parsers), every key of the scene schema,
every public module's API section and every gallery example.
"""
from __future__ import annotations

import html
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"



def _require_tools() -> None:
    """Sphinx and MyST come with the test extra: missing, the build fails here rather than being skipped
    (a skipped build would let CI pass without building the docs)."""
    import importlib.util
    missing = [m for m in ("sphinx", "myst_parser") if importlib.util.find_spec(m) is None]
    assert not missing, f"{missing} not installed: pip install -e '.[test]' (or '.[docs]')"


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    _require_tools()
    out = tmp_path_factory.mktemp("html")
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
                          "-d", str(out / ".doctrees"), str(DOCS), str(out)],
                         cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, f"sphinx-build failed:\n{run.stdout[-3000:]}\n{run.stderr[-6000:]}"
    assert "WARNING" not in run.stderr and "ERROR" not in run.stderr, run.stderr[-6000:]
    return out


def _text(site: Path, page: str) -> str:
    raw = (site / page).read_text(encoding="utf-8")
    return html.unescape(re.sub(r"<[^>]+>", "", raw))


def test_site_builds_with_every_page(site):
    for page in ("index", "quickstart", "laws", "fem", "scenes", "orbits", "cli", "gallery", "api/index",
                 "reference/contact-laws", "reference/fem-notes"):
        assert (site / f"{page}.html").is_file(), page
    # the Markdown reference notes are included as they are: their headings reach the HTML
    assert "11. Open questions" in _text(site, "reference/contact-laws.html")
    assert "scikit-fem 12 API facts" in _text(site, "reference/fem-notes.html")


def test_cli_reference_has_every_job_subcommand_and_option(site):
    sys.path.insert(0, str(DOCS / "_ext"))
    from cli_parsers import arguments, job_parsers, subparsers

    from reports.cli import JOBS
    text = _text(site, "cli.html")
    n = 0
    for job in JOBS:
        assert f"ringcontact {job}" in text, job
        for command, parser in job_parsers(job):
            assert command in text
            todo = [(command, parser)] + [(f"{command} {name}", sub) for name, sub in subparsers(parser)]
            for cmd, p in todo:
                assert cmd in text, cmd
                for arg in arguments(p):
                    assert arg.name in text, (cmd, arg.name)
                    if arg.help:
                        assert arg.help[:40] in " ".join(text.split()), (cmd, arg.name)
                    n += 1
    assert n > 150                          # the walk saw the options (guards an empty capture)


def test_scene_reference_has_every_key(site):
    schema = json.loads((DOCS / "scene.schema.json").read_text(encoding="utf-8"))
    text = _text(site, "scenes.html")
    for table, prop in schema["properties"].items():
        assert table in text
        for key in prop.get("items", prop).get("properties", {}):
            assert key in text, (table, key)


def test_api_and_gallery_pages(site):
    sys.path.insert(0, str(DOCS / "_ext"))
    from ringcontact_docs import example_files, public_modules

    for package in ("ringcontact", "contact", "sweep", "fem_reference", "rotor", "reports"):
        text = _text(site, f"api/{package}.html")
        for module in public_modules(package):
            assert module in text, module
    assert "conformal_force" in _text(site, "api/contact.html")
    gallery = _text(site, "gallery.html")
    for path in example_files():
        assert f"docs/examples/{path.name}" in gallery


def test_gallery_shows_each_example_output_and_figure(site):
    """Every example was run by the build: its printed output is on the page (the cached
    ``docs/_generated/gallery/<stem>.txt``, first line checked) and its figure is an image on the page
    whose file the site holds, a PNG of real content (> 10 kB: a blank 900×360 Agg canvas is ~3 kB)."""
    sys.path.insert(0, str(DOCS / "_ext"))
    from gallery_run import OUT
    from ringcontact_docs import example_files

    raw = (site / "gallery.html").read_text(encoding="utf-8")
    text = " ".join(_text(site, "gallery.html").split())
    images = re.findall(r'<img alt="figure of ([\w.]+)" class="gallery-figure" src="([^"]+)"', raw)
    assert sorted(name for name, _ in images) == sorted(p.name for p in example_files())
    for name, src in images:
        data = (site / src).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000, name
        first = (OUT / f"{Path(name).stem}.txt").read_text(encoding="utf-8").strip().splitlines()[0]
        assert " ".join(first.split()) in text, name


def test_gallery_screenshot_shows_every_figure(site, tmp_path):
    """The gallery page as a browser draws it (headless Chromium, docs/_ext/screenshots.py): the figures
    are on the rendered page, not only in the HTML. Each example's figure draws its first series in
    matplotlib's first colour (#1f77b4), which nothing else on the page uses: the screenshot must show
    that colour in as many separate bands down the page as there are figures."""
    sys.path.insert(0, str(DOCS / "_ext"))
    import matplotlib.image as mpimg
    import numpy as np
    from ringcontact_docs import example_files
    from screenshots import chromium, screenshot

    assert chromium() is not None, "chromium not installed (python3 dev.py test installs it with apt)"
    img = mpimg.imread(screenshot(site / "gallery.html", tmp_path / "gallery.png"))[..., :3]
    blue = np.all(np.abs(img - np.array([0x1F, 0x77, 0xB4]) / 255) < 6 / 255, axis=-1)
    rows = np.flatnonzero(blue.sum(axis=1) > 0)
    bands = 1 + int(np.sum(np.diff(rows) > 150)) if rows.size else 0
    assert blue.sum() > 300 * len(example_files())
    assert bands == len(example_files()), (bands, img.shape)


def test_tests_cited_by_the_pages_exist():
    """A test the hand-written pages name as evidence (``test_...``) is defined in tests/."""
    cited = set()
    for page in DOCS.glob("*.rst"):
        cited |= set(re.findall(r"``(test_\w+)``", page.read_text(encoding="utf-8")))
    assert len(cited) >= 5
    defined = set()
    for path in (ROOT / "tests").rglob("test_*.py"):
        defined |= set(re.findall(r"^def (test_\w+)", path.read_text(encoding="utf-8"), re.M))
    assert cited <= defined, sorted(cited - defined)
