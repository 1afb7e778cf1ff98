"""Sphinx configuration of the ringcontact documentation site.

Build from the repository root (warnings are errors, as in CI)::

    .venv/bin/python -m sphinx -W --keep-going -b html docs docs/_build/html

``tests/docs/test_docs_build.py`` runs the same build into a temporary directory.
"""
from __future__ import annotations

import sys
import tomllib
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path[:0] = [str(ROOT), str(DOCS / "_ext")]

_project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
project = "ringcontact"
author = "the ringcontact authors"
copyright = "2026, the ringcontact authors (MIT License)"
release = version = _project["version"]

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",     # numpy-style docstrings
    "sphinx.ext.mathjax",
    "myst_parser",             # only to include docs/reference/*.md unchanged
    "ringcontact_docs",        # generated pages: CLI, scene keys, FEM scenes, API, gallery (docs/_ext/)
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "examples/README.md"]
root_doc = "index"
smartquotes = False        # help texts and option names ("--out") are shown exactly as typed

napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True       # dataclass fields once, as fields of the class (no duplicate attributes)
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_format = "fully-qualified"   # "Scene" alone is ambiguous (fem_reference.scenes, rotor.model.scene)
autodoc_typehints_description_target = "documented"   # the docstrings say what a parameter is; hints add its type
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
myst_heading_anchors = 3
suppress_warnings = []

html_theme = "alabaster"
# a wide page: code and command lines at full width, gallery figures readable (docs/_static/ringcontact.css)
html_theme_options = {"page_width": "min(96%, 1400px)", "sidebar_width": "230px", "body_max_width": "none"}
html_static_path = ["_static"]
html_css_files = ["ringcontact.css"]
html_title = f"ringcontact {release}"
