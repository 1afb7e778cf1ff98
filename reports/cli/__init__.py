"""The ``ringcontact`` console command: one entry point, one sub-command per job.

Every job's command line lives in a module of ``reports/cli/`` and exposes
``main(argv: list[str]) -> int`` (or the named function of a ``"module:function"``
entry) with its own ``argparse`` parser; the computing and the report writing stay in
their own layers. The table below is the only place jobs are registered; modules are
imported only when their job runs, so ``ringcontact --help`` stays instant.

Whatever goes wrong, the user sees ONE line on stderr, never a traceback: a suite error
(:class:`~contact.errors.RingContactError`) as ``ringcontact JOB: error: MESSAGE`` with exit status
2 (bad input) or 1 (a computation that failed); anything else as an internal error with exit
status 1 (``RINGCONTACT_DEBUG=1`` shows the traceback); an interruption (Ctrl-C, SIGTERM) as
``ringcontact JOB: interrupted (SIGINT): WHAT WAS KEPT`` with exit status 130 (SIGINT) or 143 (SIGTERM),
its temporaries removed and its worker processes stopped (:mod:`contact.interrupts`). ``ringcontact --version`` prints the
version and the commit it was built from; ``ringcontact --ranges`` the plausible range of every
physical input (:mod:`contact.plausible`).
"""
from __future__ import annotations

import errno
import importlib
import os
import sys

from contact import interrupts
from contact.errors import RingContactError

# job name -> (module, one-line help). Keep sorted by data-flow layer.
JOBS: dict[str, tuple[str, str]] = {
    "law": ("reports.cli.law", "evaluate an analytic contact law at given penetrations/tilts (table or --json)"),
    "rotor": ("reports.cli.rotor", "rotor linear analyses: modes, campbell, critical-speeds, unbalance (table or --json)"),
    "simulate": ("reports.cli.simulate", "time histories of the loose-support rotor at one speed (CSV/NPZ + summary)"),
    "fem-point": ("reports.cli.fem:point_main", "solve one 2D FEM contact point (penetration in mm; --json)"),
    "fem-sweep": ("reports.cli.fem:sweep_main", "regenerate the committed 2D FEM reference dataset (with progress)"),
    "fem-check": ("reports.cli.fem:check_main", "recompute a few committed 2D FEM points, report differences"),
    "fem-report": ("reports.cli.fem:report_main", "write reports/published/fem2d-reference.* from the committed 2D dataset"),
    "fem-paper": ("reports.cli.fem:paper_main", "paper set-up study: which 2D BCs reproduce the paper's FEM loads"),
    "fem-vtu": ("reports.cli.fem:vtu_main", "export a solved 2D FEM point to VTU for ParaView"),
    "fem3d": ("reports.cli.fem3d", "3D tilted-ring FEM reference: point | sweep | check | report | vtu (mm, arcmin; --json)"),
    "bearing": ("reports.cli.bearing", "your ring pair (a .toml ring-pair file) to a verified law: FEM 2D (+3D with tilt), calibration, accuracy report, law file"),
    "calibrate": ("reports.cli.calibrate", "fit and store one calibrated contact law per FEM scene (contact/calibrated/*.json)"),
    "orbit": ("reports.cli.orbit", "the periodic orbit at one speed by shooting: period, Floquet multipliers, stability, 1X-5X (--json)"),
    "branch": ("reports.cli.orbit:branch_main", "follow the periodic orbit over a speed range, bifurcations found (--json, --plot)"),
    "study": ("reports.cli.study", "steady-state sweeps, cascades, test rig, run-up, regime map (resumable, parallel)"),
    "scenes": ("reports.cli.scenes", "the bundled rotor scenes and ring-pair files: list | show NAME | schema rotor|ring"),
    "report": ("reports.cli.report", "build the committed reports/ from the committed datasets (the main job)"),
}


def _usage() -> str:
    width = max(len(k) for k in JOBS)
    lines = ["usage: ringcontact JOB [options]   (ringcontact JOB --help for a job's options)", "", "jobs:"]
    lines += [f"  {name:<{width}}  {help_}" for name, (_, help_) in JOBS.items()]
    return "\n".join(lines)


def _ranges() -> str:
    from contact.plausible import RANGES, range_text
    return "\n".join(f"{name:<26} {range_text(name):<28} {why}" for name, (*_, why) in RANGES.items())


