"""The bad-input cases of every ``ringcontact`` job, and the harness that runs one in-process.

Each case is ``(id, argv, echo)``: ``argv`` may hold placeholders filled by :func:`make_inputs`
(``{tmp}``: a fresh directory per case, ``{file}``: a regular file, ``{dir}``: an existing empty
directory, ``{ragged}`` …); ``echo`` (or None) must appear in the one-line message: the value as
the user typed it, with its unit. Used by tests/reports/test_bad_inputs.py.
"""
from __future__ import annotations

import json
import os
import signal
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
UNWRITABLE_DIRS = ["/proc/ringcontact-out", "{file}/sub", ""]      # a file where a directory is meant, …
UNWRITABLE_FILES = ["/proc/ringcontact-out.x", "{file}/sub.x", "{dir}", ""]
NUMBERS_BAD = ["nan", "inf", "-inf", "1e30", "abc"]


def _num_cases(prefix: str, base: list[str], flag: str, values: list[str], unit: str) -> list:
    # a value that starts with '-' is typed --flag=-1e6 (argparse reads a bare '-1e6' as an option)
    return [(f"{prefix} {flag} {v}", [*base, f"{flag}={v}"] if v.startswith("-") else [*base, flag, v],
             f"{v} {unit}" if unit and v else None) for v in values]


def _out_cases(prefix: str, base: list[str], flag: str, targets: list[str]) -> list:
    return [(f"{prefix} {flag} {t or 'EMPTY'}", [*base, flag, t], None) for t in targets]


def _law_cases() -> list:
    b, c = ["law", "--penetration-mm", "0.01"], []
    c += _num_cases("law", ["law"], "--penetration-mm", NUMBERS_BAD + ["5", "-5", "2.5"], "mm")
    c += _num_cases("law", b, "--tilt-arcmin", NUMBERS_BAD + ["1e6", "-1e6"], "arcmin")
    c += _num_cases("law", b, "--clearance-mm", NUMBERS_BAD + ["0", "-0.05", "50"], "mm")
    c += _num_cases("law", b, "--width-mm", NUMBERS_BAD + ["0", "-30", "1e5"], "mm")
    for f in ("--bearing-E-GPa", "--support-E-GPa"):
        c += _num_cases("law", b, f, NUMBERS_BAD + ["0", "-204", "200e9"], "GPa")
    for f in ("--bearing-nu", "--support-nu"):
        c += _num_cases("law", b, f, ["nan", "0.5", "0.7", "-1.5", "abc"], "")
    c += [("law --law nosuch", [*b, "--law", "nosuch"], "nosuch"),
          ("law --law calibrated:nosuch", [*b, "--law", "calibrated:nosuch"], "nosuch"),
          ("law --law calibrated:", [*b, "--law", "calibrated:"], None),
          ("law --law EMPTY", [*b, "--law", ""], None),
          ("law --modulus bad", [*b, "--modulus", "bad"], None),
          ("law --penetration-at middle", [*b, "--penetration-at", "middle"], None),
          ("law calibrated with another clearance", [*b, "--law", "calibrated:clamped-foundation", "--clearance-mm",
                                                     "0.08"], "0.08"),
          ("law calibrated 5 mm", ["law", "--law", "calibrated:clamped-foundation", "--penetration-mm", "5"], "5 mm"),
          ("law no points", ["law"], None),
          ("law both sources", [*b, "--csv", "{good_csv}"], None),
          ("law grid too large", ["law", "--penetration-mm", *[f"{0.001 * i:g}" for i in range(1, 201)],
                                  "--tilt-arcmin", *[f"{0.01 * i:g}" for i in range(200)]], None)]
    for name in ("ragged", "empty_cell", "header_only", "no_column", "nan_csv", "deep_csv", "binary", "huge_csv",
                 "text_value", "missing", "dir", "fifo", "zero_link", "dup_column", "unknown_column"):
        c.append((f"law --csv {name}", ["law", "--csv", "{" + name + "}"], None))
    return c


def _fem_cases() -> list:
    c = []
    for job in ("fem-point", "fem-vtu"):
        tail = ["{tmp}/p.vtu"] if job == "fem-vtu" else []
        for v in NUMBERS_BAD + ["5", "-5"]:
            c.append((f"{job} penetration {v}", [job, "--", v, *tail] if v.startswith("-") else [job, v, *tail],
                      f"{v} mm" if v != "abc" else "abc"))
        b = [job, "0.01", *tail]
        c += _num_cases(job, b, "--h-mm", NUMBERS_BAD + ["0", "-1", "1e-6", "100"], "mm")
        c += [(f"{job} --scene nosuch", [*b, "--scene", "nosuch"], "nosuch"),
              (f"{job} --scene persson-abc", [*b, "--scene", "persson-abc"], "persson-abc"),
              (f"{job} --order 3", [*b, "--order", "3"], None),
              (f"{job} --order abc", [*b, "--order", "abc"], None)]
    c += _out_cases("fem-vtu", ["fem-vtu", "0.01"], "", UNWRITABLE_FILES)
    c += [("fem-vtu two outputs", ["fem-vtu", "0.01", "{tmp}/a.vtu", "--out", "{tmp}/b.vtu"], None)]
    c += _num_cases("fem-vtu", ["fem-vtu", "0.01", "{tmp}/p.vtu"], "--scale", ["nan", "inf", "-inf", "1e30", "abc"], "")
    c += _out_cases("fem-sweep", ["fem-sweep"], "--out", UNWRITABLE_FILES)
    c += [("fem-sweep extra", ["fem-sweep", "now"], None)]
    b = ["fem-check"]
    c += _num_cases("fem-check", b, "--points", ["-1", "0", "1000000", "abc", "2.5"], "")
    c += _num_cases("fem-check", b, "--tol", ["nan", "-1", "abc", "inf"], "")
    c += [("fem-check --scene nosuch", [*b, "--scene", "nosuch"], "nosuch")]
    for job, out in (("fem-check", None), ("fem-report", "--out")):
        for name in ("missing", "dir", "corrupt_json", "not_json", "dataset3d", "edited_points", "edited_meta",
                     "empty_file"):
            argv = [job, "--path", "{" + name + "}"] + ([out, "{tmp}/o"] if out else [])
            c.append((f"{job} --path {name}", argv, None))
    c += _out_cases("fem-report", ["fem-report"], "--out", UNWRITABLE_DIRS)
    c += _num_cases("fem-paper", ["fem-paper", "--quiet", "--out", "{tmp}/o"], "--h-mm",
                    NUMBERS_BAD + ["0", "-1", "1e-6"], "mm")
    c += _out_cases("fem-paper", ["fem-paper", "--quiet"], "--out", UNWRITABLE_DIRS)
    return c


