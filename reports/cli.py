"""The ``ringcontact`` console command: one entry point, one sub-command per job.

Each job lives in the module of the layer that owns it and exposes
``main(argv: list[str]) -> int`` with its own ``argparse`` parser. The table
below is the only place jobs are registered; modules are imported only when
their job runs, so ``ringcontact --help`` stays instant.
"""
from __future__ import annotations

import importlib
import sys

from contact.errors import RingContactError

# job name -> (module, one-line help). Keep sorted by data-flow layer.
JOBS: dict[str, tuple[str, str]] = {
    "law": ("contact.cli", "evaluate an analytic contact law at given penetrations/tilts (table or --json)"),
    "rotor": ("rotor.cli", "rotor linear analyses: modes, campbell, critical-speeds, unbalance (table or --json)"),
    "simulate": ("rotor.dynamics_cli", "time histories of the loose-support rotor at one speed (CSV/NPZ + summary)"),
    "fem-point": ("fem_reference.job_point", "solve one 2D FEM contact point (penetration in mm; --json)"),
    "fem-sweep": ("fem_reference.job_sweep", "regenerate the committed 2D FEM reference dataset (with progress)"),
    "fem-check": ("fem_reference.job_check", "recompute a few committed 2D FEM points, report differences"),
    "fem-report": ("fem_reference.report2d", "write reports/published/fem2d-reference.* from the committed 2D dataset"),
    "fem-paper": ("fem_reference.paper_setup", "paper set-up study: which 2D BCs reproduce the paper's FEM loads"),
    "fem-vtu": ("fem_reference.job_vtu", "export a solved 2D FEM point to VTU for ParaView"),
    "fem3d": ("fem_reference.cli3d", "3D tilted-ring FEM reference: point | sweep | check (mm, arcmin; --json)"),
    "calibrate": ("contact.calibrate", "fit and store one calibrated contact law per FEM scene (contact/calibrated/*.json)"),
    "study": ("reports.study_cli", "steady-state sweeps, cascades, test rig, run-up, regime map (resumable, parallel)"),
    "report": ("reports.main", "build the committed reports/ from the committed datasets (the main job)"),
}


def _usage() -> str:
    width = max(len(k) for k in JOBS)
    lines = ["usage: ringcontact JOB [options]   (ringcontact JOB --help for a job's options)", "", "jobs:"]
    lines += [f"  {name:<{width}}  {help_}" for name, (_, help_) in JOBS.items()]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in {"-h", "--help", "help"}:
        print(_usage())
        return 0
    job, rest = argv[0], argv[1:]
    if job not in JOBS:
        print(f"ringcontact: unknown job {job!r}\n\n{_usage()}", file=sys.stderr)
        return 2
    module = importlib.import_module(JOBS[job][0])
    try:
        return int(module.main(rest) or 0)
    except RingContactError as exc:  # safety net: every job reports suite errors the same way
        print(f"ringcontact {job}: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
