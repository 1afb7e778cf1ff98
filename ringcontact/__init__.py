"""ringcontact: a bearing outer ring against its support through a radial clearance, from Python.

The public face of the suite (the top layer: it may use every package below it, none uses it). Load or build a
rotor scene, run each analysis, and get result objects with named fields in SI units (the unit in the name)::

    import ringcontact as rc

    scene = rc.load_scene("verify-jeffcott")          # a bundled scene, or a .toml path, or built in Python
    m = rc.modes(scene, speed_rpm=0)                   # m.frequency_rad_s, m.whirl ...
    m.plot(); m.save("modes.json"); m.to_csv("modes.csv"); m.to_xarray()

Analyses: :func:`modes`, :func:`campbell`, :func:`unbalance_response` (linear, the loose support locked);
:func:`simulate`, :func:`orbit`, :func:`branch`, :func:`cascade` (the loose support in play: every result has
the contact-force summary ``peak_contact_force_N``, ``contact_share``, ``stick_share_right_face`` …);
:func:`law` (a contact law's force and moment), :func:`bearing` (a ring-pair file to a calibrated law).
Scenes: :class:`Scene` with :meth:`Scene.to_toml`, :meth:`Scene.checked`, :meth:`Scene.with_loose_bearing`;
element dataclasses :class:`Material`, :class:`Station`, :class:`Shaft`, :class:`Disk`, :class:`Bearing`,
:class:`SupportNode`, :class:`PointMass`, :class:`Coupling`, :class:`Boundary`, :class:`Misalignment`,
:class:`Analysis`; :func:`disk_from_geometry`, :func:`loose_support`. Errors: :class:`InputError` (a bad
value, one line naming it), :class:`RingContactError` (the base of every error the suite raises).
"""
from __future__ import annotations

from contact.errors import InputError, RingContactError
from contact.stamp import version as _version
from ringcontact.laws import BearingResult, LawResult, bearing, law
from ringcontact.linear import CampbellResult, ModesResult, UnbalanceResult, campbell, modes, unbalance_response
from ringcontact.nonlinear import (BranchResult, CascadeResult, OrbitResult, SimulationResult, branch, cascade, orbit,
                                   simulate)
from ringcontact.results import load_result
from ringcontact.scene import Scene, disk_from_geometry, list_scenes, load_scene, loose_support
from rotor.model.loose_support_scene import LooseSupport
from rotor.model.scene import (Analysis, Bearing, Boundary, Coupling, Disk, Material, Misalignment, PointMass, Shaft,
                               Station, SupportNode)

__version__ = _version()

__all__ = [
    "__version__",
    # scenes
    "Scene", "load_scene", "list_scenes", "Material", "Station", "Shaft", "Disk", "disk_from_geometry", "PointMass",
    "Bearing", "SupportNode", "Coupling", "Boundary", "Misalignment", "Analysis", "LooseSupport", "loose_support",
    # analyses and their results
    "modes", "campbell", "unbalance_response", "simulate", "orbit", "branch", "cascade", "law", "bearing",
    "ModesResult", "CampbellResult", "UnbalanceResult", "SimulationResult", "OrbitResult", "BranchResult",
    "CascadeResult", "LawResult", "BearingResult", "load_result",
    # errors
    "InputError", "RingContactError",
]
