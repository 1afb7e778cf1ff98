"""The built wheel, installed into a fresh virtual environment, runs the documented jobs from anywhere.

What the test does (192 s on 2 shared cores, most of it numba compiling the step loop and the sensitivity pass
into an empty cache for ``simulate``, ``orbit``, ``report`` and ``bearing``: it runs in the slow tier; the
default run builds and installs the same wheel and runs the jobs that compile nothing, ``--version``, ``law``,
``rotor modes`` and ``fem-point``, with the same checks):

1. **Build** the wheel with pip from a copy of the repository's tracked files as they are in the
   working tree (a ``git clone --shared --no-checkout`` with the files copied over, so the build
   backend stamps the same commit and dirty flag as the checkout, and nothing is written into the
   checkout: no ``build/``, no ``*.egg-info``, no ``contact/_build.json``). pip builds it in an
   isolated environment with the ``[build-system]`` requirements of ``pyproject.toml``, fetched from
   the package index as for any user.
2. **Install** it into a fresh venv (``python -m venv --without-pip``). The dependencies are not
   downloaded again: the venv sees, through a ``.pth`` file, a folder of links to the entries of the
   running interpreter's site-packages with every trace of ringcontact left out (its dist-info, the
   editable-install hooks, the source packages); ``pip install --no-index WHEEL`` then resolves the
   wheel's ``Requires-Dist`` against those (and fails if one is missing or too old) and installs
   the package itself only from the wheel.
3. **Run** the README's jobs with ``venv/bin/ringcontact`` from an empty directory outside the
   repository, with a clean environment (no ``PYTHONPATH``; ``HOME``, the numba cache and
   matplotlib's config in temporary folders; umask 022): ``--version``, ``law``, ``law --law
   calibrated:clamped-foundation``, ``rotor modes paper-table4 --json``, ``simulate --speed-rpm
   10500 --revolutions 2`` (default output folder) and ``report --out DIR``.
4. **Check**: every job exits 0; the outputs are where they were asked for (or in the working
   directory by default), every file 0644; the venv (its site-packages included) is byte-for-byte
   the listing taken after the install; an audit hook logging every file each job opens shows the
   calibrated law, the scene, the datasets read from the venv's site-packages and no file of the
   repository; the notes and the LICENSE ship in the wheel; the installed copy's numbers equal the source tree's.
"""
from __future__ import annotations

import json
import math
import os
import shutil
import site
import stat
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
OUR_PACKAGES = {"contact", "fem_reference", "rotor", "reports", "sweep", "ringcontact", "build_backend"}

# Imported through a .pth file of the test venv: appends the absolute path of every file the process
# opens to $RINGCONTACT_OPEN_LOG (os.write raises no audit event, so the hook does not recurse).
OPEN_LOG_HOOK = '''\
import os, sys
_log = os.environ.get("RINGCONTACT_OPEN_LOG")
if _log:
    _fd = os.open(_log, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o600)
    def _hook(event, args, _fd=_fd):
        if event == "open" and isinstance(args[0], (str, bytes)):
            os.write(_fd, os.fsencode(os.path.abspath(os.fsdecode(args[0]))) + b"\\n")
    sys.addaudithook(_hook)
'''


def _run(cmd, **kw) -> subprocess.CompletedProcess:
    proc = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=600, **kw)
    assert proc.returncode == 0, f"{cmd} exited {proc.returncode}\nstdout: {proc.stdout[-3000:]}\nstderr: {proc.stderr[-3000:]}"
    return proc


def _git(*args: str, cwd: Path = ROOT) -> str:
    return _run(["git", *args], cwd=cwd).stdout


def _build_wheel(tmp: Path) -> Path:
    """pip-built wheel of the tracked files as they are in the working tree (see the module docstring)."""
    if not (ROOT / ".git").exists():
        pytest.skip("not a git checkout: the wheel is built from the tracked files")
    src = tmp / "src"
    _git("clone", "-q", "--shared", "--no-checkout", str(ROOT), str(src))
    for rel in _git("ls-files", "-z").split("\0"):
        if rel and (ROOT / rel).is_file():
            (src / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / rel, src / rel)
    _git("reset", "-q", cwd=src)          # index = HEAD, files untouched: `git status` tells dirty
    dist = tmp / "dist"
    _run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", dist, src])
    (wheel,) = dist.glob("ringcontact-*.whl")
    return wheel


