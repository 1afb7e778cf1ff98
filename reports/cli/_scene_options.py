"""The scene argument and the loose-support overrides shared by every job that runs the rotor.

``rotor`` (modes, campbell, critical-speeds, unbalance, response), ``simulate``, ``orbit``, ``branch`` and
``study`` (cascade, point, params, testrig, map, runup) take the same spelling of the same options, with the
same defaults:

* the scene: a bundled scene name or a TOML path, given either as the first positional argument or as
  ``--scene`` (both spellings everywhere; default ``paper-table4``);
* the loose-support overrides of the scene (None keeps the scene's value): ``--law`` (as a scene's
  ``[loose_support] law`` key, :mod:`rotor.model.loose_support_scene`), ``--mu``, ``--preload-N``,
  ``--clearance-mm``, ``--misalignment-mm``, ``--tilt-ignored``;
* the transient cap ``--max-revs`` (:data:`MAX_TRANSIENT_REVS`) of the jobs that detect a steady state.

:func:`add_scene_options` puts them on a parser, :func:`finish` resolves the two spellings of the scene after
parsing, :func:`scene_from_args` returns the scene and the overrides as the keyword arguments of
:func:`rotor.studies.steady_state.point_system` (SI). Ranges are those of :mod:`contact.plausible`, checked by
the parser (:func:`reports.cli._edge.quantity`). Command-line only: the Python API builds scenes itself.
"""
from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass, field

from contact.errors import InputError
from reports.cli._edge import count, quantity

DEFAULT_SCENE = "paper-table4"
#: transient cap (revolutions) of every steady-state detection (``simulate --steady``, ``study``): at the
#: paper's point A (Table 4, 4 500 rpm) the end faces creep for about 2 000 revolutions before the ring
#: settles, so a lower cap reports points that are still settling as not converged
MAX_TRANSIENT_REVS = 8000
#: the overrides, flag -> (attribute, keyword of point_system, factor to SI)
OVERRIDES = {"--law": ("law", "law", None), "--mu": ("mu", "mu", 1.0), "--preload-N": ("preload_n", "preload_n", 1.0),
             "--clearance-mm": ("clearance_mm", "clearance_m", 1e-3),
             "--misalignment-mm": ("misalignment_mm", "misalignment_m", 1e-3),
             "--tilt-ignored": ("tilt_ignored", "tilt_ignored", None)}


@dataclass(frozen=True)
class SceneChoice:
    """The scene as typed (name or path) and the overrides given, as keyword arguments of
    :func:`rotor.studies.steady_state.point_system` (SI; only those given: ``tilt_ignored`` only when True)."""
    scene: str
    overrides: dict = field(default_factory=dict)


def add_scene_options(p: argparse.ArgumentParser, *, default: str = DEFAULT_SCENE, transient: bool = False) -> None:
    """The scene (positional or ``--scene``) and the loose-support overrides; ``transient``: also ``--max-revs``."""
    p.add_argument("scene_positional", nargs="?", default=None, metavar="SCENE",
                   help=f"scene name or TOML path (or --scene; default {default})")
    p.add_argument("--scene", dest="scene_option", default=None, metavar="SCENE",
                   help=f"the same as the positional SCENE (default {default})")
    p.set_defaults(scene_default=default)
    g = p.add_argument_group("scene overrides (default: the scene's value)")
    g.add_argument("--law", default=None, metavar="LAW",
                   help="radial contact law instead of the scene's [loose_support] law: conformal (the paper's law "
                        "as published), pereira, calibrated:<name> (contact/calibrated/<name>.json) or the path of a "
                        "calibrated-law file (.json); a calibrated law's clearance, ring width and materials must be "
                        "the scene's")
    g.add_argument("--mu", type=quantity("mu"), default=None, help="end-face friction coefficient (-)")
    g.add_argument("--preload-N", "--preload-n", dest="preload_n", type=quantity("preload_N"), default=None,
                   help="nut preload per end face (N)")
    g.add_argument("--clearance-mm", type=quantity("clearance_mm"), default=None, help="radial clearance (mm)")
    g.add_argument("--misalignment-mm", type=quantity("misalignment_mm"), default=None,
                   help="misalignment offset δ (mm; 0 removes the offset and the 2X excitation)")
    g.add_argument("--tilt-ignored", action="store_true",
                   help="line contact: no moment between bearing and support (paper §5.2, Fig. 16)")
    if transient:
        from rotor.studies.steady_state import SteadyStateOptions      # the detector's shortest transient
        p.add_argument("--max-revs", type=count(SteadyStateOptions.min_revs, 100000, "revolutions"), default=None,
                       help=f"transient cap of the steady-state detection in revolutions (default "
                            f"{MAX_TRANSIENT_REVS}: at the paper's point A the end faces creep for about 2 000 "
                            "revolutions before the ring settles; at least 24, the detector's shortest transient)")


