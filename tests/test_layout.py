"""The source tree keeps the shape DESIGN.md and the README describe.

Walks every module of the suite's packages with :mod:`ast` (nothing is imported), builds the
import graph (imports inside functions included) and checks the rules of the layout:

- no import circle between modules (strongly connected components of size > 1);
- no source module over 600 lines, no plain-Python function over 80 (numba-compiled ones exempt);
- a layer imports only layers below it: contact < sweep < fem_reference, rotor < reports;
  inside rotor: model < linear, dynamics < studies;
- ``rotor/`` is split into stage sub-packages and holds no loose modules;
- one sweep module: the resumable-store and progress machinery is defined only in ``sweep/``.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("contact", "sweep", "fem_reference", "rotor", "reports")
MAX_LINES = 600
MAX_FUNCTION_LINES = 80

# Layer rank of a module by its dotted prefix (longest prefix wins); an import must not go to a
# higher rank. Equal ranks may import each other's modules, circles are caught separately.
RANKS = {
    "contact": 0,
    "sweep": 1,
    "fem_reference": 2,
    "rotor": 2, "rotor.model": 2, "rotor.linear": 3, "rotor.dynamics": 3, "rotor.studies": 4,
    "reports": 5,
}


def _modules() -> dict[str, Path]:
    mods = {}
    for pkg in PACKAGES:
        for p in (ROOT / pkg).rglob("*.py"):
            parts = p.relative_to(ROOT).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            mods[".".join(parts)] = p
    return mods


def _edges(mods: dict[str, Path]) -> dict[str, set[str]]:
    edges: dict[str, set[str]] = {m: set() for m in mods}
    for name, path in mods.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[: len(package.split(".")) - node.level + 1]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                candidates = [target] + [f"{target}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                candidates = [a.name for a in node.names]
            else:
                continue
            # the deepest existing module named by the import (a package's __init__ only when
            # the import names the package itself)
            for c in candidates:
                if c in mods and c != name:
                    edges[name].add(c)
    return edges


def _cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in edges:
        if v not in index:
            visit(v)
    return found


def _rank(module: str) -> int:
    parts = module.split(".")
    for n in range(len(parts), 0, -1):
        key = ".".join(parts[:n])
        if key in RANKS:
            return RANKS[key]
    raise KeyError(module)


MODULES = _modules()
EDGES = _edges(MODULES)


def test_walk_finds_the_suite():
    # guards the checks below against walking an empty or wrong tree
    assert len(MODULES) > 60
    assert "rotor.dynamics.production" in MODULES and "sweep" in MODULES


def test_no_import_circle():
    assert _cycles(EDGES) == []


def test_the_cycle_finder_finds_a_circle():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


@pytest.mark.parametrize("module", sorted(MODULES))
def test_module_size(module):
    n = len(MODULES[module].read_text().splitlines())
    assert n <= MAX_LINES, f"{MODULES[module].relative_to(ROOT)} has {n} lines"


def _compiled(node: ast.FunctionDef) -> bool:
    return any("njit" in ast.unparse(d) or "jit(" in ast.unparse(d) for d in node.decorator_list)


def test_no_long_plain_function():
    long = []
    for name, path in MODULES.items():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and not _compiled(node):
                n = node.end_lineno - node.lineno + 1
                if n > MAX_FUNCTION_LINES:
                    long.append(f"{path.relative_to(ROOT)}:{node.lineno} {node.name} ({n} lines)")
    assert long == []


def test_layers_import_downwards():
    upward = [(a, b) for a, targets in EDGES.items() for b in targets if _rank(b) > _rank(a)]
    assert upward == []


def test_rotor_is_split_by_stage():
    loose = sorted(p.name for p in (ROOT / "rotor").glob("*.py") if p.name != "__init__.py")
    assert loose == []
    for stage in ("model", "linear", "dynamics", "studies"):
        assert (ROOT / "rotor" / stage / "__init__.py").is_file()


def test_one_sweep_module():
    """Store, progress and provenance classes/functions exist once, in sweep/."""
    shared = {"ResultStore", "Progress", "code_revision", "package_versions", "run_sweep", "Task"}
    defined: dict[str, list[str]] = {}
    for name, path in MODULES.items():
        for node in ast.parse(path.read_text()).body:
            if isinstance(node, (ast.ClassDef, ast.FunctionDef)) and node.name in shared:
                defined.setdefault(node.name, []).append(name)
    outside = {k: [m for m in v if not m.startswith("sweep")] for k, v in defined.items()}
    assert {k: v for k, v in outside.items() if v} == {}