def _fem3d_cases() -> list:
    c = []
    for sub in ("point", "vtu"):
        tail = ["--out", "{tmp}/p.vtu"] if sub == "vtu" else []
        for v in NUMBERS_BAD + ["5", "-5", "-1", "-0.05", "3"]:     # -1: the centre past the bore (was a 50.7 MN answer)
            c.append((f"fem3d {sub} penetration {v}", ["fem3d", sub, *tail, "--", v] if v.startswith("-")
                      else ["fem3d", sub, v, *tail], f"{v} mm" if v != "abc" else "abc"))
        b = ["fem3d", sub, "0.02", *tail]
        c += _num_cases(f"fem3d {sub}", b, "--tilt-arcmin", NUMBERS_BAD + ["1e6", "-1e6"], "arcmin")
        c += [(f"fem3d {sub} --level L9", [*b, "--level", "L9"], "L9"),
              (f"fem3d {sub} --scene nosuch", [*b, "--scene", "nosuch"], "nosuch")]
    c += [("fem3d point --tilt-axis x", ["fem3d", "point", "0.02", "--tilt-axis", "x"], None),
          ("fem3d point --check --level Q9", ["fem3d", "point", "0.02", "--check", "--level", "Q9"], "Q9"),
          ("fem3d point --check=yes", ["fem3d", "point", "0.02", "--check=yes"], None),
          ("fem3d vtu no --out", ["fem3d", "vtu", "0.02"], None),
          ("fem3d nosuch", ["fem3d", "nosuch"], None)]
    c += _out_cases("fem3d vtu", ["fem3d", "vtu", "0.02"], "--out", UNWRITABLE_FILES)
    c += _num_cases("fem3d sweep", ["fem3d", "sweep", "--out", "{tmp}/d.json"], "--workers",
                    ["0", "-1", "1000", "abc"], "")
    c += _out_cases("fem3d sweep", ["fem3d", "sweep"], "--out", UNWRITABLE_FILES)
    c += _num_cases("fem3d check", ["fem3d", "check"], "--points", ["-1", "0", "1000000", "abc"], "")
    c += _num_cases("fem3d check", ["fem3d", "check"], "--tol", ["nan", "-1"], "")
    for sub in ("check", "report"):
        for name in ("missing", "dir", "corrupt_json", "dataset2d", "edited_meta", "empty_file"):
            argv = ["fem3d", sub, "--path", "{" + name + "}"] + (["--out", "{tmp}/o"] if sub == "report" else [])
            c.append((f"fem3d {sub} --path {name}", argv, None))
    c += _out_cases("fem3d report", ["fem3d", "report"], "--out", UNWRITABLE_DIRS)
    return c


def _calibrate_cases() -> list:
    c = [(f"calibrate --dataset {n}", ["calibrate", "--dataset", "{" + n + "}", "--out", "{tmp}/cal"], None)
         for n in ("missing", "dir", "corrupt_json", "not_json", "edited_points", "empty_file")]
    c += _out_cases("calibrate", ["calibrate"], "--out", UNWRITABLE_DIRS)
    c += [("calibrate --check missing dir", ["calibrate", "--check", "--out", "{tmp}/none"], None)]
    return c


def _rotor_cases() -> list:
    c = []
    for sub in ("modes", "campbell", "critical-speeds", "unbalance"):
        for name in ("nosuch_scene", "bad_toml", "huge_modulus", "thin_shaft", "neg_density", "empty_file", "dir",
                     "binary", "unknown_field", "huge_unbalance"):
            c.append((f"rotor {sub} scene {name}", ["rotor", sub, "{" + name + "}"], None))
        b = ["rotor", sub, "verify-jeffcott"]
        c += _num_cases(f"rotor {sub}", b, "--elements", ["0", "-1", "100000", "abc"], "")
        c += _num_cases(f"rotor {sub}", b, "--modes", ["0", "1000000", "abc"], "")
        if sub != "modes":
            c += _num_cases(f"rotor {sub}", b, "--max-rpm", NUMBERS_BAD + ["0", "-1"], "rpm")
    b = ["rotor", "modes", "verify-jeffcott"]
    c += _num_cases("rotor modes", b, "--speed-rpm", NUMBERS_BAD + ["-1"], "rpm")
    for sub in ("campbell", "unbalance"):
        b = ["rotor", sub, "verify-jeffcott"]
        c += _num_cases(f"rotor {sub}", b, "--points", ["0", "-1", "1000000", "abc"], "")
        c += _out_cases(f"rotor {sub}", b, "--plot", ["/proc/ringcontact", "{file}/sub", "{dir}/", ""])
    c += _num_cases("rotor critical-speeds", ["rotor", "critical-speeds", "verify-jeffcott"], "--orders",
                    ["0", "-1", "1000000", "abc"], "")
    c += [("rotor unbalance --order 3", ["rotor", "unbalance", "verify-jeffcott", "--order", "3"], None),
          ("rotor unbalance --nodes nosuch", ["rotor", "unbalance", "verify-jeffcott", "--nodes", "nosuch"], "nosuch"),
          ("rotor nosuch", ["rotor", "nosuch"], None), ("rotor no sub", ["rotor"], None)]
    c += [(f"rotor static scene {name}", ["rotor", "static", "{" + name + "}"], None)
          for name in ("nosuch_scene", "bad_toml", "neg_density", "empty_file", "dir", "unknown_field")]
    c += _num_cases("rotor static", ["rotor", "static", "verify-jeffcott"], "--elements", ["0", "-1", "100000", "abc"], "")
    resp = ["rotor", "response", "verify-jeffcott", "--speed-rpm", "3000", "--out", "{tmp}/r"]
    c += [(f"rotor response --stations {v or 'EMPTY'}", [*resp, "--stations", v], None) for v in (",,,", "", "a,,b")]
    c += _out_cases("rotor report", ["rotor", "report"], "--out", UNWRITABLE_DIRS)
    return c


