"""The readings of Eq. 34 (the misalignment excitation) as named scene variants, and their points.

Dai et al. (2025) give Eq. 34's magnitudes ``F = 2 m_sp L tan(Δθ/2) Ω²`` and
``M = m_sp L² tan(Δθ/2) Ω²`` but neither ``m_sp`` nor ``L`` (Table 4), and say of the pair only that
it acts "of equal magnitude but in the opposite direction on the connected fan shaft and turbine
shaft" (text before Eq. 34), on nodes 3a and 3b (Eq. 47), which Eq. 31 locks together laterally.
A *reading* is therefore three things: where the pair acts (``[misalignment] excitation``, placed by
:func:`rotor.model.assembly.misalignment_pair`), the transition-shaft mass ``m_sp`` and the lever
``L``, each with the sentence it rests on. :data:`READINGS` names them; :func:`reading_scene` puts one
on a loaded scene (nothing edits a scene file); :func:`run_reading_point` computes one operating
point of it as :func:`rotor.studies.steady_state.run_point` does, so the same figure and table code
reads it.

Sleeves: the short sleeve is steel D140/d100 mm, 150 mm long (``m_sp`` = 9 kg, ``L`` = 75 mm, half
its length; the scene's until the point-B comparison). The long sleeve is the same section 420 mm
long (``m_sp`` = 25.2 kg, ``L`` = 210 mm): ``m_sp L²`` is 21.95 times the short sleeve's, the moment
pair at which the opposed reading's 2X shows at point A (2X/1X about 0.1 at the support, issue 25),
and a sleeve that still fits in the 1 400 mm between the 2# bearing and disk 2 (``l34``, Table 4).
The scene's reading is the one that meets the most of the paper's statements at points B and A
(reports/published/section5-readings.md); :func:`scene_reading` names it.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from contact.errors import InputError, OutsideDomainError
from rotor.studies.scene_digest import check_digest, scene_digest

#: the short sleeve: 9 kg over 150 mm, i.e. 60 kg per metre
_SLEEVE_KG_PER_M = 9.0 / 0.150


def sleeve_mass_kg(length_m: float) -> float:
    """Mass (kg) of the scene's sleeve section (steel D140/d100 mm) over an axial length ``length_m`` (m)."""
    return _SLEEVE_KG_PER_M * length_m


@dataclass(frozen=True)
class Reading:
    """One reading of Eq. 34.

    Attributes
    ----------
    name : str
        The reading's name (the study's and the report's key).
    excitation : str
        Where the pair acts, one of :data:`rotor.model.scene.MISALIGNMENT_EXCITATIONS`.
    shaft_mass_kg : float
        Transition-shaft mass ``m_sp`` (kg).
    lever_m : float
        Lever ``L`` (m), from the sleeve centre to the centring surfaces.
    rests_on : str
        The sentence of Dai et al. (2025) the placement rests on, and why ``m_sp`` and ``L``.
    """

    name: str
    excitation: str
    shaft_mass_kg: float
    lever_m: float
    rests_on: str

    @property
    def moment_factor(self) -> float:
        """``m_sp L²`` over the short sleeve's 9 kg × (75 mm)² (–)."""
        return self.shaft_mass_kg * self.lever_m ** 2 / (9.0 * 0.075 ** 2)


_INERTIAL = ("Eq. 34's force 2 m_sp L tan(Δθ/2) Ω² is ½ m_sp e (2Ω)² with e = L tan(Δθ/2), half the "
             "inertia force of the transition shaft, passed to both shafts in the same direction (2F on "
             "the joint, to ground through the bearings); the moment pair stays opposed")
_OPPOSED = ("\"a pair of additional excitations of equal magnitude but in the opposite direction on the "
            "connected fan shaft and turbine shaft\" (text before Eq. 34), placed on nodes 3a and 3b as "
            "Eq. 47 places it: the lateral forces cancel on the locked joint (Eq. 31), the moment pair "
            "±M acts across the angular spring")
_SHORT = "m_sp 9 kg, L 75 mm: steel sleeve D140/d100 mm, 150 mm long, L half its length (assumed; Table 4 gives neither)"
_LONG = ("m_sp 25.2 kg, L 210 mm: the same sleeve 420 mm long, L half its length (\"L denotes the maximum "
         "axial distance between the transition shaft and the centering cylindrical surfaces\", Eq. 34); "
         "m_sp L² ×21.95")

#: every reading compared at points B and A (reports/published/section5-readings.md)
READINGS: tuple[Reading, ...] = (
    Reading("inertial-at-joint", "inertial-at-joint", 9.0, 0.075, f"{_INERTIAL}; {_SHORT}"),
    Reading("opposed-at-joint-long-sleeve", "opposed-at-joint", sleeve_mass_kg(0.42), 0.210, f"{_OPPOSED}; {_LONG}"),
    Reading("opposed-at-joint", "opposed-at-joint", 9.0, 0.075, f"{_OPPOSED}; {_SHORT}"),
    Reading("inertial-at-joint-long-sleeve", "inertial-at-joint", sleeve_mass_kg(0.42), 0.210,
            f"{_INERTIAL}; {_LONG}"),
    Reading("opposed-at-centring-surfaces", "opposed-at-centring-surfaces", 9.0, 0.075,
            "the same sentence, the pair acting where the transition shaft bears on each shaft, the centring "
            f"surfaces L before and L after the joint: the forces leave the couple 2FL; {_SHORT}"),
)
READING_NAMES = tuple(r.name for r in READINGS)