def add_law_check_option(p: argparse.ArgumentParser) -> None:
    """``--allow-flagged-law``: run on a law its own file flags (held-out error beyond the bound of
    ``ringcontact bearing`` or ``calibrate``), refused without it (:func:`rotor.model.law_validity.check_allowed`)."""
    p.add_argument("--allow-flagged-law", action="store_true",
                   help="run even when the contact law's file flags it (its held-out error beyond the FEM's stated "
                        "error by more than the bound); refused without it. The run's law_validity says so")


def say_on_terminal(args, line: str) -> None:
    """``line`` on stderr where progress goes (a terminal, or ``--progress``; not with ``--no-progress``: the rule
    of :func:`sweep.progress.on_terminal`), so that a job's output and its one-line errors stay as they are in a
    pipe or a log: the geometry and law a rotor job runs on (:func:`rotor.model.law_validity.law_line`)."""
    from sweep.progress import on_terminal
    force = False if getattr(args, "no_progress", False) else getattr(args, "progress", None)
    if on_terminal(force=force):
        print(line, file=sys.stderr, flush=True)


def finish(parser: argparse.ArgumentParser, args: argparse.Namespace, sub: str | None = None) -> argparse.Namespace:
    """Resolve ``args.scene`` from the two spellings (a parser error when they name different scenes); ``sub``:
    the sub-command whose parser reports the error (``rotor modes``, ``study cascade``)."""
    if not hasattr(args, "scene_positional"):
        return args
    if sub is not None:
        parser = next(sp for a in parser._actions if isinstance(a, argparse._SubParsersAction)
                      for name, sp in a.choices.items() if name == sub)
    pos, opt = args.scene_positional, args.scene_option
    if pos is not None and opt is not None and pos != opt:
        parser.error(f"argument --scene: = {opt}: the positional scene is {pos}; give the scene once")
    args.scene = pos if pos is not None else opt if opt is not None else args.scene_default
    if not str(args.scene).strip():
        parser.error("argument --scene: = '': must name a bundled scene or a TOML file")
    return args


def scene_from_args(args) -> SceneChoice:
    """The scene and the overrides given (SI keywords of :func:`rotor.studies.steady_state.point_system`)."""
    kw = {}
    for flag, (attr, key, scale) in OVERRIDES.items():
        value = getattr(args, attr, None)
        if value is None or value is False:
            continue
        kw[key] = value * scale if scale is not None else value
    scene = getattr(args, "scene", None)
    if scene is None:      # parsed without finish(): the positional spelling first, then --scene, then the default
        scene = next(v for v in (args.scene_positional, args.scene_option, args.scene_default) if v is not None)
    return SceneChoice(str(scene), kw)


def max_revs(args) -> int:
    """``--max-revs`` or its default :data:`MAX_TRANSIENT_REVS`."""
    return int(args.max_revs) if getattr(args, "max_revs", None) is not None else MAX_TRANSIENT_REVS


def refuse_overrides(args, flags, why: str) -> None:
    """One line (exit 2) for an override that the job cannot apply: ``flags`` of :data:`OVERRIDES`, ``why``
    says what the job does instead."""
    for flag in flags:
        value = getattr(args, OVERRIDES[flag][0], None)
        if _given(value):
            shown = "" if value is True else f" = {value:g}" if isinstance(value, float) else f" = {value}"
            unit = {"--preload-N": " N", "--clearance-mm": " mm", "--misalignment-mm": " mm"}.get(flag, "")
            raise InputError(f"{flag}{shown}{unit if shown else ''}: {why}")