def _simulate_cases() -> list:
    b, c = ["simulate", "--speed-rpm", "10500", "--out", "{tmp}/o"], []
    c += _num_cases("simulate", ["simulate", "--out", "{tmp}/o"], "--speed-rpm", NUMBERS_BAD + ["-1", "0"], "rpm")
    c += _num_cases("simulate", b, "--revolutions", NUMBERS_BAD + ["0", "-1", "0.001"], "rev")
    c += [("simulate --max-revs without --steady", [*b, "--max-revs", "100"], "100 rev"),
          ("simulate --steady --max-revs 10", [*b, "--steady", "--max-revs", "10"], None)]
    c += _num_cases("simulate", b, "--steps-per-rev", ["0", "-1", "1000000000", "abc"], "")
    c += _num_cases("simulate", b, "--record-per-rev", ["0", "-1", "100000", "abc"], "")
    c += _num_cases("simulate", b, "--mu", NUMBERS_BAD + ["-0.3", "5"], "")
    c += _num_cases("simulate", b, "--preload-N", NUMBERS_BAD + ["-1"], "N")
    c += _num_cases("simulate", b, "--clearance-mm", NUMBERS_BAD + ["0", "-1", "50"], "mm")
    c += _num_cases("simulate", b, "--misalignment-mm", NUMBERS_BAD + ["-1", "500"], "mm")
    c += [("simulate --scheme x", [*b, "--scheme", "x"], None),
          ("simulate --dofs nosuch", [*b, "--dofs", "nosuch.y"], "nosuch"),
          ("simulate --law nosuch", [*b, "--law", "nosuch"], "nosuch"),
          ("simulate --law calibrated:nosuch", [*b, "--law", "calibrated:nosuch"], "nosuch"),
          ("simulate --law missing law file", [*b, "--law", "{tmp}/missing.json"], "missing.json"),
          ("simulate --law not a law file", [*b, "--law", "{not_json}"], "not.json"),
          ("simulate --law edited law file", [*b, "--law", "{edited_law_dir}/clamped-foundation.json"],
           "clamped-foundation.json"),
          ("simulate --steady reference", [*b, "--steady", "--scheme", "reference"], None),
          ("simulate no speed", ["simulate", "--out", "{tmp}/o"], None)]
    for name in ("nosuch_scene", "bad_toml", "huge_modulus", "thin_shaft"):
        c.append((f"simulate --scene {name}", [*b, "--scene", "{" + name + "}"], None))
    c += _out_cases("simulate", ["simulate", "--speed-rpm", "10500"], "--out", UNWRITABLE_DIRS)
    return c


def _study_cases() -> list:
    c = []
    for sub in ("cascade", "point", "params", "testrig", "map", "runup"):
        b = ["study", sub, "--out", "{tmp}/o", "--no-progress"]
        c += _num_cases(f"study {sub}", b, "--workers", ["0", "-1", "1000", "abc"], "")
        c += _num_cases(f"study {sub}", b, "--steps-per-rev", ["0", "1000000000", "abc"], "")
        c += _num_cases(f"study {sub}", b, "--max-revs", ["0", "-5"], "")
        c += _num_cases(f"study {sub}", b, "--elements", ["0", "100000"], "")
        c += [(f"study {sub} --scene nosuch", [*b, "--scene", "nosuch"], "nosuch"),
              (f"study {sub} --scene huge_modulus", [*b, "--scene", "{huge_modulus}"], None)]
        c += _out_cases(f"study {sub}", ["study", sub, "--no-progress"], "--out", UNWRITABLE_DIRS)
        c += _out_cases(f"study {sub}", ["study", sub, "--no-progress", "--out", "{tmp}/o"], "--figures",
                        ["/proc/ringcontact-figs", "{file}/sub"])
    for sub in ("cascade", "params", "map"):
        b = ["study", sub, "--out", "{tmp}/o", "--no-progress"]
        c += _num_cases(f"study {sub}", b, "--points", ["0", "-1", "1000000", "abc"], "")
        c += _num_cases(f"study {sub}", b, "--rpm-max", NUMBERS_BAD + ["0", "-1"], "rpm")
    b = ["study", "cascade", "--out", "{tmp}/o", "--no-progress"]
    c += _num_cases("study cascade", b, "--rpm-min", ["nan", "-1", "1e30"], "rpm")
    c += _num_cases("study cascade", b, "--clearance-mm", ["nan", "0", "50"], "mm")
    c += _num_cases("study cascade", b, "--misalignment-mm", ["-1", "nan"], "mm")
    c += [("study cascade rpm-min > rpm-max", [*b, "--rpm-min", "5000", "--rpm-max", "3000"], None)]
    for sub in ("cascade", "params"):
        for v in ("harmonic-balance", "SHOOTING", ""):
            c.append((f"study {sub} --method {v or 'EMPTY'}", ["study", sub, "--out", "{tmp}/o", "--no-progress",
                                                               "--method", v], v or None))
    c += _num_cases("study point", ["study", "point", "--out", "{tmp}/o"], "--speed-rpm", NUMBERS_BAD + ["-1"], "rpm")
    for sub, flag in (("params", "--clearances-mm"), ("params", "--misalignments-mm"), ("map", "--clearances-mm")):
        c += [(f"study {sub} {flag} {v}", ["study", sub, "--out", "{tmp}/o", flag, v], v)
              for v in ("a,b", "-1", "nan", "1e30", ",")]
    b = ["study", "runup", "--out", "{tmp}/o", "--no-progress"]
    c += _num_cases("study runup", b, "--rpm-start", NUMBERS_BAD + ["-1"], "rpm")
    c += _num_cases("study runup", b, "--rpm-end", ["nan", "1e30", "-1"], "rpm")
    c += _num_cases("study runup", b, "--duration-s", NUMBERS_BAD + ["0", "-1"], "s")
    c += [("study runup same speeds", [*b, "--rpm-start", "3000", "--rpm-end", "3000"], None)]
    for name in ("missing", "file", "dir"):
        c.append((f"study publish --cascade {name}", ["study", "publish", "--cascade", "{" + name + "}",
                                                      "--out", "{tmp}/pub"], None))
        c.append((f"study publish --map {name}", ["study", "publish", "--map", "{" + name + "}",
                                                  "--out", "{tmp}/pub"], None))
    c += [("study publish nothing", ["study", "publish", "--out", "{tmp}/pub"], None)]
    c += _out_cases("study publish", ["study", "publish", "--cascade", "{dir}"], "--out",
                    ["/proc/ringcontact-pub", "{file}/sub"])
    b = ["study", "sensitivity", "--out", "{tmp}/o", "--no-progress"]
    c += [("study sensitivity --variants nosuch", [*b, "--variants", "nosuch"], "nosuch"),
          ("study sensitivity --workers 0", [*b, "--workers", "0"], None),
          ("study sensitivity --report-only empty", [*b, "--report-only", "--report-out", "{tmp}/r"], None)]
    c += _out_cases("study sensitivity", ["study", "sensitivity", "--no-progress", "--variants", "nosuch"], "--out",
                    ["/proc/ringcontact-sens"])
    for name in ("missing", "file", "dir", "redraw_ragged", "redraw_no_column", "redraw_text", "redraw_header_only",
                 "redraw_negative"):
        c.append((f"study redraw --from {name}", ["study", "redraw", "--from", "{" + name + "}"], None))
    c += _out_cases("study redraw", ["study", "redraw", "--from", "{redraw_text}"], "--out", UNWRITABLE_DIRS)
    c += [("study redraw --from EMPTY", ["study", "redraw", "--from", ""], None),
          ("study redraw extra", ["study", "redraw", "now"], None)]
    c += [("study nosuch", ["study", "nosuch"], None), ("study no sub", ["study"], None)]
    return c


