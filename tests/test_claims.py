"""The registry of published claims (tests/claims.py) is complete and true to the files it quotes.

Every claim is quoted verbatim from its report (a regenerated report that changes the number fails here until the
registry follows); every guarding test exists, parsed with :mod:`ast`, and carries ``pytest.mark.slow`` exactly
when its tier says ``slow``; every Markdown report of reports/published/ has a claim or a stated reason; and the
published list, reports/published/claims.md, is what benchmarks/list_claims.py writes now. Nothing is computed.
"""
from __future__ import annotations

import ast
import importlib.util
from pathlib import Path

import pytest

import claims

ROOT = Path(__file__).resolve().parents[1]
PUBLISHED = ROOT / "reports" / "published"
TIERS = ("default", "slow")


def _load(path: Path, name: str):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _module_names(tree: ast.Module) -> dict[str, ast.AST]:
    """Module-level definitions and assignments by name."""
    names: dict[str, ast.AST] = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names[node.name] = node
        elif isinstance(node, ast.Assign):
            names.update({t.id: node for t in node.targets if isinstance(t, ast.Name)})
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names[node.target.id] = node
    return names


def find_test(source: str, node_id_tail: str) -> ast.FunctionDef | None:
    """The test function ``name`` or ``Class::name`` of a test file's source (parametrize ids dropped)."""
    parts = node_id_tail.split("[", 1)[0].split("::")
    scope: list[ast.stmt] = ast.parse(source).body
    for part in parts[:-1]:
        cls = next((n for n in scope if isinstance(n, ast.ClassDef) and n.name == part), None)
        if cls is None:
            return None
        scope = cls.body
    return next((n for n in scope if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and n.name == parts[-1]),
                None)


def marked_slow(source: str, node_id_tail: str) -> bool:
    """Whether the test carries ``pytest.mark.slow``: a module-level ``pytestmark``, or its decorators, following
    the module-level names they use (a parametrize list whose entries a helper marks slow counts as slow)."""
    tree = ast.parse(source)
    names = _module_names(tree)
    if "pytestmark" in names and "mark.slow" in ast.unparse(names["pytestmark"]):
        return True
    fn = find_test(source, node_id_tail)
    if fn is None:
        raise LookupError(node_id_tail)
    seen, todo = {fn.name}, list(fn.decorator_list)
    while todo:
        node = todo.pop()
        if "mark.slow" in ast.unparse(node):
            return True
        for sub in ast.walk(node):
            if isinstance(sub, ast.Name) and sub.id in names and sub.id not in seen:
                seen.add(sub.id)
                todo.append(names[sub.id])
    return False


def published_reports() -> set[str]:
    """Every Markdown report under reports/published/ (its sub-folders included), relative to the repository."""
    return {str(p.relative_to(ROOT)) for p in PUBLISHED.rglob("*.md")}


def test_entries_are_well_formed():
    assert claims.CLAIMS, "no claim registered"
    for c in claims.CLAIMS:
        assert set(c) == {"report", "claim", "test", "tier"}, c
        assert c["tier"] in TIERS, c
        assert c["claim"].strip() == c["claim"] and "\n" not in c["claim"] and c["claim"], c
        path, sep, name = c["test"].partition("::")
        assert sep and path.startswith("tests/") and path.endswith(".py") and name, c
    keys = [(c["report"], c["claim"], c["test"]) for c in claims.CLAIMS]
    assert len(keys) == len(set(keys)), "an entry is registered twice"
    for u in claims.UNGUARDED:
        assert set(u) == {"report", "claim", "reason"} and u["reason"].strip(), u


@pytest.mark.parametrize("entry", claims.CLAIMS + claims.UNGUARDED, ids=lambda e: f"{e['report']}: {e['claim'][:40]}")
def test_every_claim_is_quoted_verbatim_from_its_file(entry):
    path = ROOT / entry["report"]
    assert path.is_file(), entry["report"]
    assert entry["claim"] in path.read_text(encoding="utf-8"), \
        f"{entry['report']} no longer says {entry['claim']!r}: update tests/claims.py (and benchmarks/list_claims.py)"


def test_every_guarding_test_exists_with_the_registered_tier():
    wrong = []
    for c in claims.CLAIMS:
        path, _, tail = c["test"].partition("::")
        source = (ROOT / path).read_text(encoding="utf-8") if (ROOT / path).is_file() else None
        if source is None or find_test(source, tail) is None:
            wrong.append(f"{c['test']}: no such test")
        elif ("slow" if marked_slow(source, tail) else "default") != c["tier"]:
            wrong.append(f"{c['test']}: registered {c['tier']}, marked otherwise")
    assert wrong == []


SYNTHETIC = '''
import pytest

def _param(x, slow):
    return pytest.param(x, marks=[pytest.mark.slow] if slow else [])

CASES = [_param(1, True), _param(2, False)]
PLAIN = [1, 2]

@pytest.mark.slow
def test_decorated():
    pass

@pytest.mark.parametrize("x", CASES)
def test_through_a_helper(x):
    pass

@pytest.mark.parametrize("x", PLAIN)
def test_plain(x):
    pass

class TestGroup:
    @pytest.mark.slow
    def test_method(self):
        pass
'''


def test_the_slow_mark_is_found_where_it_is():
    """The tier check reads marks as pytest applies them: on the function, through a parametrize list built by a
    helper, on a method, or for the whole module."""
    assert marked_slow(SYNTHETIC, "test_decorated") and marked_slow(SYNTHETIC, "test_through_a_helper")
    assert marked_slow(SYNTHETIC, "TestGroup::test_method")
    assert not marked_slow(SYNTHETIC, "test_plain[1]")
    assert marked_slow("import pytest\npytestmark = pytest.mark.slow\ndef test_x():\n    pass\n", "test_x")
    assert find_test(SYNTHETIC, "test_missing") is None
    with pytest.raises(LookupError):
        marked_slow(SYNTHETIC, "test_missing")


def test_every_published_report_has_a_claim_or_a_reason():
    with_claims = {c["report"] for c in claims.CLAIMS}
    excused = dict(claims.NOT_CLAIMS)
    assert len(excused) == len(claims.NOT_CLAIMS), "a report is excused twice"
    for report, reason in excused.items():
        assert (ROOT / report).is_file(), report
        assert reason.strip() and "\n" not in reason, report
        assert report not in with_claims, f"{report} has claims and is excused"
    assert "reports/published/claims.md" in excused
    missing = sorted(published_reports() - with_claims - set(excused))
    assert missing == [], f"reports with no registered claim and no reason: {missing}"


def test_the_published_list_is_what_the_generator_writes_now():
    render = _load(ROOT / "benchmarks" / "list_claims.py", "list_claims").render
    text = render(claims)
    assert f"{len(claims.CLAIMS)} claims in " in text
    assert (PUBLISHED / "claims.md").read_text(encoding="utf-8") == text, \
        "reports/published/claims.md is stale: run `.venv/bin/python benchmarks/list_claims.py`"
