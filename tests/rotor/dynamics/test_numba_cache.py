"""The suite's numba cache (contact.compiled_cache): in the user's cache folder, stale when a module
compiled into a kernel changes, and the production step loop compiled once for every run."""
import importlib
from pathlib import Path

import numpy as np

from contact import compiled_cache


def test_cache_root_follows_ringcontact_cache_then_xdg(monkeypatch, tmp_path):
    monkeypatch.setenv("RINGCONTACT_CACHE", str(tmp_path / "rc"))
    assert compiled_cache.cache_root() == tmp_path / "rc" / "numba"
    monkeypatch.delenv("RINGCONTACT_CACHE")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert compiled_cache.cache_root() == tmp_path / "xdg" / "ringcontact" / "numba"


def test_stamp_changes_when_a_declared_dependency_changes(tmp_path, monkeypatch):
    pkg = tmp_path / "fakepkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    dep = pkg / "dep.py"
    dep.write_text("X = 1\n")
    owner = pkg / "owner.py"
    owner.write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    alone = compiled_cache.source_stamp(str(owner))
    compiled_cache.compiled_with(str(owner), ["fakepkg.dep"])
    first = compiled_cache.source_stamp(str(owner))
    assert first != alone
    assert compiled_cache.source_stamp(str(owner)) == first     # unchanged dependency: same stamp
    dep.write_text("X = 2\n")
    assert compiled_cache.source_stamp(str(owner)) != first     # changed dependency: entries stale


def test_cached_kernels_go_to_the_cache_root_not_the_source_tree(tmp_path, monkeypatch):
    """A fresh cached function of a watched file is written under cache_root(), and a second
    dispatcher of the same source (a new process, in effect) loads it instead of compiling."""
    from numba import njit

    monkeypatch.setenv("RINGCONTACT_CACHE", str(tmp_path))
    src = tmp_path / "src" / "mod_cached.py"
    src.parent.mkdir()
    src.write_text("def f(x):\n    return 2.0 * x + 1.0\n")
    monkeypatch.syspath_prepend(str(src.parent))
    compiled_cache.compiled_with(str(src), [])
    mod = importlib.import_module("mod_cached")
    first = njit(cache=True)(mod.f)
    assert first(2.0) == 5.0
    entries = list((tmp_path / "numba").rglob("*.nbi"))
    assert entries and not list(src.parent.rglob("*.nbi"))
    second = njit(cache=True)(mod.f)
    assert second(3.0) == 7.0 and sum(second.stats.cache_hits.values()) == 1


def test_cached_modules_declare_the_compiled_code_they_take_from_other_modules():
    """numba's on-disk cache watches only the cached function's own file: a module with
    ``@njit(cache=True)`` functions calls ``compiled_with(__file__, deps)`` before its first njit,
    and ``deps`` names every module whose compiled functions it uses (those compile into its kernels)."""
    import ast

    from numba.core.dispatcher import Dispatcher

    import contact
    import rotor.dynamics

    def njit_calls(node):
        return [c for c in ast.walk(node) if isinstance(c, ast.Call) and ast.unparse(c.func).endswith("njit")]

    def cached(call):
        return any(k.arg == "cache" and isinstance(k.value, ast.Constant) and k.value.value is True
                   for k in call.keywords)

    checked = []
    files = sorted(Path(rotor.dynamics.__file__).parent.glob("*.py")) + sorted(Path(contact.__file__).parent.glob("*.py"))
    for path in files:
        tree = ast.parse(path.read_text())
        uses_njit = [n for n in tree.body if njit_calls(n)]
        if not any(cached(c) for n in uses_njit for c in njit_calls(n)):
            continue
        guards = [n for n in tree.body if isinstance(n, ast.Expr) and isinstance(n.value, ast.Call)
                  and ast.unparse(n.value.func) == "compiled_with"]
        assert len(guards) == 1, f"{path.name}: cache=True kernels without a compiled_with declaration"
        assert guards[0].lineno < uses_njit[0].lineno, f"{path.name}: declaration after the first njit"
        deps = set(ast.literal_eval(guards[0].value.args[1]))
        modname = ".".join(path.relative_to(Path(contact.__file__).parent.parent).with_suffix("").parts)
        module = importlib.import_module(modname)
        foreign = {obj.py_func.__module__ for obj in vars(module).values()
                   if isinstance(obj, Dispatcher) and obj.py_func.__module__ != module.__name__}
        assert foreign <= deps, f"{path.name}: compiled code from {sorted(foreign - deps)} not in {sorted(deps)}"
        for name in deps:
            assert importlib.util.find_spec(name) is not None, f"{path.name}: declares unknown module {name}"
        checked.append(path.stem)
    assert {"kernels", "production_kernels", "_kernel"} <= set(checked), checked


def test_step_loop_compiled_once_for_warm_up_and_runs():
    """warm_up's argument types are those of a real run: the loop has one signature after both,
    with a support and without one (a scene with no loose support runs through the same loop)."""
    from rotor.dynamics import production
    from rotor.dynamics.production_loop import step_loop
    from tests.rotor.dynamics.dynamics_standin import friction_body

    info = production.warm_up()
    assert info["compile_s"] >= 0.0
    system = friction_body()
    production.simulate_production(system, 1e-5, 5, check_step=False)
    assert len(step_loop.signatures) == 1, step_loop.signatures
    assert np.isfinite(production.warm_up()["compile_s"])
