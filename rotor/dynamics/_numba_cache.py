"""Keep numba's on-disk cache honest across modules.

numba's ``cache=True`` checks only the source file of the cached function itself. Kernels in
:mod:`rotor.dynamics.kernels` inline functions from :mod:`contact._kernel`, those in
:mod:`rotor.dynamics.production_kernels` functions from :mod:`rotor.dynamics.constraints`; after a
change there, numba would silently load the old machine code.
:func:`drop_stale_cache` hashes the dependency sources and deletes the caller's cache entries
when the hash changed, before any ``@njit`` in the caller is compiled or loaded.
"""
from __future__ import annotations

import hashlib
from pathlib import Path


def drop_stale_cache(owner_file: str, dependency_modules: list[str]) -> bool:
    """Delete ``owner_file``'s numba cache entries if a dependency's source changed.

    Parameters
    ----------
    owner_file : str
        ``__file__`` of the module whose ``@njit(cache=True)`` functions use the dependencies.
    dependency_modules : list of str
        Importable module names whose source is compiled into the owner's kernels.

    Returns
    -------
    bool
        True if stale entries were found and removed.
    """
    import importlib.util

    digest = hashlib.sha256()
    for name in dependency_modules:
        spec = importlib.util.find_spec(name)
        if spec is None or spec.origin is None:
            continue
        digest.update(Path(spec.origin).read_bytes())
    owner = Path(owner_file)
    cache_dir = owner.parent / "__pycache__"
    stamp = cache_dir / f"{owner.stem}.deps.sha256"
    current = digest.hexdigest()
    try:
        if stamp.read_text().strip() == current:
            return False
    except OSError:
        pass
    removed = False
    if cache_dir.is_dir():
        for entry in cache_dir.glob(f"{owner.stem}.*.nb[ic]"):
            try:
                entry.unlink()
                removed = True
            except OSError:
                pass
    try:
        cache_dir.mkdir(exist_ok=True)
        tmp = stamp.with_suffix(f".tmp{id(current)}")
        tmp.write_text(current)
        tmp.replace(stamp)
    except OSError:
        pass  # read-only install: numba will not cache there either
    return removed