def main(argv: list[str] | None = None) -> int:
    program = argv is None            # the ringcontact process itself, not a caller in Python
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in {"-h", "--help", "help"}:
        print(_usage())
        return 0
    if argv[0] in {"--version", "-V"}:
        from reports.version import version_line
        print(version_line())
        return 0
    if argv[0] == "--ranges":
        try:
            print(_ranges())
        except BrokenPipeError:          # piped into head
            sys.stderr.close()
        return 0
    job, rest = argv[0], argv[1:]
    if job not in JOBS:
        print(f"ringcontact: error: job = {job!r}: unknown (jobs: {', '.join(JOBS)}; ringcontact --help)",
              file=sys.stderr)
        return 2
    with interrupts.handled():       # SIGINT and SIGTERM: one orderly way out (contact.interrupts)
        status = _run(job, rest, program)
    if program and interrupts.pending_at_exit():
        interrupts.quiet_shutdown()  # the one line is said: nothing a finaliser prints at shutdown after it
    return status


#: jobs whose dense algebra is on matrices of tens to a few hundred rows (the rotor's reduced coordinates): one BLAS
#: thread. Measured on the shared 2-core machine at load 4: an SVD of 55 × 53 (the continuation's corrector step)
#: 0.28 ms with one OpenBLAS thread, 104 ms with two; in a Table 4 branch of 20 orbits from 5 740 rpm (2 240 steps per
#: revolution) the SVDs were 21 s of 87 s.
ONE_BLAS_THREAD = frozenset({"law", "rotor", "simulate", "orbit", "branch"})


def blas_threads(job: str) -> dict:
    """Set the BLAS/OpenMP thread variables for ``job`` before numpy loads (:mod:`contact.threads`): one thread for the
    jobs of :data:`ONE_BLAS_THREAD`, a value the user set is kept. Returns the variables (an empty dict for the other
    jobs, which choose their own: ``fem3d``, the sweeps' workers)."""
    if job not in ONE_BLAS_THREAD:
        return {}
    from contact.threads import set_thread_env
    return set_thread_env(1)


#: the errors of a write the user can remedy (space, quota, a read-only file system), said in one line
WRITE_FAILURES = (errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EFBIG)


def _run(job: str, rest: list[str], program: bool = False) -> int:
    """Run ``job``'s entry on ``rest``: its exit status, every failure and interruption as one line
    (``program``: this is the ringcontact process, which may end at once after an interruption)."""
    module_name, _, func_name = JOBS[job][0].partition(":")
    blas_threads(job)
    try:
        entry = getattr(importlib.import_module(module_name), func_name or "main")
        return int(entry(rest) or 0)
    except SystemExit as exc:         # argparse: --help (0) or its one-line error (2)
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 2)
    except RingContactError as exc:  # safety net: every job reports suite errors the same way
        print(f"ringcontact {job}: error: {' '.join(str(exc).split())}", file=sys.stderr)
        return int(getattr(exc, "exit_status", 2))
    except KeyboardInterrupt as exc:  # Ctrl-C or SIGTERM: temporaries removed, workers stopped, one line
        status, text = interrupts.finish(exc)
        print(f"ringcontact {job}: {text}", file=sys.stderr)
        if program:
            interrupts.quiet_shutdown()   # said in one line: a finaliser failing from here on prints nothing
        if program and isinstance(exc, interrupts.Interrupted) and interrupts.busy_threads():
            interrupts.exit_now(status)   # a thread still computing a point would hold the exit until it is done
        return status
    except BrokenPipeError:          # output piped into head & co.
        sys.stderr.close()
        return 0
    except OSError as exc:
        if exc.errno in WRITE_FAILURES:      # disk full, quota, read-only: atomic writes leave no half-written file
            where = os.fsdecode(exc.filename) if exc.filename else "the output"
            print(f"ringcontact {job}: error: could not write {where} ({exc.strerror or os.strerror(exc.errno)}); "
                  "every file written is whole, none half-written; free space (or choose another --out) and run "
                  "again", file=sys.stderr)
            return 1
        if exc.errno != errno.ENAMETOOLONG:
            return _internal(job, exc)
        name = os.fsdecode(exc.filename or "")     # only a name the user typed (or one made from it) is too long
        print(f"ringcontact {job}: error: {name[:60]}… ({len(name)} characters): a file or folder name longer than "
              "the file system takes (255 bytes a name, 4096 a path); a shorter name", file=sys.stderr)
        return 2
    except (Exception, MemoryError) as exc:   # never a traceback for the user
        return _internal(job, exc)


def _internal(job: str, exc: BaseException) -> int:
    """An error the suite did not foresee: one line, exit status 1 (``RINGCONTACT_DEBUG=1``: the traceback); an
    error that follows a Ctrl-C or SIGTERM (:func:`contact.interrupts.pending`) is that interruption."""
    if interrupts.pending():
        status, text = interrupts.finish(interrupts.Interrupted(interrupts.pending()))
        print(f"ringcontact {job}: {text}", file=sys.stderr)
        return status
    if os.environ.get("RINGCONTACT_DEBUG"):
        raise exc
    print(f"ringcontact {job}: internal error: {type(exc).__name__}: {' '.join(str(exc).split())[:300]} "
          "(a bug: please report it with the command line; RINGCONTACT_DEBUG=1 shows the traceback)",
          file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