def _orbit_cases() -> list:
    c = []
    b = ["orbit", "paper-table4", "--speed-rpm", "10500"]
    c += _num_cases("orbit", ["orbit", "paper-table4"], "--speed-rpm", NUMBERS_BAD + ["-1", "0", "10500rpm"], "rpm")
    c += _num_cases("orbit", b, "--period-revs", ["0", "9", "-1", "1.5", "abc"], "revolutions")
    c += [("orbit no speed", ["orbit", "paper-table4"], None),
          ("orbit --speed-hz (wrong unit)", ["orbit", "paper-table4", "--speed-hz", "175"], None)]
    br = ["branch", "paper-table4", "--rpm-start", "10000", "--rpm-end", "11000"]
    for flag in ("--rpm-start", "--rpm-end"):
        base = [x for x in br if x not in (flag, {"--rpm-start": "10000", "--rpm-end": "11000"}[flag])]
        c += _num_cases("branch", base, flag, NUMBERS_BAD + ["-1", "0", "9000rpm"], "rpm")
    c += _num_cases("branch", br, "--max-points", ["0", "1", "-1", "1000000", "abc"], "points")
    c += [("branch rpm-start = rpm-end", ["branch", "paper-table4", "--rpm-start", "9000", "--rpm-end", "9000"],
           "9000 rpm"),
          ("branch --station nosuch", [*br, "--station", "nosuch.y"], "nosuch.y"),
          ("branch --rpm-end missing", ["branch", "paper-table4", "--rpm-start", "9000"], None),
          ("branch --speed-rpm (one speed)", [*br, "--speed-rpm", "10500"], None)]
    c += _out_cases("branch", br, "--plot", ["/proc/ringcontact", "{file}/sub", "{dir}/", ""])
    c += _num_cases("branch", br, "--turn-back-rpm", NUMBERS_BAD + ["-1", "0", "250rpm"], "rpm")
    c += [("branch --from-state nosuch", [*br, "--from-state", "/nonexistent/run"], "/nonexistent/run"),
          ("branch --from-state a file", [*br, "--from-state", "{file}"], None),
          ("branch --from-state not a run", [*br, "--from-state", "{dir}"], None),
          ("branch --family-member middle", [*br, "--family-member", "middle"], "middle"),
          ("branch --family-member empty", [*br, "--family-member", ""], None)]
    for job, base in (("orbit", b), ("branch", br)):
        c += _num_cases(job, base, "--steps-per-rev", ["0", "-1", "1000000000", "abc"], "")
        c += _num_cases(job, base, "--clearance-mm", NUMBERS_BAD + ["0", "-1", "50"], "mm")
        c += _num_cases(job, base, "--misalignment-mm", NUMBERS_BAD + ["-1", "500"], "mm")
        for name in ("nosuch_scene", "bad_toml", "huge_modulus", "thin_shaft"):
            c.append((f"{job} scene {name}", [base[0], "{" + name + "}", *base[2:]], None))
        c += _out_cases(job, base, "--out", UNWRITABLE_FILES)
        c += [(f"{job} --friction-scheme moreau", [*base, "--friction-scheme", "moreau"], "moreau")]
    return c


def _other_cases() -> list:
    c = [("report --only nosuch", ["report", "--only", "nosuch", "--out", "{tmp}/r"], None),
         ("nosuch job", ["nosuch"], None), ("empty job", [""], None)]
    c += _out_cases("report", ["report"], "--out", UNWRITABLE_DIRS)
    return c


RING_FILES = ("ring_crossing", "ring_bore_crossing", "ring_zero_clearance", "ring_nu_half", "ring_pa_modulus",
              "ring_unresolved_range", "ring_unknown_key", "ring_bad_toml", "ring_schema", "ring_tilt_no_3d")


def _bearing_cases() -> list:
    """Ring-pair files refused by every job that takes one (``bearing`` and the FEM jobs' ``--scene``)."""
    c = []
    for name in RING_FILES:
        f = "{" + name + "}"
        c += [(f"bearing {name}", ["bearing", f, "--out", "{tmp}/o"], None),
              (f"fem-point --scene {name}", ["fem-point", "0.01", "--scene", f], None),
              (f"fem3d point --scene {name}", ["fem3d", "point", "0.01", "--scene", f], None)]
    c += [("bearing missing file", ["bearing", "{missing}.toml", "--out", "{tmp}/o"], None),
          ("bearing a directory", ["bearing", "{dir}/", "--out", "{tmp}/o"], None),
          ("bearing nosuch name", ["bearing", "no-such-bearing", "--out", "{tmp}/o"], "no-such-bearing"),
          ("fem-sweep --scene ring_nu_half", ["fem-sweep", "--scene", "{ring_nu_half}", "--out", "{tmp}/d.json"], None),
          ("fem3d sweep --scene 2D only", ["fem3d", "sweep", "--scene", "clamped-stress", "--out", "{tmp}/d.json"],
           "clamped-stress"),
          ("fem3d point --scene half-clamped", ["fem3d", "point", "0.01", "--scene", "{ring_half_clamped}"], None)]
    c += _num_cases("bearing", ["bearing", "{ring_good}", "--out", "{tmp}/o"], "--workers", ["0", "-1", "abc", "1000"], "")
    c += _out_cases("bearing", ["bearing", "{ring_good}"], "--out", UNWRITABLE_DIRS[:2])
    return c