def _dependency_view(tmp: Path) -> Path:
    """Links to the running interpreter's site-packages entries, every trace of ringcontact left out."""
    view = tmp / "deps"
    view.mkdir()
    dirs = [Path(p) for p in site.getsitepackages() + [sysconfig.get_paths()["purelib"]] if Path(p).is_dir()]
    for d in dict.fromkeys(dirs):
        for entry in d.iterdir():
            name = entry.name
            if (name.startswith(("ringcontact-", "ringcontact.", "__editable__")) or name.endswith(".pth")
                    or name in OUR_PACKAGES or name == "__pycache__" or (view / name).exists()):
                continue
            (view / name).symlink_to(entry)
    return view


def _listing(root: Path) -> dict[str, tuple[int, int, int]]:
    """Every file and folder under ``root``: relative path -> (mode, size, mtime in ns)."""
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for name in dirnames + filenames:
            p = Path(dirpath) / name
            st = p.lstat()
            out[str(p.relative_to(root))] = (st.st_mode, st.st_size if not stat.S_ISDIR(st.st_mode) else 0,
                                              st.st_mtime_ns if not stat.S_ISDIR(st.st_mode) else 0)
    return out


def _opened(log: Path) -> set[Path]:
    return {Path(line) for line in log.read_text(encoding="utf-8", errors="replace").splitlines()} if log.exists() else set()


def _source_json(argv: list[str], capsys) -> dict:
    """The same job run from the source tree (this process), its --json output."""
    from reports import cli
    capsys.readouterr()
    assert cli.main(argv) == 0
    return json.loads(capsys.readouterr().out)


