"""Documents the code cites exist in the repository; the licence and citation agree with pyproject.toml."""
from __future__ import annotations

import re
import subprocess
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
REFERENCE_NOTES = ("contact-laws.md", "fem-notes.md")
# Files allowed to cite a reference note by its bare name (none left); each entry must still need it.
PENDING_BARE: set[str] = set()


def _tracked(*suffixes: str) -> list[Path]:
    out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True)
    if out.returncode != 0:
        pytest.skip("not a git checkout")
    return [ROOT / p for p in out.stdout.split() if p.endswith(suffixes) and not p.startswith("docs/")
            and (ROOT / p).is_file()]


def test_every_cited_document_exists():
    cited = {}
    for path in _tracked(".py", ".toml", ".md"):
        for m in re.finditer(r"(?<![\w/.-])(docs/[\w./-]+\.md)", path.read_text(encoding="utf-8")):
            cited.setdefault(m.group(1), path.relative_to(ROOT))
    assert {f"docs/reference/{n}" for n in REFERENCE_NOTES} <= cited.keys()
    missing = {doc: str(where) for doc, where in cited.items() if not (ROOT / doc).is_file()}
    assert not missing, missing


def test_reference_notes_are_cited_by_their_repository_path():
    bare = re.compile(r"(?<![\w/-])(?:" + "|".join(re.escape(n) for n in REFERENCE_NOTES) + ")")
    offenders = {str(p.relative_to(ROOT)) for p in _tracked(".py", ".toml")
                 if p != Path(__file__).resolve() and bare.search(p.read_text(encoding="utf-8"))}
    assert offenders == PENDING_BARE, sorted(offenders)


def test_licence_and_citation_agree_with_pyproject():
    assert PROJECT["license"] == "MIT"
    assert (ROOT / "LICENSE").read_text(encoding="utf-8").startswith("MIT License\n")
    cff = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    assert re.search(rf"^version: {re.escape(PROJECT['version'])}$", cff, re.M)
    assert re.search(r"^license: MIT$", cff, re.M)
    assert "doi: 10.3390/act14090422" in cff      # Dai et al. (2025), the source of the model
    assert "## Unreleased (" + PROJECT["version"] + ")" in (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")


# A repository path cited in code, docstrings, help texts, scene files or the hand-written documents.
_CITED_PATH = re.compile(r"(?<![\w/.-])((?:contact|sweep|fem_reference|rotor|reports|docs|tests|benchmarks|build_backend)"
                         r"/[\w./*<>{},-]*\.(?:py|md|json|toml|csv|png|svg|npz|vtu|txt|cff|rst))")
# Cited paths that are not files of the checkout, each with its reason; every entry must still be cited.
NOT_IN_CHECKOUT = {
    "contact/_build.json": "written into the wheel at build time (build_backend/ringcontact_build.py)",
    "docs/examples/exNN.py": "DESIGN.md quotes scikit-fem's layout, not a file of this repository",
    "docs/_generated/gallery/<stem>.png": "written by the docs build (docs/_ext/gallery_run.py), git-ignored",
    "docs/_generated/gallery/<stem>.txt": "written by the docs build (docs/_ext/gallery_run.py), git-ignored",
}


def _cited_paths() -> dict[str, str]:
    out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=ROOT,
                         capture_output=True, text=True)
    if out.returncode != 0:
        pytest.skip("not a git checkout")
    cited: dict[str, str] = {}
    for rel in out.stdout.split():
        if not rel.endswith((".py", ".toml", ".md", ".rst", ".cff")) or rel.startswith("reports/published/"):
            continue                                         # published reports are generated output
        path = ROOT / rel
        if path.is_file():
            for m in _CITED_PATH.finditer(path.read_text(encoding="utf-8")):
                cited.setdefault(m.group(1).rstrip("."), rel)
    return cited


def test_every_cited_repository_file_exists():
    """Paths such as ``rotor/model/elements.py`` name a file that exists; a pattern (``*``, ``<name>``,
    ``{field}``) names at least one."""
    cited = _cited_paths()
    assert len(cited) > 50                       # the walk found the citations (guards an empty walk)
    missing = {}
    for c, where in cited.items():
        pattern = re.sub(r"<[^>]*>|\{[^}]*\}", "*", c)
        found = any(ROOT.glob(pattern)) if "*" in pattern else (ROOT / c).exists()
        if not found and c not in NOT_IN_CHECKOUT:
            missing[c] = where
    assert not missing, missing
    stale = set(NOT_IN_CHECKOUT) - set(cited)
    assert not stale, f"no longer cited, remove from NOT_IN_CHECKOUT: {sorted(stale)}"
