"""The orbits ``ringcontact orbit`` and ``ringcontact branch`` start on when told (reports/cli/orbit.py): an
``orbit --out`` file (``--from-orbit``) or the end of a ``simulate --out`` run (``--from-state``), read and checked
before any computing (a bad file: :class:`contact.errors.InputError`, exit 2 with one line)."""
from __future__ import annotations

import json
from pathlib import Path

from contact.errors import InputError, RingContactError


def chosen_orbit(args, name: str) -> dict:
    """``start``, ``period_revs`` and ``steps_per_rev`` of the ``orbit --out`` file ``--from-orbit`` (empty without
    it); the file's scene and speed must be the branch's."""
    if args.from_orbit is None:
        return {}
    got, rpm = orbit_file(args, name)
    if abs(rpm - args.rpm_start) > 1e-9 * rpm:
        raise InputError(f"--rpm-start = {args.rpm_start:g} rpm: the orbit of --from-orbit is at {rpm!r} rpm; "
                         "start the branch there")
    return got


def orbit_file(args, name: str) -> tuple[dict, float]:
    """``({start, period_revs, steps_per_rev}, speed_rpm)`` of the ``orbit --out`` file ``--from-orbit``, an orbit
    of scene ``name`` (``--steps-per-rev`` where given, else the file's)."""
    import numpy as np
    try:
        o = json.loads(Path(args.from_orbit).read_text(encoding="utf-8"))
        state, rpm, scene = o["phase0_state"], float(o["speed_rpm"]), o["scene"]
        got = {"start": (np.array(state["q_m_rad"], float), np.array(state["v_m_s_rad_s"], float)),
               "period_revs": int(o["period_revs"]),
               "steps_per_rev": args.steps_per_rev or (int(o["steps_per_rev"]) if o.get("steps_per_rev") else None)}
    except (ValueError, KeyError, TypeError) as e:
        raise InputError(f"--from-orbit = {args.from_orbit}: not an `orbit --out` file with phase0_state "
                         f"({type(e).__name__}: {e})") from None
    if scene != name:
        raise InputError(f"--from-orbit = {args.from_orbit}: an orbit of scene {scene}, not of {name}")
    q, v = got["start"]
    steps = got["steps_per_rev"]
    # the file's numbers within what the options themselves allow (--period-revs 1-8, --steps-per-rev 16-100000)
    if not (np.all(np.isfinite(q)) and np.all(np.isfinite(v)) and 1 <= got["period_revs"] <= 8
            and (steps is None or 16 <= steps <= 100000)):
        raise InputError(f"--from-orbit = {args.from_orbit}: its phase0_state must be finite, its period_revs 1 to 8 "
                         f"and its steps_per_rev 16 to 100000 (has period_revs {got['period_revs']}, steps_per_rev "
                         f"{steps})")
    return got, rpm


def state_start(args, name: str, n_dofs: int) -> dict:
    """``start`` (full ``(q, v)`` at phase 0) from the last sample of the ``simulate --out`` run ``--from-state``
    (empty without it): the run complete (:func:`contact.files.check_run_files`), of the branch's scene and
    ``--rpm-start``, with the branch's DOFs, ended after a whole number of revolutions (phase 0)."""
    if args.from_state is None:
        return {}
    import numpy as np

    from contact.files import check_run_files
    opt = f"--from-state = {args.from_state}"
    try:
        summary = check_run_files(args.from_state, "simulate")
        scene, rpm = summary["scene"], float(summary["speed_rpm"])
        with np.load(Path(args.from_state) / "simulate.npz") as z:
            t, q, v = float(z["t"][-1]), np.array(z["q"][-1], float), np.array(z["v"][-1], float)
    except RingContactError as e:
        raise InputError(f"{opt}: not a complete `simulate --out` run ({e})") from None
    except (OSError, ValueError, KeyError, TypeError, IndexError) as e:
        raise InputError(f"{opt}: not a `simulate --out` run with simulate.npz ({type(e).__name__}: {e})") from None
    if scene != name:
        raise InputError(f"{opt}: a run of scene {scene}, not of {name}")
    if abs(rpm - args.rpm_start) > 1e-9 * rpm:
        raise InputError(f"--rpm-start = {args.rpm_start:g} rpm: the run of --from-state is at {rpm!r} rpm; "
                         "start the branch there")
    revs = t * rpm / 60.0
    if abs(revs - round(revs)) > 1e-6 * max(1.0, revs) or round(revs) < 1:
        raise InputError(f"{opt}: the run ends after {revs:.6g} revolutions; a start needs a whole number (phase 0): "
                         "run simulate with whole --revolutions")
    if q.shape != (n_dofs,) or v.shape != (n_dofs,) or not (np.all(np.isfinite(q)) and np.all(np.isfinite(v))):
        raise InputError(f"{opt}: its state has {q.shape[0] if q.ndim else 0} DOFs, the branch's scene {n_dofs} "
                         "(another mesh or scene options), or is not finite")
    return {"start": (q, v)}
