"""What a ``ringcontact bearing`` run folder holds, and the error bound its law is checked against."""
from __future__ import annotations

from contact.calibrate.fit import HOLDOUT_BOUND_REL as LAW_ERROR_BOUND_REL   # noqa: F401  (the one bound)


def file_names(name: str) -> dict[str, str]:
    """The files of one run in its output folder, by role."""
    return {"fem2d": f"fem2d-{name}.json", "fem3d": f"fem3d-{name}.json", "law": f"{name}-law.json",
            "law2d": f"{name}-law-2d.json",
            "law_straight": f"{name}-law-straight.json", "report": f"accuracy-{name}.md", "csv": f"accuracy-{name}.csv",
            "timings": "timings.json", "summary": "summary.json"}