def _scene_option_cases() -> list:
    """The scene argument and loose-support overrides every rotor command shares (reports/cli/_scene_options.py):
    the same ranges everywhere, two different scenes refused, and what a command cannot apply refused."""
    c = []
    commands = {"rotor modes": [], "rotor campbell": [], "rotor critical-speeds": [], "rotor unbalance": [],
                "rotor response": ["--speed-rpm", "3000", "--out", "{tmp}/o"], "orbit": ["--speed-rpm", "3000"],
                "branch": ["--rpm-start", "3000", "--rpm-end", "3100"]}
    commands.update({f"study {s}": ["--out", "{tmp}/o", "--no-progress"]
                     for s in ("cascade", "point", "params", "testrig", "map", "runup")})
    for cmd, rest in commands.items():
        b = [*cmd.split(), "paper-table4", *rest]
        c += _num_cases(f"shared {cmd}", b, "--mu", ["5"], "")         # the full NaN/inf/sign sets: simulate's
        c += _num_cases(f"shared {cmd}", b, "--preload-N", ["-1"], "N")
        c += _num_cases(f"shared {cmd}", b, "--clearance-mm", ["0"], "mm")
        c += _num_cases(f"shared {cmd}", b, "--misalignment-mm", ["500"], "mm")
        c += [(f"shared {cmd} --law nosuch", [*b, "--law", "nosuch"], "nosuch"),
              (f"shared {cmd} two scenes", [*b, "--scene", "verify-jeffcott"], "verify-jeffcott"),
              (f"shared {cmd} --scene EMPTY", [*cmd.split(), *rest, "--scene", ""], None)]
    for cmd in ("rotor modes", "rotor campbell", "rotor critical-speeds"):      # a locked support: no contact
        c += [(f"shared {cmd} --mu on a locked support", [*cmd.split(), "paper-table4", "--mu", "0.2"], "0.2"),
              (f"shared {cmd} --misalignment-mm (no effect on frequencies)",
               [*cmd.split(), "paper-table4", "--misalignment-mm", "2"], "2 mm")]
    c += [("shared study testrig --clearance-mm (the rig's own)", ["study", "testrig", "--out", "{tmp}/o", "--clearance-mm",
                                                           "0.08"], "0.08 mm"),
          ("shared study map --clearance-mm (swept)", ["study", "map", "--out", "{tmp}/o", "--clearance-mm", "0.08"], "0.08 mm"),
          ("shared simulate --mu on a scene without loose support",
           ["simulate", "verify-jeffcott", "--speed-rpm", "3000", "--out", "{tmp}/o", "--mu", "0.2"], None)]
    for sub in ("modes", "campbell", "critical-speeds", "unbalance"):          # the table's units
        c += [(f"rotor {sub} --units {v}", ["rotor", sub, "verify-jeffcott", "--units", v], v) for v in ("khz", "rpm")]
    c += _num_cases("rotor campbell", ["rotor", "campbell", "verify-jeffcott"], "--orders", ["0", "21", "abc"], "")
    c += [("orbit --out /dev/null (a device: an atomic write would replace it)",
           ["orbit", "paper-table4", "--speed-rpm", "3000", "--out", "/dev/null"], "/dev/null")]
    c += [("rotor critical-speeds --backward=yes", ["rotor", "critical-speeds", "verify-jeffcott", "--backward=yes"],
           None)]
    return c


LONG_NAME = "x" * 250


