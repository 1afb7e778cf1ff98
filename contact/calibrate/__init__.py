"""Calibrated contact laws: fitted to a named FEM scene, stored as data, loaded by name.

The conformal law (Dai et al. 2025 Eq. 5; Persson 1964; Ciavarella & Decuzzi 2001) is exact
for a pin in an infinite plate. Real rings between a shaft and a housing are stiffer or softer:
the reference FEM (``fem_reference``, scenes ``clamped``, ``clamped-stress``, ``persson-*``)
measures how much, per boundary-condition scene. This module fits, per scene, the law with the
**fewest parameters the data justify**, each parameter with a physical meaning:

``conformal-scaled`` (1 parameter)
    ``P = s · P_conformal(Δr)``: a stiffness (modulus) factor ``s`` on the conformal law with
    the scene's own composite modulus (plane strain or plane stress).
``foundation`` (1 parameter)
    Winkler elastic foundation (Johnson 1985, *Contact Mechanics*, §4.3 "elastic foundation
    model"): the two rings act as a bed of independent springs of modulus ``k_f`` (Pa/m)
    between a rigid shaft and a rigid housing. The overlap of the rigid circles at polar angle
    φ is ``e cos φ − δ0`` (``e = δ0 + Δr``), so the pressure is ``k_f (e cos φ − δ0)`` on
    ``|φ| < ε``, ``cos ε = δ0/e``, and the resultant is
    ``P = k_f R l e (ε − sin ε cos ε)``, ``R`` the contact radius, ``l`` the width. For thin
    rings clamped on their far faces ``k_f`` should be the constrained (oedometric) modulus
    over the total ring thickness, ``M/(h_b + h_s)``; the fit is compared with that.
``conformal-compliance`` (1 parameter)
    The conformal law's force–angle relation (exact for a pin in an infinite plate) with the
    penetration of a finite body: the rigid overlap ``δ0(sec ε − 1)`` plus the elastic approach
    of the contact in series, ``P/(π E* l) · (2 ln(1/sin ε) + C)``. The ``2 ln`` term is the
    logarithm of 2D contact mechanics (the approach of a line contact of half-width ``R sin ε``,
    Johnson 1985 §5.6); the dimensionless ``C`` lumps the far field (support size and how it is
    held). ``P(Δr)`` is the root of a monotone equation in ``b² = tan²(ε/2)`` (bisection), so
    this family is not available in the compiled kernel.
``power`` (2 parameters)
    ``P = C · l · Δr^n``: the form of Pereira et al. (2015) with its constants refitted.
``foundation-spline`` (one parameter per knot, the flexible family)
    The foundation law times a monotone (Fritsch–Carlson) cubic spline correction in log force against log
    penetration through the fitted points, continued beyond the end knots as a power of Δr
    (:mod:`contact.calibrate.spline`). It follows any rising force curve; tried by ``ringcontact bearing``
    (a ring pair nobody tuned a family for), not by the shipped calibrations, whose names scenes cite.

Fitting is linear least squares in log force (every family is ``log P = base(Δr) + Xθ``), so
each fit is exact and the parameter covariance is the classical ``s²(XᵀX)⁻¹`` with ``s²`` the
residual variance: the uncertainty reflects how well the family describes the FEM, not only
the FEM's own (much smaller) discretisation error. Hold-out validation is leave-one-out: each
point is predicted by a fit that never saw it. Selection (:data:`~contact.calibrate.fit.SELECTION_RULE`) is on
issue 37's accuracy target: a family *meets the target* when every held-out error is within 2x its point's stated
FEM error + 0.2 % (:func:`~contact.calibrate.fit.within_accuracy`), and of the families that meet it the fewest
parameters wins (ties: the lower held-out max). If none meets it, the rule falls back to the flag bound: a family
*holds* when no held-out error exceeds its point's stated FEM error by more than 2 % (the bound a law is flagged by,
:func:`~contact.calibrate.fit.family_holds`), and of those the fewest parameters wins; if none holds either, the
lowest held-out max error wins. The law file's ``fit.selection_reason`` says which case applied ("met the target",
"holds only the flag bound", or "no family holds") and what the families with fewer parameters missed.

A calibration is stored as JSON in ``contact/calibrated/<name>.json`` (parameters with their
standard deviations and units, the scene and its geometry, the range of validity, the dataset
file, its checksum and code revision, the fit and hold-out errors, the family comparison) and
loaded with :func:`load_calibrated`. :meth:`CalibratedLaw.loose_support_params` turns it into
:class:`CalibratedSupportParams`, a :class:`~contact.loose_support.LooseSupportParams` that the
rotor solver uses like any other (same compiled kernel; the ``foundation`` family is the
kernel's law code 2, ``foundation-spline`` its code 3, see ``contact._kernel``). Under tilt, a calibrated law is evaluated slice by
slice along the ring width (:meth:`CalibratedLaw.tilted`; the kernel does the same for code 2),
not with the paper's edge-penetration × patch-length rule: for a Winkler bed every axial slice
carries the load of its own penetration. The ``power`` family goes through the kernel's Pereira
branch and keeps the paper's tilt rule.

Example::

    from contact.calibrate import load_calibrated
    from rotor.dynamics.kernels import support_law_from_params
    law = load_calibrated("clamped")                  # -> "clamped-foundation"
    params = law.loose_support_params(c_c_s_per_m=100.0, mu=0.3, preload_N=5000.0)
    support_law = support_law_from_params(params)     # pass as system_from_model(..., law=support_law)

``ringcontact calibrate`` (:mod:`reports.cli.calibrate`) refits every scene of the committed
datasets and writes the files; ``--check`` only compares the stored files with a fresh fit.

Modules: :mod:`~contact.calibrate.families` (the closed forms), :mod:`~contact.calibrate.spline` (the flexible family), :mod:`~contact.calibrate.fit`
(least squares, hold-out, selection, from a dataset to a law), :mod:`~contact.calibrate.law`
(the stored object), :mod:`~contact.calibrate.store` (the files in ``contact/calibrated/``),
:mod:`~contact.calibrate.check` (drift of the stored files against a refit). Every public name
is importable from ``contact.calibrate``.
"""
from __future__ import annotations

