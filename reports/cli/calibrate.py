"""``ringcontact calibrate [--check]``: fit and store one calibrated contact law per FEM scene.

The fitting and the stored files are :mod:`contact.calibrate`; this is only the command line.
"""
from __future__ import annotations

import sys

from contact.calibrate import CALIBRATED_DIR, check_calibrations, load_calibrated, write_calibrations
from contact.dataset import read_dataset
from contact.errors import RingContactError
from reports.cli._edge import Parser, check_arg, fail, in_dir, in_file, out_dir

OUT = "contact/calibrated"     # relative to the working directory: the package's copy from the repository root


def main(argv: list[str] | None = None) -> int:
    """``ringcontact calibrate``: fit and store the calibrated laws of the committed 2D dataset."""
    p = Parser(prog="ringcontact calibrate",
               description="Fit one calibrated contact law per FEM scene and store it in contact/calibrated/.")
    p.add_argument("--dataset", type=in_file, action="append",
                   help="reference dataset (repeatable; default: the committed 2D dataset and every 3D one)")
    p.add_argument("--out", type=str, default=None,
                   help=f"directory of the JSON files (default: {OUT} when fitting; the packaged files with --check)")
    p.add_argument("--check", action="store_true", help="only compare the stored files with a fresh fit; exit 1 on drift")
    args = p.parse_args(argv)
    if args.check:
        args.out = check_arg(p, "--out", in_dir, args.out) if args.out is not None else CALIBRATED_DIR
    else:
        args.out = check_arg(p, "--out", out_dir, args.out if args.out is not None else OUT)
    try:
        for d in args.dataset or []:
            read_dataset(d)
        if args.check:
            problems = check_calibrations(args.dataset, args.out)
            for msg in problems:
                print(msg)
            print("calibrations up to date" if not problems else f"{len(problems)} calibration(s) out of date")
            return 1 if problems else 0
        for f in write_calibrations(args.dataset, args.out):
            law = load_calibrated(f.stem, args.out)
            pars = ", ".join(f"{k} = {v:.6g} ± {law.parameter_std[k]:.2g} {law.parameter_units[k]}"
                             for k, v in law.parameters.items())
            print(f"{law.name}: {pars}; hold-out max {100 * law.fit['holdout_max_rel']:.3f} % -> {f}")
            if law.fit.get("warning"):
                print(f"ringcontact calibrate: warning: {law.name}: {law.fit['warning']} (flagged in {f.name})",
                      file=sys.stderr)
    except RingContactError as exc:
        return fail("ringcontact calibrate", exc)
    return 0


if __name__ == "__main__":   # pragma: no cover
    sys.exit(main())