def _trust_cases() -> list:
    """Issue "Trust under attack": damaged run directories, hostile scene files, names nothing can hold, work
    beyond the budget, options that name nothing, and values the parser took that the job refused."""
    cas = ["study", "cascade", "--points", "2", "--rpm-min", "3000", "--rpm-max", "3100", "--no-progress", "--out"]
    c = [(f"study cascade --out {d}", [*cas, "{" + d + "}"], None)
         for d in ("study_garbage_journal", "study_points_file", "study_foreign_status", "study_status_dir",
                   "study_text_journal")]
    for sub in ("modes", "campbell", "critical-speeds"):
        c += [(f"rotor {sub} zero_mass", ["rotor", sub, "{zero_mass}"], None),
              (f"rotor {sub} deep_toml", ["rotor", sub, "{deep_toml}"], None),
              (f"rotor {sub} big_scene", ["rotor", sub, "{big_scene}"], None),
              (f"rotor {sub} fifo scene", ["rotor", sub, "{fifo}"], None)]
    sim = ["simulate", "--speed-rpm", "10500", "--out", "{tmp}/o"]
    c += [("simulate zero_mass", ["simulate", "--speed-rpm", "3000", "--scene", "{zero_mass}", "--out", "{tmp}/o"], None),
          ("orbit zero_mass", ["orbit", "{zero_mass}", "--speed-rpm", "3000"], None)]
    for sub in ("point", "params", "testrig", "runup"):      # the paper's stations drawn (was an internal error)
        c.append((f"study {sub} on a scene without disk1/disk2/s", ["study", sub, "--scene", "verify-jeffcott",
                                                                   "--no-progress", "--out", "{tmp}/o"], "verify-jeffcott"))
    for sub in ("point", "params", "testrig", "map", "runup"):
        c += [(f"study {sub} --out {d}", ["study", sub, "--no-progress", "--out", "{" + d + "}"], None)
              for d in ("study_points_file", "study_garbage_journal")]
    c += [("simulate --scene deep_toml", [*sim, "--scene", "{deep_toml}"], None),
          ("orbit deep_toml", ["orbit", "{deep_toml}", "--speed-rpm", "10500"], None),
          ("simulate --law deep_json", [*sim, "--law", "{deep_json}"], None),
          ("simulate --dofs EMPTY", [*sim, "--dofs", ""], None),
          ("simulate --stations ' , '", [*sim, "--stations", " , "], None),
          ("simulate --steps-per-rev 100 --record-per-rev 64", [*sim, "--steps-per-rev", "100", "--record-per-rev",
                                                                 "64"], "64"),
          ("branch --station EMPTY", ["branch", "paper-table4", "--rpm-start", "10500", "--rpm-end", "11000",
                                      "--station", ""], None),
          ("study runup --duration-s 0.05", ["study", "runup", "--duration-s", "0.05", "--out", "{tmp}/o"], "0.05 s"),
          ("study cascade --points 2000 over 1-2 rpm", ["study", "cascade", "--points", "2000", "--rpm-min", "1",
                                                        "--rpm-max", "2", "--out", "{tmp}/o"], "2000"),
          ("study redraw NaN cell", ["study", "redraw", "--from", "{redraw_nan}", "--out", "{tmp}/o"], "nan"),
          ("fem3d point --tilt-arcmin 172", ["fem3d", "point", "0.02", "--tilt-arcmin", "172"], "172 arcmin"),
          ("fem3d vtu --tilt-arcmin 600", ["fem3d", "vtu", "0.02", "--tilt-arcmin", "600", "--out", "{tmp}/q.vtu"],
           "600 arcmin")]
    # a file name the job's temporary (.NAME.PID.XXXXXXXX.tmp) or suffix would take past 255 bytes; a folder's
    # own name past 255 bytes (was an internal OSError, ENAMETOOLONG)
    for job, argv, name in (("simulate", [*sim[:3], "--out"], "y" * 300), ("fem-vtu", ["fem-vtu", "0.01"], LONG_NAME),
                            ("orbit", ["orbit", "paper-table4", "--speed-rpm", "10500", "--out"], LONG_NAME),
                            ("rotor campbell", ["rotor", "campbell", "verify-jeffcott", "--plot"], LONG_NAME),
                            ("study cascade", ["study", "cascade", "--no-progress", "--out"], "y" * 300),
                            ("fem3d vtu", ["fem3d", "vtu", "0.02", "--out"], LONG_NAME)):
        c.append((f"{job} over-long output name", [*argv, "{tmp}/" + name], None))
    long_in = "{tmp}/" + "z" * 300            # an input name past 255 bytes (Path.exists raised ENAMETOOLONG)
    c += [(f"{' '.join(a[:2])} over-long input name", a, None)
          for a in (["rotor", "modes", long_in], ["law", "--csv", long_in], [*sim, "--scene", long_in],
                    ["fem-point", "0.01", "--scene", long_in + ".toml"], ["bearing", long_in + ".toml", "--out", "{tmp}/o"],
                    ["study", "redraw", "--from", long_in], ["study", "export", long_in])]
    # long work refused before it starts, with the estimate and the flag that accepts it
    c += [("orbit --steps-per-rev 100000", ["orbit", "paper-table4", "--speed-rpm", "10500", "--steps-per-rev",
                                            "100000"], "--accept-long"),
          ("branch --steps-per-rev 100000", ["branch", "paper-table4", "--rpm-start", "10500", "--rpm-end", "11000",
                                             "--steps-per-rev", "100000"], "--accept-long"),
          ("simulate 1e5 rev at 1e5 steps", [*sim, "--revolutions", "100000", "--steps-per-rev", "100000",
                                             "--record-per-rev", "1"], "--accept-long"),
          ("study runup --duration-s 3600", ["study", "runup", "--duration-s", "3600", "--no-progress", "--out",
                                             "{tmp}/o"], "--accept-long"),
          ("study cascade 18 rpm", ["study", "cascade", "--rpm-max", "18", "--points", "2", "--no-progress", "--out",
                                    "{tmp}/o"], "--accept-long"),
          ("rotor campbell 64 elements 2000 points", ["rotor", "campbell", "paper-table4", "--elements", "64",
                                                      "--points", "2000", "--modes", "200"], "--accept-long"),
          ("rotor response newmark 1e5 rev", ["rotor", "response", "paper-table4", "--speed-rpm", "3000",
                                              "--revolutions", "100000", "--method", "newmark", "--steps-per-rev",
                                              "65536", "--out", "{tmp}/r"], "--accept-long")]
    return c


def _trust_inputs(root: Path, p: dict) -> None:
    """Damaged study directories, hostile scene and law files (:func:`_trust_cases`)."""
    scene = (ROOT / "rotor" / "scenes" / "verify-jeffcott.toml").read_text()
    files = {"deep_toml": "x = " + "[" * 5000 + "]" * 5000 + "\n",
             "zero_mass": _scene_variant(scene, "mass_kg = 10", "mass_kg = 0"),
             "big_scene": scene + "# padding\n" * 600_000}
    for k, text in files.items():
        p[k] = root / f"{k}.toml"
        p[k].write_text(text)
    p["deep_json"] = root / "deep.json"
    p["deep_json"].write_text("[" * 100_000 + "]" * 100_000)
    dirs = {"study_garbage_journal": {"journal.jsonl": bytes(range(128, 256)) * 8},
            "study_text_journal": {"journal.jsonl": b"hello\nworld\nnot a journal\n"},
            "study_points_file": {"points": b"not a folder\n"},
            "study_foreign_status": {"status.json": b'{"state": "finished by someone else", "owner": "tool"}\n'},
            "study_status_dir": {"status.json/": b""}}
    for name, parts in dirs.items():
        d = root / name
        d.mkdir(exist_ok=True)
        for part, data in parts.items():
            if part.endswith("/"):
                (d / part).mkdir(exist_ok=True)
            else:
                (d / part).write_bytes(data)
        p[name] = d
    cascade = (ROOT / "reports" / "published" / "study-cascade.csv").read_text().splitlines()
    row = cascade[1].split(",")
    row[cascade[0].split(",").index("disk1_v1X_mm_s")] = "nan"
    d = root / "redraw_nan"
    d.mkdir(exist_ok=True)
    (d / "study-cascade.csv").write_text(cascade[0] + "\n" + ",".join(row) + "\n" + "\n".join(cascade[2:]) + "\n")
    p["redraw_nan"] = d


CASES = _law_cases() + _fem_cases() + _fem3d_cases() + _calibrate_cases() + _rotor_cases() + _simulate_cases() \
    + _study_cases() + _orbit_cases() + _other_cases() + _bearing_cases() + _scene_option_cases() + _trust_cases()