#: the no-excitation control compared beside the readings (reports/protocols/section5-readings.toml): the
#: scene's placement with m_sp = 0, so Eq. 34's F and M are zero while the joint's geometric misalignment offset
#: and everything else stay; what a model without the excitation of Eq. 34 already meets
CONTROL = Reading("no-excitation", "opposed-at-joint", 0.0, 0.0,
                  "control: no Eq. 34 excitation (m_sp = 0, so F = M = 0); the misalignment offset of the joint kept")
#: the readings and the control, as ``study readings`` runs them
COMPARED = READINGS + (CONTROL,)
COMPARED_NAMES = tuple(r.name for r in COMPARED)


def reading(name: str) -> Reading:
    """The reading called ``name`` (one of :data:`COMPARED_NAMES`: a reading or the control)."""
    for r in COMPARED:
        if r.name == name:
            return r
    raise InputError(f"reading = {name!r}: unknown; allowed: {', '.join(COMPARED_NAMES)}")


def reading_scene(scene, name: str):
    """``scene`` with the misalignment excitation, ``m_sp`` and ``L`` of reading ``name``."""
    r = reading(name)
    mis = scene.misalignment
    if mis is None:
        raise InputError(f"reading {name!r}: scene {scene.name!r} has no [misalignment] table")
    couplings = tuple(dataclasses.replace(c, shaft_mass_kg=r.shaft_mass_kg, lever_m=r.lever_m)
                      if c.name == mis.coupling else c for c in scene.couplings)
    return dataclasses.replace(scene, couplings=couplings,
                               misalignment=dataclasses.replace(mis, excitation=r.excitation))


_MODELS: dict = {}


def reading_model(scene_name: str, name: str, elements_per_segment: int | None = None):
    """``(scene, model)`` of a reading on a mesh, cached per process."""
    key = (scene_name, name, elements_per_segment)
    if key not in _MODELS:
        from rotor.model.assembly import assemble
        from rotor.model.scene import load_scene

        sc = reading_scene(load_scene(scene_name), name)
        _MODELS[key] = (sc, assemble(sc, elements_per_segment=elements_per_segment))
    return _MODELS[key]


def run_reading_point(scene: str, reading_name: str, speed_rpm: float, elements_per_segment: int | None = None,
                      options: dict | None = None, history_revs: int = 8, scene_sha256: str | None = None):
    """Steady state of one reading at one speed, as ``(arrays, info)`` of
    :func:`rotor.studies.steady_state.point_record` plus ``info["reading"]`` (a :class:`sweep.Task` function;
    ``scene_sha256`` as in :func:`rotor.studies.scene_digest.check_digest`)."""
    from contact.units import check_positive
    from rotor.dynamics.build import system_from_model
    from rotor.studies.steady_state import SteadyStateOptions, point_record, steady_state

    check_positive("speed_rpm", speed_rpm, "rpm", upper=1e5)
    sc, model = reading_model(scene, reading_name, elements_per_segment)
    check_digest(scene_sha256, sc, elements_per_segment, what=f"reading {reading_name} at {speed_rpm:g} rpm")
    opts = SteadyStateOptions(**(options or {}))
    system = system_from_model(model, sc, float(speed_rpm) * math.pi / 30.0)
    r = reading(reading_name)
    tag = {"reading": {"name": r.name, "excitation": r.excitation, "shaft_mass_kg": r.shaft_mass_kg,
                       "lever_m": r.lever_m}}
    try:
        res = steady_state(system, model, options=opts)
    except OutsideDomainError as exc:
        # a measured outcome of the reading, not a failure of the run: its load drives the ring past the
        # contact law's neat-fit limit at this speed (the report says so where it uses the point)
        return {"channels": np.array([], dtype=str)}, {"speed_rpm": float(speed_rpm), "outside_law_domain": str(exc),
                                                        "converged": False, **tag}
    arrays, info = point_record(res, sc, model, system, opts, speed_rpm=speed_rpm, misalignment_m=None,
                                tilt_ignored=False, history_revs=history_revs,
                                elements_per_segment=elements_per_segment)
    info.update(tag)
    return arrays, info


def reading_tasks(scene: str, names, speeds_rpm, meshes=(None, 2), *, options: dict | None = None,
                  history_revs: int = 8, prefix: str = "") -> list:
    """One :class:`sweep.Task` per (reading, mesh, speed); keys ``<prefix><reading>-e<mesh>-rpm<speed>``
    (mesh ``paper`` for the scene's own mesh); params carry the resolved scene's digest
    (rotor/studies/scene_digest.py), so a point stored before the scene changed is stale, not reused."""
    from sweep import Task

    out = []
    for name in names:
        reading(name)
        for m in meshes:
            for s in speeds_rpm:
                tag = "paper" if m is None else str(int(m))
                params = {"scene": scene, "reading_name": name, "speed_rpm": float(s),
                          "options": dict(options or {}), "history_revs": int(history_revs),
                          "scene_sha256": scene_digest(reading_model(scene, name, m)[0], m)}
                if m is not None:
                    params["elements_per_segment"] = int(m)
                out.append(Task(f"{prefix}{name}-e{tag}-rpm{float(s):.0f}", run_reading_point, params))
    return out


def scene_reading(scene) -> str | None:
    """Name of the reading ``scene`` carries (its excitation, ``m_sp`` and ``L``), None if it is none of :data:`READINGS`."""
    mis = scene.misalignment
    if mis is None:
        return None
    cp = next(c for c in scene.couplings if c.name == mis.coupling)
    for r in READINGS:
        if (r.excitation == mis.excitation and math.isclose(r.shaft_mass_kg, cp.shaft_mass_kg, rel_tol=1e-9)
                and math.isclose(r.lever_m, cp.lever_m, rel_tol=1e-9)):
            return r.name
    return None
