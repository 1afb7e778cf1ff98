"""``ringcontact scenes``: the bundled scenes and the schemas, for a user with the installed package only.

    ringcontact scenes list                      rotor scenes (rotor/scenes) and ring-pair files (fem_reference/ring_scenes)
    ringcontact scenes show NAME                 a bundled scene's TOML text (a start for your own: > my.toml)
    ringcontact scenes schema rotor|ring         the JSON Schema of a rotor scene or a ring-pair file

Rotor scenes are read by ``rotor``, ``simulate``, ``orbit``, ``branch`` and ``study`` (docs: scenes); ring-pair
files by ``bearing`` and the FEM jobs' ``--scene`` (docs: ring-scenes).
"""
from __future__ import annotations

import json
import sys

from contact.errors import InputError, RingContactError
from reports.cli._edge import Parser, fail

PROG = "ringcontact scenes"


def _rotor_entries() -> dict:
    from contact.package_data import entries, stem
    from rotor.model.scene import SCENE_DIR
    return {stem(e): e for e in entries(SCENE_DIR, ".toml")}


def _ring_entries() -> dict:
    from contact.package_data import entries, stem
    from fem_reference.ring_scene import RING_SCENE_DIR
    return {stem(e): e for e in entries(RING_SCENE_DIR, ".toml")}


def _list() -> str:
    import tomllib
    lines = ["rotor scenes (ringcontact rotor|simulate|orbit|branch|study SCENE):"]
    for name, e in _rotor_entries().items():
        lines.append(f"  {name:<28} {tomllib.loads(e.read_text(encoding='utf-8')).get('title', '')}")
    lines.append("ring-pair files (ringcontact bearing FILE; --scene of the FEM jobs):")
    for name, e in _ring_entries().items():
        lines.append(f"  {name:<28} {tomllib.loads(e.read_text(encoding='utf-8')).get('description', '')}")
    return "\n".join(lines)


def _show(name: str) -> str:
    found = {**_ring_entries(), **_rotor_entries()}
    if name not in found:
        raise InputError(f"NAME = {name!r}: not a bundled scene (have {', '.join(sorted(found))})")
    return found[name].read_text(encoding="utf-8")


def _schema(kind: str) -> str:
    if kind == "rotor":
        from rotor.model.scene_schema import schema_text
        return schema_text()
    from fem_reference.ring_scene import json_schema
    return json.dumps(json_schema(), indent=1) + "\n"


def main(argv: list[str] | None = None) -> int:
    """``ringcontact scenes list | show NAME | schema rotor|ring``."""
    ap = Parser(prog=PROG, description="the bundled scenes and the scene schemas")
    sub = ap.add_subparsers(dest="what", required=True, parser_class=Parser)
    sub.add_parser("list", help="every bundled rotor scene and ring-pair file, one line each")
    sp = sub.add_parser("show", help="a bundled scene's TOML text")
    sp.add_argument("name", metavar="NAME", help="a name from 'ringcontact scenes list'")
    sp = sub.add_parser("schema", help="the JSON Schema of a scene file")
    sp.add_argument("kind", choices=("rotor", "ring"), help="rotor scene or ring-pair file")
    args = ap.parse_args(sys.argv[1:] if argv is None else argv)
    try:
        text = _list() if args.what == "list" else _show(args.name) if args.what == "show" else _schema(args.kind)
    except RingContactError as exc:
        return fail(PROG, exc)
    sys.stdout.write(text if text.endswith("\n") else text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