def _close(a, b) -> bool:
    """Same JSON document, numbers equal to 1e-9 relative."""
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(_close(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(_close(x, y) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
    return a == b


def _installed(tmp_path: Path) -> tuple[Path, Path, dict, Path, Path]:
    """The wheel built and installed into a fresh venv: ``(venv, python, environment, site-packages, work folder)``."""
    wheel = _build_wheel(tmp_path)
    venv = tmp_path / "venv"
    _run([sys.executable, "-m", "venv", "--without-pip", venv])
    py = venv / "bin" / "python"
    site_packages = Path(_run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"]).stdout.strip())
    hooks = tmp_path / "hooks"
    hooks.mkdir()
    (hooks / "_ringcontact_open_log.py").write_text(OPEN_LOG_HOOK, encoding="utf-8")
    (site_packages / "_test_dependencies.pth").write_text(
        f"{_dependency_view(tmp_path)}\n{hooks}\nimport _ringcontact_open_log\n", encoding="utf-8")

    home, work = tmp_path / "home", tmp_path / "work"
    home.mkdir(), work.mkdir()
    env = {"PATH": f"{venv / 'bin'}:/usr/bin:/bin", "HOME": str(home), "LANG": "C.UTF-8",
           "RINGCONTACT_CACHE": str(tmp_path / "cache"), "MPLBACKEND": "Agg", "MPLCONFIGDIR": str(home / "mpl"),
           "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "TMPDIR": str(tmp_path)}
    install = _run([py, "-m", "pip", "install", "--no-index", "--no-input", "--disable-pip-version-check", wheel],
                   cwd=work, env=env)
    assert "Successfully installed ringcontact-" in install.stdout
    where = _run([py, "-c", "import contact, reports, rotor, ringcontact; print(contact.__file__); "
                  "print(ringcontact.__file__)"], cwd=work, env=env).stdout.split()
    for w in where:
        assert Path(w).is_relative_to(site_packages), f"{w} imported, not the venv's"
    return venv, py, env, site_packages, work


def test_wheel_in_a_fresh_venv_runs_the_documented_jobs_that_compile_nothing(tmp_path, capsys):
    """The default run's share of :func:`test_wheel_in_a_fresh_venv_runs_the_documented_jobs`: the same wheel,
    venv and checks on the jobs that need no step loop compiled (``--version``, ``law``, ``rotor modes``,
    ``fem-point``); the rotor's jobs (``simulate``, ``orbit``), ``report`` and ``bearing`` compile the step loop
    and the sensitivity pass into an empty cache (about 150 s of the full test's 192 s measured on 2 shared
    cores) and run in the slow tier."""
    _documented_jobs(tmp_path, capsys, full=False)


@pytest.mark.slow
def test_wheel_in_a_fresh_venv_runs_the_documented_jobs(tmp_path, capsys):
    _documented_jobs(tmp_path, capsys, full=True)


def _documented_jobs(tmp_path, capsys, full: bool) -> None:
    venv, py, env, site_packages, work = _installed(tmp_path)
    before = _listing(venv)

    def job(name: str, *argv: str) -> tuple[str, set[Path]]:
        log = tmp_path / f"opened-{name}.log"
        proc = _run([venv / "bin" / "ringcontact", *argv], cwd=work, env=dict(env, RINGCONTACT_OPEN_LOG=str(log)),
                    umask=0o022)
        return proc.stdout, _opened(log)

    # --version: the stamp written at build time (the commit of the checkout), never a git lookup
    out, _ = job("version", "--version")
    head = _git("rev-parse", "HEAD").strip()
    dirty = "+dirty" if _git("status", "--porcelain", "--untracked-files=no").strip() else ""
    assert out.startswith(f"ringcontact 0.1.0 (commit {head[:12]}{dirty}, built "), out

    out, _ = job("law", "law", "--penetration-mm", "0.01", "0.02", "0.03")
    assert "0.03" in out
    calibrated = ["law", "--law", "calibrated:clamped-foundation", "--penetration-mm", "0.01", "--tilt-arcmin", "0", "1", "--json"]
    out, opened_law = job("calibrated", *calibrated)
    assert _close(json.loads(out), _source_json(calibrated, capsys))
    modes = ["rotor", "modes", "paper-table4", "--json"]
    out, opened_modes = job("modes", *modes)
    assert _close(json.loads(out), _source_json(modes, capsys))
    # your bearing: a bundled ring-pair file in a FEM job
    out, opened_ring = job("fem-point", "fem-point", "0.01", "--scene", "steel-in-aluminium", "--h-mm", "2", "--json")
    assert json.loads(out)["scene"] == "steel-in-aluminium"
    opened = opened_law | opened_modes | opened_ring
    if full:
        _compiling_jobs(job, work, site_packages, opened)
    written = [p for p in work.rglob("*") if p.is_file()]
    modes_of = {str(p.relative_to(work)): oct(p.stat().st_mode & 0o777) for p in written}
    assert set(modes_of.values()) <= {"0o644"}, modes_of    # the full run writes 14 files or more

    # nothing written into the venv (site-packages included) by any job
    after = _listing(venv)
    assert after == before, {k: (before.get(k), after.get(k)) for k in set(before) ^ set(after) | {
        k for k in before.keys() & after.keys() if before[k] != after[k]}}

    # package data read from the installed package, no file of the repository opened
    assert site_packages / "contact" / "calibrated" / "clamped-foundation.json" in opened_law
    assert site_packages / "rotor" / "scenes" / "paper-table4.toml" in opened_modes
    assert site_packages / "fem_reference" / "ring_scenes" / "steel-in-aluminium.toml" in opened_ring
    repo_files = sorted(str(p) for p in opened
                        if p.resolve().is_relative_to(ROOT) and not p.resolve().is_relative_to(Path(sys.prefix).resolve()))
    assert not repo_files, repo_files
    notes = _run([py, "-c", "from importlib.resources import files; "
                  "print(files('reports').joinpath('notes/study-sensitivity-reading.md').read_text(encoding='utf-8'), end='')"],
                 cwd=work, env=env).stdout
    assert notes == (ROOT / "reports" / "notes" / "study-sensitivity-reading.md").read_text(encoding="utf-8")
    licence = next(site_packages.glob("ringcontact-*.dist-info")) / "licenses" / "LICENSE"
    assert licence.read_text(encoding="utf-8") == (ROOT / "LICENSE").read_text(encoding="utf-8")


def _compiling_jobs(job, work: Path, site_packages: Path, opened: set) -> None:
    """The slow share of :func:`_documented_jobs`: simulate, report, orbit and bearing from the wheel, their
    outputs where asked and the package data they read (the files they open are added to ``opened``)."""
    _, opened_sim = job("simulate", "simulate", "--speed-rpm", "10500", "--revolutions", "2")
    _, opened_report = job("report", "report", "--out", "rep")
    # shooting on a bundled scene (Jeffcott rotor, 3000 rpm: a synchronous orbit of period 1/50 s)
    _, opened_orbit = job("orbit", "orbit", "verify-jeffcott", "--speed-rpm", "3000", "--out", "orbit.json")
    # a ring-pair file of one's own through `bearing` (2D only)
    mine = (ROOT / "fem_reference" / "ring_scenes" / "steel-in-aluminium.toml").read_text(encoding="utf-8")
    mine = mine.replace('name = "steel-in-aluminium"', 'name = "small-ring"').replace(
        "tilt_arcmin = [0, 2]", "tilt_arcmin = [0, 0]\npenetration_points_mm = [0.004, 0.01, 0.02, 0.04]")
    (work / "small.toml").write_text(mine, encoding="utf-8")
    _, opened_bearing = job("bearing", "bearing", "small.toml", "--out", "brg", "--workers", "1")
    opened |= opened_sim | opened_report | opened_orbit | opened_bearing

    # outputs: where asked (simulate's default folder is in the working directory), all 0644
    summary = json.loads((work / "simulate-out" / "simulate-summary.json").read_text(encoding="utf-8"))
    assert summary["revolutions"] == 2.0 and summary["steps"] > 0
    assert {"simulate.csv", "simulate.npz", "simulate-summary.json"} <= {p.name for p in (work / "simulate-out").iterdir()}
    assert {"laws-vs-paper.md", "accuracy-table2.md"} <= {p.name for p in (work / "rep").iterdir()}
    assert {"small-ring-law.json", "accuracy-small-ring.md", "fem2d-small-ring.json"} <= {p.name for p in (work / "brg").iterdir()}
    orbit = json.loads((work / "orbit.json").read_text(encoding="utf-8"))
    assert orbit["converged"] and orbit["period_revs"] == 1 and abs(orbit["period_s"] - 0.02) < 1e-12
    assert len([p for p in work.rglob("*") if p.is_file()]) >= 14
    assert site_packages / "rotor" / "scenes" / "paper-table4.toml" in opened_sim
    assert site_packages / "rotor" / "scenes" / "verify-jeffcott.toml" in opened_orbit
    assert site_packages / "fem_reference" / "data" / "fem2d-reference.json" in opened_report
    assert site_packages / "fem_reference" / "data" / "3d" / "fem3d-reference.json" in opened_report


# Friswell, Penny, Garvey & Lees (2010), Example 5.9.1 (bored disks): whirl frequencies (rad/s) at rest and 4 000 rpm
FRISWELL_591 = {"rest": [86.66, 86.66, 274.31, 274.31, 716.78, 716.78], "4000": [85.39, 87.80, 251.78, 294.71, 600.18]}
WALKTHROUGH_DRIVER = """\
import importlib.util, json, sys
import ringcontact
spec = importlib.util.spec_from_file_location("ex07", "ex07_your_rotor.py")
ex = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ex)
f = ex.frequencies()
res = ex.main(full=True)
keys = ("peak_contact_force_N", "contact_share", "stick_share_right_face")
print(json.dumps({"file": ringcontact.__file__, "rest": list(f[0.0].frequency_rad_s),
                  "4000": list(f[4000.0].frequency_rad_s), "scene": ex.loose_rotor(ex.book_rotor()).to_toml(),
                  "contact": {k: {c: res[k].to_dict().get(c) for c in keys} for k in res if k != "unbalance"}}),
      file=sys.stderr)
"""


@pytest.mark.slow
def test_wheel_runs_the_your_rotor_walkthrough(tmp_path):
    """A fresh venv with the wheel only: docs/examples/ex07_your_rotor.py (the rotor written from scratch, modes,
    unbalance, simulate, orbit, branch, a small cascade) run end to end from a folder outside the repository,
    with the book's frequencies and the contact force in every nonlinear output (about 2 min on 2 shared cores:
    the build, and numba compiling into an empty cache)."""
    _, py, env, site_packages, work = _installed(tmp_path)
    shutil.copy2(ROOT / "docs" / "examples" / "ex07_your_rotor.py", work / "ex07_your_rotor.py")
    (work / "driver.py").write_text(WALKTHROUGH_DRIVER, encoding="utf-8")
    proc = _run([py, "driver.py"], cwd=work, env=env)
    d = json.loads(proc.stderr.strip().splitlines()[-1])
    assert Path(d["file"]).is_relative_to(site_packages)
    assert d["rest"] == pytest.approx(FRISWELL_591["rest"], abs=0.01)
    assert d["4000"][:5] == pytest.approx(FRISWELL_591["4000"], abs=0.01)
    assert "[loose_support]" in d["scene"] and 'law = "conformal"' in d["scene"]
    assert set(d["contact"]) == {"simulate", "orbit", "branch", "cascade"}
    for name, fields in d["contact"].items():
        assert fields["peak_contact_force_N"] is not None and fields["contact_share"] is not None, name
    assert d["contact"]["simulate"]["peak_contact_force_N"] > 0 and "peak contact force" in proc.stdout
