"""The source tree keeps the shape DESIGN.md and the README describe.

Walks every module of the suite's packages with :mod:`ast` (nothing is imported), builds the
import graph (imports inside functions included) and checks the rules of the layout:

- no import circle between modules (strongly connected components of size > 1);
- no source module over 600 lines, no plain-Python function over 80 (numba-compiled ones exempt);
- a layer imports only layers below it: contact < sweep < fem_reference, rotor < reports < ringcontact (the
  public Python API, which nothing imports);
  inside rotor: model < linear, dynamics < periodic < studies;
- ``rotor/`` is split into stage sub-packages and holds no loose modules;
- one sweep module: the resumable-store and progress machinery is defined only in ``sweep/``;
- package data is located through importlib.resources: no module names its own ``__file__`` except
  the few listed in :data:`OWN_FILE_USES` (source stamps, checkout detection, git), once each.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("contact", "sweep", "fem_reference", "rotor", "reports", "ringcontact")
MAX_LINES = 600
MAX_FUNCTION_LINES = 80

# Layer rank of a module by its dotted prefix (longest prefix wins); an import must not go to a
# higher rank. Equal ranks may import each other's modules, circles are caught separately.
RANKS = {
    "contact": 0,
    "sweep": 1,
    "fem_reference": 2,
    "rotor": 2, "rotor.model": 2, "rotor.linear": 3, "rotor.dynamics": 3, "rotor.periodic": 4, "rotor.studies": 5,
    "reports": 6,
    "ringcontact": 7,
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
    for stage in ("model", "linear", "dynamics", "periodic", "studies"):
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


# The modules that may name their own file, and why: none of them locates data shipped in the package
# (calibrated laws, scenes, datasets, notes: read through importlib.resources, contact/package_data.py).
OWN_FILE_USES = {
    "contact.compiled_cache": "which .py sources belong to the suite, for the numba cache's source stamps",
    "contact.stamp": "a source checkout (pyproject.toml beside the packages) or an installed wheel",
    "sweep.provenance": "the git repository of a source checkout, for code_revision",
}


def _own_file_lines(tree: ast.AST) -> list[int]:
    """Lines naming ``__file__`` (a name or an attribute), except as the first argument of
    ``compiled_with(__file__, ...)`` (the numba cache's stamp of the module's own source)."""
    stamped = {id(n.args[0]) for n in ast.walk(tree)
               if isinstance(n, ast.Call) and getattr(n.func, "id", getattr(n.func, "attr", None)) == "compiled_with"
               and n.args and isinstance(n.args[0], ast.Name) and n.args[0].id == "__file__"}
    return sorted({n.lineno for n in ast.walk(tree) if id(n) not in stamped and (
        (isinstance(n, ast.Name) and n.id == "__file__") or (isinstance(n, ast.Attribute) and n.attr == "__file__"))})


def test_package_data_is_read_through_importlib_resources():
    uses = {name: _own_file_lines(ast.parse(path.read_text())) for name, path in MODULES.items()}
    offenders = {name: lines for name, lines in uses.items() if lines and name not in OWN_FILE_USES}
    assert offenders == {}, "locate shipped data with contact.package_data.shipped(...), not __file__"
    # each allowed module names its file once (its stated use), so a data read added beside it fails too
    assert {name: len(uses[name]) for name in OWN_FILE_USES} == {name: 1 for name in OWN_FILE_USES}


def test_the_own_file_check_finds_a_data_read():
    bad = ('SCENES = Path(__file__).resolve().parents[1] / "scenes"\n'
           'NOTES = os.path.join(os.path.dirname(__file__), "notes")\nx = sys.modules[__name__].__file__\n')
    assert _own_file_lines(ast.parse(bad)) == [1, 2, 3]
    assert _own_file_lines(ast.parse("compiled_with(__file__, ['contact._kernel'])\n")) == []
    assert _own_file_lines(ast.parse("compiled_with(__file__, [])\nROOT = Path(__file__).parent\n")) == [2]
