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
