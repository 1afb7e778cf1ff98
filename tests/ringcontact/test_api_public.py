"""The public API needs no private names: the walk-through uses ``import ringcontact`` only, reaches no name that
starts with ``_``, and every name ringcontact exports is documented."""
from __future__ import annotations

import ast
import inspect
from pathlib import Path

import ringcontact as rc

ROOT = Path(__file__).resolve().parents[2]
WALKTHROUGH = ROOT / "docs" / "examples" / "ex07_your_rotor.py"
SUITE = {"contact", "sweep", "fem_reference", "rotor", "reports"}


def private_uses(source: str) -> list[str]:
    """Imports of the suite's inner packages, ``x._name`` attribute reads and ``from … import _name`` in ``source``."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__"):
            found.append(f"line {node.lineno}: .{node.attr}")
        elif isinstance(node, ast.ImportFrom):
            if (node.module or "").split(".")[0] in SUITE:
                found.append(f"line {node.lineno}: from {node.module}")
            found += [f"line {node.lineno}: import {a.name}" for a in node.names if a.name.startswith("_")]
        elif isinstance(node, ast.Import):
            found += [f"line {node.lineno}: import {a.name}" for a in node.names if a.name.split(".")[0] in SUITE]
    return sorted(found, key=lambda s: int(s.split(":")[0].split()[1]))


def test_the_check_finds_private_uses():
    bad = "from rotor.model.scene import load_scene\nimport reports.cli\nx = m._metadata\nfrom ringcontact import _y\n"
    assert private_uses(bad) == ["line 1: from rotor.model.scene", "line 2: import reports.cli",
                                 "line 3: ._metadata", "line 4: import _y"]


def test_the_walkthrough_uses_the_public_api_only():
    source = WALKTHROUGH.read_text(encoding="utf-8")
    assert private_uses(source) == []
    used = {n.attr for n in ast.walk(ast.parse(source))
            if isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name) and n.value.id == "rc"}
    assert used and used <= set(rc.__all__), used - set(rc.__all__)


def test_every_exported_name_exists_and_is_documented():
    assert rc.__version__ and rc.__version__[0].isdigit()
    for name in rc.__all__:
        obj = getattr(rc, name)
        if name != "__version__":
            assert not name.startswith("_") and inspect.getdoc(obj), name
    for name in ("modes", "campbell", "unbalance_response", "simulate", "orbit", "branch", "cascade", "law", "bearing"):
        sig = inspect.signature(getattr(rc, name))
        assert all(p.kind is not p.VAR_KEYWORD for p in sig.parameters.values()), name   # named options only
