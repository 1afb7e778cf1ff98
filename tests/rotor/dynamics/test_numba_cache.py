"""The cross-module numba cache guard drops stale entries when a dependency changes."""
from pathlib import Path

from rotor.dynamics._numba_cache import drop_stale_cache


def test_stale_cache_entries_dropped_when_dependency_changes(tmp_path, monkeypatch):
    pkg = tmp_path / "fakepkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    dep = pkg / "dep.py"
    dep.write_text("X = 1\n")
    owner = pkg / "owner.py"
    owner.write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    cache = pkg / "__pycache__"
    cache.mkdir()
    entry = cache / "owner.kernel-10.py311.nbi"
    entry.write_text("old machine code")
    assert drop_stale_cache(str(owner), ["fakepkg.dep"]) is True   # first sight: no stamp yet
    assert not entry.exists()
    entry.write_text("fresh machine code")
    assert drop_stale_cache(str(owner), ["fakepkg.dep"]) is False  # unchanged dependency
    assert entry.exists()
    dep.write_text("X = 2\n")
    assert drop_stale_cache(str(owner), ["fakepkg.dep"]) is True   # changed dependency
    assert not entry.exists()
    assert Path(cache / "owner.deps.sha256").read_text()


def test_cached_dynamics_modules_guard_the_compiled_code_they_take_from_other_modules():
    """numba's on-disk cache watches only the cached function's own file: a rotor/dynamics module with
    ``@njit(cache=True)`` functions calls ``drop_stale_cache(__file__, deps)`` before its first njit,
    and ``deps`` names every module whose compiled functions it uses (those compile into its kernels)."""
    import ast
    import importlib

    from numba.core.dispatcher import Dispatcher

    import rotor.dynamics

    def njit_calls(node):
        return [c for c in ast.walk(node) if isinstance(c, ast.Call) and ast.unparse(c.func).endswith("njit")]

    def cached(call):
        return any(k.arg == "cache" and isinstance(k.value, ast.Constant) and k.value.value is True
                   for k in call.keywords)

    checked = []
    for path in sorted(Path(rotor.dynamics.__file__).parent.glob("*.py")):
        tree = ast.parse(path.read_text())
        uses_njit = [n for n in tree.body if njit_calls(n)]
        if not any(cached(c) for n in uses_njit for c in njit_calls(n)):
            continue
        guards = [n for n in tree.body if isinstance(n, ast.Expr) and isinstance(n.value, ast.Call)
                  and ast.unparse(n.value.func) == "drop_stale_cache"]
        assert len(guards) == 1, f"{path.name}: cache=True kernels without a drop_stale_cache guard"
        assert guards[0].lineno < uses_njit[0].lineno, f"{path.name}: guard after the first njit"
        deps = set(ast.literal_eval(guards[0].value.args[1]))
        module = importlib.import_module(f"rotor.dynamics.{path.stem}")
        foreign = {obj.py_func.__module__ for obj in vars(module).values()
                   if isinstance(obj, Dispatcher) and obj.py_func.__module__ != module.__name__}
        assert foreign <= deps, f"{path.name}: compiled code from {sorted(foreign - deps)} not in its guard {sorted(deps)}"
        for name in deps:
            assert importlib.util.find_spec(name) is not None, f"{path.name}: guard names unknown module {name}"
        checked.append(path.stem)
    assert {"kernels", "production_kernels"} <= set(checked), checked
