#!/usr/bin/env python3
"""Set up everything on a fresh machine, then run a job.

Usage (from the repository root, with nothing but python3 installed)::

    python3 dev.py demo     # the main job on the committed default data
    python3 dev.py test     # the default test suite (slow studies skipped)

Each creates ``.venv`` if missing, installs the package with its test
dependencies (again whenever ``pyproject.toml`` changes), installs the Debian
libraries that gmsh's wheel links against when they are absent, then runs.
Extra arguments after the job are passed on (``python3 dev.py test -k law``).
"""
from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent
VENV = ROOT / ".venv"
PY = VENV / "bin" / "python"

# Shared libraries the gmsh wheel's libgmsh.so needs, mapped to Debian packages
# (measured with ldd on gmsh 4.15; see docs/reference/fem-notes.md).
GMSH_DEBIAN_LIBS = {
    "libGLU.so": "libglu1-mesa",
    "libGL.so": "libgl1",
    "libXrender.so": "libxrender1",
    "libXcursor.so": "libxcursor1",
    "libXfixes.so": "libxfixes3",
    "libXext.so": "libxext6",
    "libXft.so": "libxft2",
    "libfontconfig.so": "libfontconfig1",
    "libXinerama.so": "libxinerama1",
    "libX11.so": "libx11-6",
    "libgomp.so": "libgomp1",
}


def _run(cmd: list[str], **kw) -> None:
    print("+", " ".join(str(c) for c in cmd), flush=True)
    subprocess.run([str(c) for c in cmd], check=True, **kw)


def _apt_install(packages: list[str]) -> None:
    if not packages:
        return
    if shutil.which("apt-get") is None:
        sys.exit(f"dev.py: need Debian packages {packages} but apt-get is not available")
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    _run(sudo + ["apt-get", "update", "-q"], env=env)
    _run(sudo + ["apt-get", "install", "-y", "-q", "--no-install-recommends", *packages], env=env)


def _ensure_venv() -> None:
    if PY.exists():
        return
    try:
        _run([sys.executable, "-m", "venv", VENV])
    except subprocess.CalledProcessError:
        shutil.rmtree(VENV, ignore_errors=True)
        ver = f"{sys.version_info.major}.{sys.version_info.minor}"
        _apt_install([f"python{ver}-venv"])
        _run([sys.executable, "-m", "venv", VENV])


def _ensure_installed() -> None:
    digest = hashlib.sha256((ROOT / "pyproject.toml").read_bytes()).hexdigest()[:16]
    stamp = VENV / f".installed-{digest}"
    if stamp.exists():
        return
    _run([PY, "-m", "pip", "install", "-q", "--upgrade", "pip"])
    _run([PY, "-m", "pip", "install", "-q", "-e", f"{ROOT}[test]"])
    for old in VENV.glob(".installed-*"):
        old.unlink()
    stamp.touch()


def _ensure_gmsh_libraries() -> None:
    probe = subprocess.run([PY, "-c", "import gmsh"], capture_output=True, text=True)
    if probe.returncode == 0:
        return
    libdir = subprocess.run(
        [PY, "-c", "import sysconfig,glob;print(' '.join(glob.glob(sysconfig.get_paths()['platlib']+'/**/libgmsh.so*',recursive=True)+glob.glob(sysconfig.get_paths()['data']+'/lib*/libgmsh.so*')))"],
        capture_output=True, text=True).stdout.split()
    missing: set[str] = set()
    for lib in libdir:
        out = subprocess.run(["ldd", lib], capture_output=True, text=True).stdout
        for line in out.splitlines():
            if "not found" in line:
                name = line.split()[0]
                for stem, pkg in GMSH_DEBIAN_LIBS.items():
                    if name.startswith(stem):
                        missing.add(pkg)
    _apt_install(sorted(missing) or sorted(set(GMSH_DEBIAN_LIBS.values())))
    probe = subprocess.run([PY, "-c", "import gmsh"], capture_output=True, text=True)
    if probe.returncode != 0:
        sys.exit("dev.py: gmsh still fails to import:\n" + probe.stderr)


def _ensure_chromium() -> None:
    """The docs tests screenshot the built gallery with headless Chromium (docs/_ext/screenshots.py)."""
    if not any(shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")):
        _apt_install(["chromium"])


def _workers(rest: list[str]) -> list[str]:
    """pytest-xdist options: one worker per core, at most two (the reference machine's), each test file on one
    worker (its module fixtures built once); none where the caller chose (``-n``, ``-p no:xdist``) or on one core."""
    if any(a == "-n" or a.startswith("-n") and a[2:].isdigit() or a.startswith("--numprocesses") or "xdist" in a
           for a in rest):
        return []
    n = min(2, os.cpu_count() or 1)
    return ["-n", str(n), "--dist", "loadfile"] if n > 1 else []


def main(argv: list[str]) -> int:
    if not argv or argv[0] not in {"demo", "test", "setup"}:
        print(__doc__)
        return 2
    job, rest = argv[0], argv[1:]
    _ensure_venv()
    _ensure_installed()
    _ensure_gmsh_libraries()
    if job in ("test", "setup"):
        _ensure_chromium()
    if job == "setup":
        return 0
    # One BLAS thread per process: on 2 shared cores, threaded OpenBLAS made small dense
    # eigenproblems ~100x slower (0.6 s vs 4 ms measured for 128x128); sweeps use processes.
    env = dict(os.environ, MPLBACKEND="Agg")
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    env.setdefault("OMP_NUM_THREADS", "1")
    if job == "demo":
        cmd = [VENV / "bin" / "ringcontact", "report", *rest]
    else:
        cmd = [PY, "-m", "pytest", "-q", *_workers(rest), *rest]
    print("+", " ".join(str(c) for c in cmd), flush=True)
    return subprocess.run([str(c) for c in cmd], cwd=ROOT, env=env).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