from contact.calibrate.check import check_calibrations
from contact.calibrate.families import (ANALYTIC_FAMILIES, FAMILIES, KERNEL_LAW_CODE, LINEAR_FAMILIES, PARAMETERS,
                                        SceneGeometry, conformal_compliance_force, family_force, foundation_shape)
from contact.calibrate.fit import (DATA_3D_DIR, DATASET_2D, SELECTION_RULE, FamilyFit, calibrate_dataset,
                                   calibrate_scene, committed_datasets, dataset_provenance, fit_family, scene_geometry,
                                   scene_points, select_family, within_accuracy)
from contact.calibrate.fit import family_holds, meets_target
from contact.calibrate.law import SCHEMA, VERSION, CalibratedLaw, CalibratedSupportParams
from contact.calibrate.store import CALIBRATED_DIR, available, load_calibrated, write_calibrations
from contact.calibrate.store import LAW_FILE_MAX_BYTES, LawFile, law_file_record, load_law_file, shipped_record
from contact.errors import DatasetError, InputError

__all__ = [
    "ANALYTIC_FAMILIES", "CALIBRATED_DIR", "DATASET_2D", "DATA_3D_DIR", "FAMILIES", "KERNEL_LAW_CODE",
    "LINEAR_FAMILIES", "PARAMETERS",
    "SCHEMA", "SELECTION_RULE", "VERSION", "CalibratedLaw", "CalibratedSupportParams", "DatasetError",
    "FamilyFit", "InputError", "family_holds", "meets_target", "SceneGeometry", "available", "calibrate_dataset",
    "calibrate_scene",
    "check_calibrations", "committed_datasets", "conformal_compliance_force", "dataset_provenance", "family_force",
    "fit_family", "foundation_shape", "load_calibrated", "scene_geometry", "scene_points", "select_family",
    "within_accuracy", "write_calibrations",
    "LAW_FILE_MAX_BYTES", "LawFile", "law_file_record", "load_law_file", "shipped_record",
]
