"""JSON Schema of a ring-pair file (``ringcontact.ring-scene/1``), generated from the loader's key table.

The source of truth is :data:`fem_reference.ring_scene.KEYS` with :func:`fem_reference.ring_scene.json_schema`;
the loader enforces more than a schema can say (radii that do not cross, a clearance <= 5 % of the
radius, a range the meshes resolve), listed on the documentation page ``docs/ring-scenes.rst``.

Run from the repository root::

    python docs/_ext/ring_scene_schema.py           # rewrite docs/ring-scene.schema.json
    python docs/_ext/ring_scene_schema.py --check   # exit 1 if the committed file is out of date
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from fem_reference.ring_scene import json_schema  # noqa: E402

SCHEMA_FILE = DOCS / "ring-scene.schema.json"


def main(argv: list[str]) -> int:
    text = json.dumps(json_schema(), indent=1) + "\n"
    if "--check" in argv:
        ok = SCHEMA_FILE.exists() and SCHEMA_FILE.read_text(encoding="utf-8") == text
        print(f"{SCHEMA_FILE}: {'up to date' if ok else 'OUT OF DATE'}")
        return 0 if ok else 1
    SCHEMA_FILE.write_text(text, encoding="utf-8")
    print(f"wrote {SCHEMA_FILE}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