def _ring_inputs(root: Path, p: dict) -> None:
    """Ring-pair files, each broken in one key (fem_reference/ring_scenes/steel-in-aluminium.toml as the base)."""
    good = (ROOT / "fem_reference" / "ring_scenes" / "steel-in-aluminium.toml").read_text()
    v = _scene_variant
    rings = {"ring_good": good.replace("tilt_arcmin = [0, 2]", "tilt_arcmin = [0, 0]"),
             "ring_crossing": v(good, "inner_radius_mm = 48.0", "inner_radius_mm = 60.0"),
             "ring_bore_crossing": v(good, "outer_radius_mm = 75.0", "outer_radius_mm = 54.0"),
             "ring_zero_clearance": v(good, "radial_clearance_mm = 0.03", "radial_clearance_mm = 0"),
             "ring_nu_half": v(good, "poisson_ratio = 0.33", "poisson_ratio = 0.5"),
             "ring_pa_modulus": v(good, "youngs_modulus_gpa = 72.0", "youngs_modulus_gpa = 72e9"),
             "ring_unresolved_range": v(good, "penetration_mm = [0.004, 0.04]", "penetration_mm = [1e-7, 0.04]"),
             "ring_unknown_key": v(good, "width_mm = 22.0", "width_mm = 22.0\nlength_mm = 3"),
             "ring_bad_toml": "schema = [not toml\n",
             "ring_schema": v(good, 'schema = "ringcontact.ring-scene/1"', 'schema = "ringcontact.ring-scene/7"'),
             "ring_tilt_no_3d": v(good, 'hold = "clamped-outer-axially-free"', 'hold = "clamped-outer-upper"'),
             "ring_half_clamped": v(good.replace("tilt_arcmin = [0, 2]", "tilt_arcmin = [0, 0]"),
                                    'hold = "clamped-outer-axially-free"', 'hold = "clamped-outer-upper"')}
    for k, text in rings.items():
        p[k] = root / f"{k}.toml"
        p[k].write_text(text)


