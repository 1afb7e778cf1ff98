"""``ringcontact bearing FILE``: a ring-pair file to a verified, checksummed contact law.

    ringcontact bearing my-bearing.toml [--out DIR] [--workers 2] [--scheduler ADDRESS] [--fresh] [--json]
                                        [--range-from RUN] [--plane-check | --no-plane-check]

FILE is a ring-pair file (schema ``ringcontact.ring-scene/1``, docs/ring-scenes.rst) or a bundled one by
name (``clamped``, ``steel-in-aluminium``, ...). Runs the 2D reference sweep, the 3D tilt sweep when the
range asks for tilt, calibration with held-out points, the accuracy report and the law file, into
``DIR`` (default ``bearing-<name>`` in the working directory); progress on a terminal; an interrupted
run resumes where it stopped (``--fresh`` starts over). The law file ``DIR/<name>-law.json`` is what a
rotor scene names in ``[loose_support] law``. Stages are in :mod:`reports.bearing.pipeline`.

``--range-from RUN`` lets the law follow the rotor: the file's ``[range]`` is widened to the penetrations and tilt a
rotor run visited in contact (its ``law_validity`` record: a ``simulate --out`` or ``study --out`` folder, or an
``orbit``/``branch --out`` JSON file), with a margin, rounded outward (:mod:`reports.bearing.range_from`); what the
FEM references cannot reach is said, and the parts of the range no law family holds are listed
(:mod:`reports.bearing.holds`) in the summary, the report and on the terminal.

Plane stress or strain: a file left at ``plane = "auto"`` (the default) gets the plane whose force lies closer to the
3D ring's at zero tilt (:mod:`fem_reference.plane_check`, stage 0 of :mod:`reports.bearing.pipeline`); a file with a
tilt range is checked too; ``--plane-check`` checks a plane stated in a straight-only file (the 3D levels' build,
about 20 s cold), ``--no-plane-check`` checks nothing (``auto`` then means plane strain, said so).
"""
from __future__ import annotations

import argparse
import json
import sys

from contact.threads import set_thread_env, thread_share

set_thread_env(thread_share(1))      # this process's share of the cores, before numpy loads (contact/threads.py)

from contact.errors import OutputError, RingContactError  # noqa: E402
from reports.cli._budget import add_accept_long, check  # noqa: E402
from reports.cli._edge import Parser, check_arg, count, fail, out_dir  # noqa: E402

PROG = "ringcontact bearing"


def _run(args, rs, out, note) -> dict:
    """The pipeline into ``out``; an I/O error while writing (disk full, folder removed meanwhile) is one line
    naming the path: each file is whole or absent, the summary last."""
    from reports.bearing.pipeline import run
    from sweep.cluster import connect

    log = (lambda msg: print(msg, file=sys.stderr)) if args.json else print
    try:
        with connect(args.scheduler) as client:
            return run(rs, out, workers=args.workers, executor=client, fresh=args.fresh, log=log,
                       range_from=note, plane_check=args.plane_check)
    except OSError as exc:
        if isinstance(exc, RingContactError):
            raise
        where = exc.filename or out
        raise OutputError(f"--out: could not write {where} ({exc.strerror or exc}); the folder holds no summary, so "
                          "no complete run: free space and run again (finished points are kept)") from None


def main(argv: list[str] | None = None) -> int:
    """``ringcontact bearing FILE [options]``."""
    ap = Parser(prog=PROG, description="a ring-pair file to a verified contact law (FEM, calibration, report, law file)")
    ap.add_argument("scene", metavar="FILE", help="ring-pair file (.toml) or the name of a bundled one")
    ap.add_argument("--out", default=None, help="output folder (default: bearing-<name> in the working directory)")
    ap.add_argument("--workers", type=count(1, 64, "processes"), default=2, help="local processes (1-64)")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="run the FEM points on the dask.distributed cluster at ADDRESS (the dask extra)")
    ap.add_argument("--fresh", action="store_true", help="recompute every point (ignore an interrupted run's points)")
    ap.add_argument("--json", action="store_true", help="print the summary as JSON")
    ap.add_argument("--range-from", default=None, metavar="RUN",
                    help="widen the file's range to what a rotor run visited in contact: a `simulate --out` or "
                         "`study --out` folder, or an `orbit`/`branch --out` JSON file")
    pc = ap.add_mutually_exclusive_group()
    pc.add_argument("--plane-check", dest="plane_check", action="store_const", const=True, default=None,
                    help="check the file's plane against the 3D ring even for a straight-only file with its plane "
                         "stated (default: checked for plane = \"auto\" and for a tilt range)")
    pc.add_argument("--no-plane-check", dest="plane_check", action="store_const", const=False,
                    help="no 3D check of the plane (plane = \"auto\" then means plane strain, said so)")
    add_accept_long(ap)
    args = ap.parse_args(sys.argv[1:] if argv is None else argv)
    if args.out is not None:
        check_arg(ap, "--out", out_dir, args.out)      # '' refused as every job refuses it, not the default folder
    try:
        from fem_reference.ring_scene import load
        from reports.bearing.work import estimate

        rs = load(args.scene)
        note = None
        if args.range_from is not None:
            from reports.bearing.range_from import note_lines, read_visited, widened
            rs, note = widened(rs, read_visited(args.range_from))
            for line in note_lines(note):
                print(line, file=sys.stderr if args.json else sys.stdout)
        out = check_arg(ap, "--out", out_dir, args.out if args.out is not None else f"bearing-{rs.name}")
        check(PROG, estimate(rs, args.workers), args.accept_long,
              f"FILE = {args.scene}: ring pair {rs.name!r}, bore radius {rs.scene.rings.bore_radius_m * 1e3:g} mm",
              "a smaller ring or fewer penetration and tilt points")
        summary = _run(args, rs, out, note)
    except RingContactError as exc:
        return fail(PROG, exc)
    if args.json:
        print(json.dumps(summary, indent=1, allow_nan=False))
    else:
        print(f"law file {out}/{summary['law_file']}: {summary['law_name']} "
              f"({'verified' if not summary['warnings'] else 'FLAGGED: ' + str(len(summary['warnings'])) + ' warning(s)'})")
        if summary.get("law_straight_file"):
            print(f"straight {out}/{summary['law_straight_file']}: the same run's law without the tilt correction "
                  "(for a rotor scene: the rotor's step loops do not evaluate a correction yet)")
        print(f"report   {out}/accuracy-{rs.name}.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
