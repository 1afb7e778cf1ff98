"""``ringcontact --version``: the version and the commit it was built from (:mod:`contact.stamp`)."""
from __future__ import annotations

from contact.stamp import SOURCE_ROOT, build_stamp, is_source_checkout, version
from sweep.provenance import code_revision


def version_line() -> str:
    """``ringcontact 0.1.0 (commit abc123def456, built 2026-…)`` for ``ringcontact --version``."""
    stamp = build_stamp()
    if stamp is None and is_source_checkout():
        rev = code_revision()
        commit = rev["git_commit"][:12] + ("+dirty" if rev.get("git_dirty") else "")
        return f"ringcontact {version()} (source checkout {SOURCE_ROOT}, commit {commit})"
    if stamp is None:
        return f"ringcontact {version()} (commit unknown: built without a stamp)"
    commit = str(stamp.get("git_commit", "unknown"))[:12] + ("+dirty" if stamp.get("git_dirty") else "")
    return f"ringcontact {stamp.get('version', version())} (commit {commit}, built {stamp.get('built_utc', '?')})"