def _scene_variant(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def make_inputs(root: Path) -> dict[str, str]:
    """Create the malformed inputs under ``root``; return placeholder -> path."""
    root.mkdir(parents=True, exist_ok=True)
    p = {"file": root / "plain.txt", "dir": root / "empty-dir", "missing": root / "no-such-file"}
    p["file"].write_text("hello\n")
    p["dir"].mkdir(exist_ok=True)
    csvs = {"good_csv": "penetration_mm,tilt_arcmin\n0.01,1\n", "ragged": "penetration_mm,tilt_arcmin\n0.01,1\n0.02\n",
            "empty_cell": "penetration_mm,tilt_arcmin\n0.01,\n,1\n", "header_only": "penetration_mm\n",
            "no_column": "pen,tilt\n0.01,1\n", "nan_csv": "penetration_mm\nnan\n", "deep_csv": "penetration_mm\n5\n",
            "text_value": "penetration_mm\nten\n",
            "huge_csv": "penetration_mm,tilt_arcmin\n" + "0.01,1\n" * 200_000,
            "dup_column": "penetration_mm,penetration_mm\n0.01,0.02\n", "unknown_column": "penetration_mm,speed\n0.01,3\n"}
    for k, text in csvs.items():
        p[k] = root / f"{k}.csv"
        p[k].write_text(text)
    p["fifo"] = root / "points.fifo"          # reading a pipe nobody writes to blocks forever
    if not p["fifo"].exists():
        os.mkfifo(p["fifo"])
    p["zero_link"] = root / "zero.csv"        # a link to a device that never ends
    if not p["zero_link"].is_symlink():
        p["zero_link"].symlink_to("/dev/zero")
    p["binary"] = root / "binary.bin"
    p["binary"].write_bytes(bytes(range(256)) * 4)
    p["empty_file"] = root / "empty.json"
    p["empty_file"].write_text("")
    p["corrupt_json"] = root / "corrupt.json"
    p["corrupt_json"].write_text('{"schema": "ringcontact/reference-dataset", "points": [')
    p["not_json"] = root / "not.json"
    p["not_json"].write_text("penetration,force\n1,2\n")
    d2 = ROOT / "fem_reference" / "data" / "fem2d-reference.json"
    d3 = ROOT / "fem_reference" / "data" / "3d" / "fem3d-reference.json"
    p["dataset2d"], p["dataset3d"] = d2, d3
    doc = json.loads(d2.read_text())
    doc["points"][0]["force_n"] *= 1.01
    p["edited_points"] = root / "edited-points.json"
    p["edited_points"].write_text(json.dumps(doc))
    doc = json.loads(d3.read_text())
    doc["metadata"]["edited"] = "clearance changed by hand"
    p["edited_meta"] = root / "edited-meta.json"
    p["edited_meta"].write_text(json.dumps(doc))
    law_dir = root / "calibrated"
    law_dir.mkdir(exist_ok=True)
    for f in (ROOT / "contact" / "calibrated").glob("*.json"):
        (law_dir / f.name).write_text(f.read_text().replace("204000000000", "104000000000"))
    p["edited_law_dir"] = law_dir
    scene = (ROOT / "rotor" / "scenes" / "verify-jeffcott.toml").read_text()
    scenes = {"bad_toml": "this is [not toml\n", "huge_modulus": _scene_variant(scene, "youngs_modulus_gpa = ",
                                                                               "youngs_modulus_gpa = 200e9 # "),
              "thin_shaft": _scene_variant(scene, "outer_diameter_mm = ", "outer_diameter_mm = 0.02 # "),
              "neg_density": _scene_variant(scene, "density_kg_m3 = ", "density_kg_m3 = -7800 # "),
              "unknown_field": _scene_variant(scene, "density_kg_m3 = ", "density_kg = 7800\ndensity_kg_m3 = "),
              "huge_unbalance": _scene_variant(scene, "unbalance_g_mm = ", "unbalance_g_mm = 1e300 # ")}
    for k, text in scenes.items():
        p[k] = root / f"{k}.toml"
        p[k].write_text(text)
    p["nosuch_scene"] = "no-such-scene"
    _ring_inputs(root, p)
    _redraw_inputs(root, p)
    _trust_inputs(root, p)
    return {k: str(v) for k, v in p.items()}


def _redraw_inputs(root: Path, p: dict) -> None:
    """Folders of broken study-*.csv tables for ``study redraw --from`` (each refused before drawing)."""
    published = ROOT / "reports" / "published"
    points = (published / "study-sensitivity-points.csv").read_text().splitlines()
    params = (published / "study-params.csv").read_text().splitlines()
    cascade = (published / "study-cascade.csv").read_text().splitlines()
    text_row = cascade[1].split(",")
    text_row[cascade[0].split(",").index("disk1_v1X_mm_s")] = "ten"
    negative_row = points[1].split(",")[:5] + ["-1"] * (len(points[0].split(",")) - 5)
    bad = {"redraw_ragged": {"study-params.csv": "\n".join(params[:2] + [params[2].rsplit(",", 2)[0]]) + "\n"},
           "redraw_no_column": {"study-cascade.csv": "speed_rpm,converged\n0,1\n"},
           "redraw_text": {"study-cascade.csv": cascade[0] + "\n" + ",".join(text_row) + "\n"},
           "redraw_header_only": {"study-sensitivity-points.csv": points[0] + "\n"},
           # a good table beside a bad one: nothing is drawn from the good one either
           "redraw_negative": {"study-params.csv": "\n".join(params[:3]) + "\n",
                               "study-sensitivity-points.csv": points[0] + "\n" + ",".join(negative_row) + "\n"}}
    for name, tables in bad.items():
        d = root / name
        d.mkdir(exist_ok=True)
        for fname, text in tables.items():
            (d / fname).write_text(text)
        p[name] = d


PRELOAD = ("reports.cli.law", "reports.cli.fem", "reports.cli.fem3d", "reports.cli.rotor", "reports.cli.simulate",
           "reports.cli.study", "reports.cli.calibrate", "reports.cli.report", "fem_reference.plane.sweep",
           "fem_reference.solid.sweep", "rotor.model.assembly", "rotor.studies.steady_state", "matplotlib.pyplot")


def preload() -> None:
    """Import the jobs' modules once, and load (or compile) the compiled loose-support kernel, so that each forked
    case starts warm. A rotor job's time-step check evaluates the support law before it can refuse a step count
    (``simulate --revolutions 0.001``); compiled in a forked case from a cold cache that took 28 s of CPU, past a
    case's 10 s, where this file ran before any other test had compiled it (the test files spread over two workers,
    dev.py)."""
    import importlib
    for name in PRELOAD:
        try:
            importlib.import_module(name)
        except Exception:          # noqa: BLE001 - a module the old code lacks
            pass
    from rotor.dynamics.system import largest_stable_step
    from rotor.studies.steady_state import point_system
    largest_stable_step(point_system("paper-table4", 10500.0)[2])


def fill(argv: list[str], inputs: dict[str, str], tmp: Path) -> list[str]:
    """Substitute the placeholders of one case."""
    return [a.format(tmp=tmp, **inputs) if "{" in a else a for a in argv]


def _child(argv: list[str], out_dir: Path, cwd: Path | None) -> None:
    import resource
    import traceback
    os.setpgid(0, 0)
    if cwd is not None:
        os.chdir(cwd)             # default outputs (relative paths) land in the case's own directory
    resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))
    for fd, name in ((1, "stdout"), (2, "stderr")):
        f = os.open(out_dir / name, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(f, fd)
    sys.stdout = open(1, "w", closefd=False)
    sys.stderr = open(2, "w", closefd=False)
    res = {"outcome": "exit"}
    try:
        from reports import cli
        res["rc"] = cli.main(list(argv))
    except SystemExit as exc:
        res["rc"] = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    except BaseException as exc:    # noqa: BLE001 - the suite counts these
        res.update(outcome="traceback", error=f"{type(exc).__name__}: {exc}"[:300])
        traceback.print_exc()
    sys.stdout.flush()
    sys.stderr.flush()
    (out_dir / "result.json").write_text(json.dumps(res))
    os._exit(0)


#: a child that does not end within this many times its CPU allowance of wall time, computing or not, hangs
WALL_FACTOR = 10.0


def _cpu_s(pid: int) -> float:
    """CPU seconds (user + system) of process ``pid`` so far; 0 when it is gone."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return 0.0
    f = text[text.rindex(")") + 2:].split()
    return (int(f[11]) + int(f[12])) / os.sysconf("SC_CLK_TCK")


def run_case(argv: list[str], out_dir: Path, timeout_s: float = 10.0, cwd: Path | None = None) -> dict:
    """Run ``ringcontact ARGV`` in a forked child (warm, 4 GiB address-space cap, own process group).

    Returns ``rc``, ``outcome`` ('exit', 'traceback' or 'hang': killed with its workers after
    ``timeout_s`` of the child's own CPU time, or ``WALL_FACTOR`` times that of wall time when it sits idle),
    ``stdout``, ``stderr`` and ``wall_s``. CPU time, not wall time: on a shared machine at load 5-9 a case
    that takes 1 s idle takes several seconds of wall time, and would be called a hang.
    """
    out_dir.mkdir(parents=True, exist_ok=True)
    sys.stdout.flush()
    sys.stderr.flush()
    t0 = time.perf_counter()
    pid = os.fork()
    if pid == 0:
        _child(argv, out_dir, cwd)
    res = {"rc": None, "outcome": "hang", "error": ""}
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        if _cpu_s(pid) > timeout_s or time.perf_counter() - t0 > WALL_FACTOR * timeout_s:
            try:
                os.killpg(pid, signal.SIGKILL)
            except OSError:
                os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            break
        time.sleep(0.005)
    try:
        os.killpg(pid, signal.SIGKILL)        # workers a pool left behind
    except OSError:
        pass
    if (out_dir / "result.json").exists():
        res.update(json.loads((out_dir / "result.json").read_text()))
    elif done:
        res.update(outcome="crash", error=f"status {status}")
    res["wall_s"] = time.perf_counter() - t0
    for name in ("stdout", "stderr"):
        f = out_dir / name
        res[name] = f.read_text(errors="replace") if f.exists() else ""
    return res


if __name__ == "__main__":      # measure: python tests/reports/bad_inputs.py OUT.json (run from a scratch copy)
    import tempfile
    work = Path(tempfile.mkdtemp(prefix="bad-inputs-"))
    os.chdir(work)
    inputs = make_inputs(work / "inputs")
    preload()
    rows = []
    for i, (cid, argv, echo) in enumerate(CASES):
        tmp = work / f"case{i}"
        tmp.mkdir()
        r = run_case(fill(argv, inputs, tmp), work / f"io{i}", cwd=tmp)
        r.update(id=cid, stderr=r["stderr"][-400:], stdout=r["stdout"][-200:])
        rows.append(r)
        print(f"{r['outcome']:9s} rc={r['rc']} {r['wall_s']:5.1f}s {cid} | {r['error'] or r['stderr'].strip()[:150]!r}",
              flush=True)
    Path(sys.argv[1]).write_text(json.dumps(rows, indent=1))