LOCKED = ("the linear analyses lock the loose support (bearing and support move together; --open-support leaves them "
          "apart): no contact law, friction, preload or clearance acts; simulate, orbit, branch and study apply it")


def linear_scene(args, scene, *, misalignment: bool):
    """``scene`` for a linear job (``ringcontact rotor``): the loose-support overrides refused (:data:`LOCKED`), and
    ``--misalignment-mm`` applied where the job's answer depends on it (``misalignment``: the 2X response), refused
    where it does not (natural frequencies)."""
    from dataclasses import replace

    refuse_overrides(args, [f for f in OVERRIDES if f != "--misalignment-mm"], LOCKED)
    if not misalignment:
        refuse_overrides(args, ("--misalignment-mm",), "the natural frequencies do not depend on the misalignment "
                         "offset (a static load); rotor unbalance --order 2 and rotor response apply it")
        return scene
    if getattr(args, "misalignment_mm", None) is None:
        return scene
    if scene.misalignment is None:
        if args.misalignment_mm == 0:
            return scene
        raise InputError(f"--misalignment-mm = {args.misalignment_mm:g} mm: scene {scene.name!r} has no "
                         "[misalignment] to scale; set it in the scene")
    return replace(scene, misalignment=replace(scene.misalignment, offset_m=args.misalignment_mm * 1e-3))


def add_progress_option(p: argparse.ArgumentParser) -> None:
    """``--progress``: the progress line on stderr also when it is not a terminal (default: only on a terminal,
    :func:`sweep.progress.on_terminal`); never on stdout, so ``--json`` output stays clean."""
    p.add_argument("--progress", action="store_true", default=None,
                   help="progress on stderr (compile, transient, Newton residual per iteration, branch points and "
                        "time left) even when stderr is not a terminal (default: only on a terminal)")


def warm_up_shown(label: str, args, warm_up) -> dict:
    """Run ``warm_up()`` (a compile of the step loop, or its load from the disk cache) with the seconds shown on a
    terminal while it lasts more than a second (:class:`sweep.progress.Elapsed`); its result."""
    from sweep.progress import Elapsed
    with Elapsed(label, "compiling the step loop, first run only", enabled=getattr(args, "progress", None)):
        return warm_up()


def override_words(args) -> str:
    """The overrides given, as typed options (`` --mu 0 --law pereira``), for a command a message suggests."""
    words = []
    for flag, (attr, _, _) in OVERRIDES.items():
        value = getattr(args, attr, None)
        if value is True:
            words.append(flag)
        elif _given(value):
            words.append(f"{flag} {value:g}" if isinstance(value, float) else f"{flag} {value}")
    return "".join(" " + w for w in words)


def _given(value) -> bool:
    """An override given: not None and not an unset flag (a value of 0 is given: ``--mu 0``)."""
    return value is not None and value is not False


def scene_top_rpm(scene) -> float:
    """The scene's ``[analysis] max_speed_rpm`` (rpm) as typed (12 significant digits: stored in rad/s)."""
    return float(f"{scene.analysis.max_speed_rad_s * 30.0 / math.pi:.12g}")


def warn_speeds_beyond_scene(prog: str, scene, speeds_rpm) -> float | None:
    """One warning line on stderr when a job runs faster than its scene's speed range (``[analysis]
    max_speed_rpm``: the range the scene's author modelled, its Campbell diagram's; 2 000 rpm where a scene gives
    none); returns that top speed (rpm) when passed, else None."""
    top = scene_top_rpm(scene)
    fastest = max((float(s) for s in speeds_rpm), default=0.0)
    if fastest <= top * (1 + 1e-9):
        return None
    from rotor.model.scene import Analysis
    said = " (the default: the scene gives no [analysis] max_speed_rpm)" if scene.analysis == Analysis() else ""
    print(f"{prog}: warning: {fastest:g} rpm is beyond scene {scene.name!r}'s speed range, max_speed_rpm = {top:g} rpm"
          f"{said}: check that the rotor's model holds there (bearings, speed tables, critical speeds)",
          file=sys.stderr, flush=True)
    return top
