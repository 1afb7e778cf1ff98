"""Sensitivity of the paper's Section 5 findings to the inputs Table 4 does not give.

Dai et al. 2025, Section 5, state three qualitative findings our Table 4 rotor reproduces only in part:
**clearance** (§5.3.1, Fig. 18: at high speed 2X and 3X of the displacement fall as δ0 grows, 0.03 → 0.05 →
0.08 mm), **misalignment** (§5.3.2, Fig. 19: as δ grows, 0.5 → 1 → 2 mm, 1X stays while 2X and 3X rise) and
**tilt** (§5.2, Fig. 16 vs 12: ignoring the support's tilt "markedly" reduces 3X–5X of the y velocity).

This module builds scene *variants* — the loaded scene with named inputs replaced
(:func:`apply_overrides`, :func:`dataclasses.replace`, re-assembled by :func:`rotor.model.assembly.assemble`)
— computes, for one variant at one speed, the steady state of the reference case (δ0 = 0.05 mm,
δ = 1 mm, tilt on) and of the five neighbouring cases continued from it (:func:`run_variant_point`,
a picklable :class:`sweep.Task` function), and evaluates the three findings on the
resulting amplitude tables (:func:`clearance_finding`, :func:`misalignment_finding`,
:func:`tilt_finding`). Nothing here edits a scene file.

Continuation: each neighbouring case starts from the end state of the reference case at the same
speed (as ``tests/rotor/studies/test_study_paper.py`` does), so a comparison is between neighbouring states of
one branch of solutions, not between coexisting attractors reached from rest.

Everything is SI inside; override names carry their SI unit (``support_inertia_kg_m2``).
"""
from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field

import numpy as np

from contact.errors import InputError
from contact.units import check_positive
from rotor.studies.scene_digest import check_digest, scene_digest

# ---------------------------------------------------------------------------------------------
# overrides of the unstated inputs
# ---------------------------------------------------------------------------------------------

#: override name -> (where, attribute, unit, allow_zero, upper bound in SI (wrong-unit guard))
#: where: 'support' = the loose support node, 'coupling' = the misaligned transition shaft,
#: 'loose' = the [loose_support] table.
PARAMETERS = {
    "support_stiffness_n_m": ("support", "stiffness_n_m", "N/m", True, 1e12),
    "support_damping_n_s_m": ("support", "damping_n_s_m", "N s/m", True, 1e9),
    "support_angular_stiffness_n_m_rad": ("support", "angular_stiffness_n_m_rad", "N m/rad", True, 1e12),
    "support_angular_damping_n_m_s_rad": ("support", "angular_damping_n_m_s_rad", "N m s/rad", True, 1e9),
    "support_inertia_kg_m2": ("support", "inertia_kg_m2", "kg m^2", False, 1e4),
    "coupling_a0_n_m_rad": ("coupling", "a0_n_m_rad", "N m/rad", True, 1e12),
    "coupling_a1_n_m_rad3": ("coupling", "a1_n_m_rad3", "N m/rad^3", True, 1e18),
    "coupling_shaft_mass_kg": ("coupling", "shaft_mass_kg", "kg", True, 1e4),
    "coupling_lever_m": ("coupling", "lever_m", "m", True, 10.0),
    "collision_factor_s_m": ("loose", "collision_factor_s_m", "s/m", True, 1e6),
    "friction_coefficient": ("loose", "friction_coefficient", "-", True, 2.0),
    "preload_n": ("loose", "preload_n", "N", True, 1e7),
}

#: groups varied together by one factor (:func:`scaled_overrides`), with the reason.
GROUPS = {
    # k_s,θ = k_s b², c_s,θ = c_s b² in the scene: a factor on b² scales both
    "ks_theta": ("support_angular_stiffness_n_m_rad", "support_angular_damping_n_m_s_rad"),
    "js": ("support_inertia_kg_m2",),
    # the support-to-ground spring and damper read as k3, c3: one frame, scaled together
    "ks": ("support_stiffness_n_m", "support_damping_n_s_m"),
    "a0": ("coupling_a0_n_m_rad",),
    "a1": ("coupling_a1_n_m_rad3",),
    # m_sp alone: the 2X force is 2 m_sp L tan(Δθ/2) Ω², linear in m_sp (Eq. 34)
    "msp": ("coupling_shaft_mass_kg",),
    # L alone: the 2X force grows as L, the 2X moment pair as L² (Eq. 34)
    "lever": ("coupling_lever_m",),
    "cc": ("collision_factor_s_m",),
    "preload": ("preload_n",),
    "mu": ("friction_coefficient",),
}


def _target(scene, where: str):
    if where == "support":
        if scene.loose_support is None:
            raise InputError(f"scene {scene.name!r}: no [loose_support]; support overrides need one")
        for s in scene.supports:
            if s.name == scene.loose_support.support:
                return s
        raise InputError(f"scene {scene.name!r}: loose support node {scene.loose_support.support!r} not found")
    if where == "coupling":
        want = scene.misalignment.coupling if scene.misalignment is not None else None
        cps = [c for c in scene.couplings if want is None or c.name == want]
        if len(cps) != 1:
            raise InputError(f"scene {scene.name!r}: coupling overrides need exactly one (misaligned) coupling, "
                             f"found {len(cps)}")
        return cps[0]
    if scene.loose_support is None:
        raise InputError(f"scene {scene.name!r}: no [loose_support] to override")
    return scene.loose_support


def check_overrides(overrides: dict) -> dict:
    """Validate named overrides (SI values) and return them as plain floats.

    Raises
    ------
    InputError
        Unknown name (the message lists the known ones), a value that is not a finite number,
        negative (or zero where zero is meaningless: ``support_inertia_kg_m2``), or above the
        wrong-unit guard; the message names the parameter, its value and unit.
    """
    if not isinstance(overrides, dict):
        raise InputError(f"overrides: expected a mapping name -> value, got {type(overrides).__name__}")
    out = {}
    for name, value in overrides.items():
        if name not in PARAMETERS:
            raise InputError(f"override {name!r}: unknown parameter; known: {', '.join(sorted(PARAMETERS))}")
        _, _, unit, allow_zero, upper = PARAMETERS[name]
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
            raise InputError(f"{name} = {value!r} {unit}: must be a number")
        check_positive(name, float(value), unit, allow_zero=allow_zero, upper=upper)
        out[name] = float(value)
    return out


def apply_overrides(scene, overrides: dict):
    """The scene with named inputs replaced (a new frozen Scene; ``scene`` is unchanged).

    Parameters
    ----------
    scene : rotor.model.scene.Scene
    overrides : dict name -> SI value, names from :data:`PARAMETERS`.
    """
    ov = check_overrides(overrides)
    by_where: dict = {}
    for name, value in ov.items():
        where, attr, *_ = PARAMETERS[name]
        by_where.setdefault(where, {})[attr] = value
    new = scene
    for where, changes in by_where.items():
        old = _target(new, where)
        rep = dataclasses.replace(old, **changes)
        if where == "support":
            new = dataclasses.replace(new, supports=tuple(rep if s is old else s for s in new.supports))
        elif where == "coupling":
            new = dataclasses.replace(new, couplings=tuple(rep if c is old else c for c in new.couplings))
        else:
            new = dataclasses.replace(new, loose_support=rep)
    return new


def base_values(scene) -> dict:
    """Current SI value of every overridable parameter of ``scene``."""
    out = {}
    for name, (where, attr, *_) in PARAMETERS.items():
        out[name] = float(getattr(_target(scene, where), attr))
    return out


def scaled_overrides(scene, factors: dict) -> dict:
    """Absolute overrides from factors on groups (:data:`GROUPS`) or single parameters.

    ``{"ks_theta": 0.01}`` → k_s,θ and c_s,θ at 1 % of the scene's values.
    """
    base = base_values(scene)
    out = {}
    for key, f in factors.items():
        names = GROUPS.get(key, (key,) if key in PARAMETERS else None)
        if names is None:
            raise InputError(f"factor {key!r}: unknown group or parameter; groups: {', '.join(GROUPS)}; "
                             f"parameters: {', '.join(sorted(PARAMETERS))}")
        check_positive(f"factor on {key}", f, "-", allow_zero=True, upper=1e6)
        for n in names:
            out[n] = base[n] * float(f)
    return check_overrides(out)


@dataclass(frozen=True)
class Variant:
    """A named set of factors on the unstated inputs (empty: the scene as it is), under a reading of
    Eq. 34 (``reading``: a name of :data:`rotor.studies.readings.READINGS`; None: the scene's)."""

    name: str
    factors: dict = field(default_factory=dict)
    why: str = ""
    reading: str | None = None


_MODELS: dict = {}


def _reading_scene(scene_name: str, reading: str | None):
    from rotor.model.scene import load_scene
    from rotor.studies.readings import reading_scene

    sc = load_scene(scene_name)
    return sc if reading is None else reading_scene(sc, reading)


def variant_model(scene_name: str, overrides: dict, reading: str | None = None):
    """``(scene, model)`` of a variant (under ``reading``, None: the scene's), cached per process."""
    key = (scene_name, json.dumps(check_overrides(overrides), sort_keys=True), reading)
    if key not in _MODELS:
        from rotor.model.assembly import assemble

        sc = apply_overrides(_reading_scene(scene_name, reading), overrides)
        _MODELS[key] = (sc, assemble(sc))
    return _MODELS[key]


# ---------------------------------------------------------------------------------------------
# one (variant, speed): reference case + five continued neighbours
# ---------------------------------------------------------------------------------------------

#: the paper's parameter values (Figs. 18, 19, 16): case -> system overrides
REFERENCE = {"clearance_m": 0.05e-3, "misalignment_m": 1.0e-3}
CASES = {
    "base": {},
    "clear0.03": {"clearance_m": 0.03e-3},
    "clear0.08": {"clearance_m": 0.08e-3},
    "mis0.5": {"misalignment_m": 0.5e-3},
    "mis2": {"misalignment_m": 2.0e-3},
    "notilt": {"tilt_ignored": True},
}
CASE_NAMES = tuple(CASES)
LOCATIONS = ("disk1.y", "disk2.y", "s.y")
ORDERS = (1, 2, 3, 4, 5)


def run_variant_point(scene: str, speed_rpm: float, overrides: dict | None = None, options: dict | None = None,
                      cases: list | None = None, reading: str | None = None, scene_sha256: str | None = None):
    """Steady states of every case at one speed for one variant, as ``(arrays, info)``.

    ``scene_sha256``: the digest of the variant's resolved scene its task was made from
    (:func:`rotor.studies.scene_digest.scene_digest`); refused if the scene now digests otherwise.

    The reference case ('base': δ0 = 0.05 mm, δ = 1 mm, tilt on) starts from the misalignment
    offset at rest; every other case starts from its end state (continuation).

    Arrays (SI): ``harm_q`` (C, 5, L) displacement amplitudes of 1X–5X (m) at :data:`LOCATIONS`,
    ``harm_v`` (C, 5, L) y-velocity (m/s), ``harm_u`` (C, 5, 4) relative bearing − support motion
    (m, rad), ``periodic`` (C,) bool, ``contact_fraction`` (C,). Info: per case convergence,
    period, regime, transient revolutions and wall time.
    """
    from rotor.dynamics.build import system_from_model
    from rotor.studies.steady_state import SteadyStateOptions, steady_state

    check_positive("speed_rpm", speed_rpm, "rpm", upper=1e5)
    names = list(cases) if cases is not None else list(CASE_NAMES)
    if not names or names[0] != "base" or any(c not in CASES for c in names):
        raise InputError(f"cases = {names}: must start with 'base' and be among {', '.join(CASE_NAMES)}")
    sc, model = variant_model(scene, overrides or {}, reading)
    check_digest(scene_sha256, sc, what=f"sensitivity point at {speed_rpm:g} rpm")
    opts = SteadyStateOptions(**(options or {}))
    omega = float(speed_rpm) * math.pi / 30.0
    C = len(names)
    hq = np.zeros((C, len(ORDERS), len(LOCATIONS)))
    hv = np.zeros_like(hq)
    hu = np.zeros((C, len(ORDERS), 4))
    periodic = np.zeros(C, bool)
    cfrac = np.zeros(C)
    from rotor.dynamics.system import NewmarkOptions

    info = {"speed_rpm": float(speed_rpm), "overrides": check_overrides(overrides or {}), "cases": names,
            "integrator": dataclasses.asdict(NewmarkOptions()),
            **({"reading": reading} if reading else {})}
    base = None
    for i, name in enumerate(names):
        kw = {**REFERENCE, **CASES[name]}
        system = system_from_model(model, sc, omega, **kw)
        start = {} if base is None else {"q0": base.q_end, "v0": base.v_end}
        res = steady_state(system, model, options=opts, **start)
        if base is None:
            base = res
        cols = [res.channel(c) for c in LOCATIONS]
        hq[i] = res.harmonics("q", ORDERS)[:, cols]
        hv[i] = res.harmonics("v", ORDERS)[:, cols]
        hu[i] = res.harmonics("u", ORDERS)
        periodic[i] = bool(res.convergence.converged)
        reg = res.regime()
        cfrac[i] = reg["contact_fraction"]
        info[name] = {"converged": bool(res.convergence.converged), "period_revs": int(res.convergence.period),
                      "poincare_change": float(res.convergence.change), "transient_revs": int(res.transient_revs),
                      "wall_s": round(float(res.wall_s), 3), "least_residual_steps": int(res.unconverged_steps),
                      **reg}
    arrays = {"harm_q": hq, "harm_v": hv, "harm_u": hu, "periodic": periodic, "contact_fraction": cfrac,
              "cases": np.array(names), "locations": np.array(LOCATIONS)}
    return arrays, info


def variant_tasks(scene: str, variant: Variant, speeds_rpm, *, options: dict | None = None) -> list:
    """One :class:`sweep.Task` of :func:`run_variant_point` per speed for ``variant``.

    Keys ``<variant>-rpm<speed>``; params hold the absolute overrides (resolved from the factors
    against the scene) and the digest of the resolved scene (``scene_sha256``), so a stored point says exactly
    what it was computed with, and one computed before the scene file changed is stale, not reused."""
    from sweep import Task

    ov = scaled_overrides(_reading_scene(scene, variant.reading), variant.factors) if variant.factors else {}
    extra = {"reading": variant.reading} if variant.reading else {}
    extra["scene_sha256"] = scene_digest(variant_model(scene, ov, variant.reading)[0])
    return [Task(f"{variant.name}-rpm{float(s):.0f}", run_variant_point,
                 {"scene": scene, "speed_rpm": float(s), "overrides": ov, "options": dict(options or {}), **extra})
            for s in speeds_rpm]


# ---------------------------------------------------------------------------------------------
# amplitude tables and the three findings
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class AmplitudeTable:
    """Harmonic amplitudes of one variant over speed, every case.

    speeds_rpm : (S,) ; cases : case names (C) ; locations : (L) channel names
    q : (C, S, 5, L) displacement amplitudes of 1X–5X (m) ; v : same for the y velocity (m/s)
    periodic : (C, S) bool, the steady state was found periodic
    contact_fraction : (C, S) fraction of the record with contact (–)
    """

    speeds_rpm: np.ndarray
    cases: tuple
    locations: tuple
    q: np.ndarray
    v: np.ndarray
    periodic: np.ndarray
    contact_fraction: np.ndarray | None = None

    def __post_init__(self):
        C, S, L = len(self.cases), len(self.speeds_rpm), len(self.locations)
        for nm in ("q", "v"):
            a = np.asarray(getattr(self, nm))
            if a.ndim != 4 or a.shape[0] != C or a.shape[1] != S or a.shape[3] != L or a.shape[2] < 3:
                raise InputError(f"AmplitudeTable.{nm}: shape {a.shape}, expected ({C}, {S}, >=3, {L})")
            if not np.all(np.isfinite(a)) or np.any(a < 0):
                raise InputError(f"AmplitudeTable.{nm}: amplitudes must be finite and >= 0")
        if np.shape(self.periodic) != (C, S):
            raise InputError(f"AmplitudeTable.periodic: shape {np.shape(self.periodic)}, expected ({C}, {S})")

    def amp(self, quantity: str, case: str) -> np.ndarray:
        """(S, orders, L) amplitudes of one case; quantity 'q' (m) or 'v' (m/s)."""
        if quantity not in ("q", "v"):
            raise InputError(f"quantity = {quantity!r}: use 'q' (displacement) or 'v' (velocity)")
        if case not in self.cases:
            raise InputError(f"case {case!r}: not in the table ({', '.join(self.cases)})")
        return np.asarray(getattr(self, quantity))[self.cases.index(case)]

    def ok(self, case: str) -> np.ndarray:
        return np.asarray(self.periodic)[self.cases.index(case)].astype(bool)


def table_from_points(points) -> AmplitudeTable:
    """Amplitude table of one variant from stored sweep points (:class:`sweep.PointResult`)."""
    pts = sorted(points, key=lambda p: p.params["speed_rpm"])
    if not pts:
        raise InputError("table_from_points: no points")
    cases = tuple(str(c) for c in pts[0].arrays["cases"])
    locs = tuple(str(c) for c in pts[0].arrays["locations"])
    q = np.stack([p.arrays["harm_q"] for p in pts], axis=1)
    v = np.stack([p.arrays["harm_v"] for p in pts], axis=1)
    per = np.stack([p.arrays["periodic"] for p in pts], axis=1)
    cf = np.stack([p.arrays["contact_fraction"] for p in pts], axis=1)
    return AmplitudeTable(np.array([p.params["speed_rpm"] for p in pts]), cases, locs, q, v, per, cf)


#: a finding holds for a variant when it holds at ≥ this fraction of the compared speeds
HOLD_FRACTION = 2.0 / 3.0
#: 'markedly lower' harmonics without tilt: at most this fraction of the tilted ones (30 % lower)
MARKEDLY = 0.7
#: '1X remains essentially unchanged' across δ: largest/smallest − 1 at most this
ONE_F_SPREAD = 0.05


@dataclass(frozen=True)
class Finding:
    """Outcome of one finding on one variant.

    holds : bool — at ≥ :data:`HOLD_FRACTION` of the compared speeds, and at least two compared;
    n_pass, n_compared : speeds where the statement holds / could be checked;
    per_speed : list of dicts (speed_rpm, holds, and the numbers compared, SI).
    """

    name: str
    quantity: str
    holds: bool
    n_pass: int
    n_compared: int
    per_speed: tuple

    def summary(self) -> str:
        return f"{'holds' if self.holds else 'does not hold'} ({self.n_pass}/{self.n_compared} speeds)"


def _verdict(name, quantity, rows) -> Finding:
    n = len(rows)
    k = sum(1 for r in rows if r["holds"])
    return Finding(name, quantity, bool(n >= 2 and k >= HOLD_FRACTION * n - 1e-12), k, n, tuple(rows))


def _mask(table, cases, require_periodic, require_contact=False):
    m = np.ones(len(table.speeds_rpm), bool)
    if require_periodic:
        for c in cases:
            m &= table.ok(c)
    if require_contact:
        if table.contact_fraction is None:
            raise InputError("require_contact: the table has no contact fractions")
        m &= np.asarray(table.contact_fraction)[table.cases.index("base")] > 0
    return m


def clearance_finding(table: AmplitudeTable, quantity: str = "q", *, require_periodic: bool = True,
                      require_contact: bool = False, locations=("disk2.y", "s.y"), orders=(2, 3)) -> Finding:
    """Dai 2025 §5.3.1: at high speed 2X and 3X decrease as δ0 grows (0.03 → 0.05 → 0.08 mm).

    Per speed: strictly ``A(0.03) > A(0.05) > A(0.08)`` for every order in ``orders`` at every
    location in ``locations`` (disk 2 and the support, where the paper's harmonics are)."""
    cases = ("clear0.03", "base", "clear0.08")
    A = [table.amp(quantity, c) for c in cases]
    m = _mask(table, cases, require_periodic, require_contact)
    rows = []
    for s in np.flatnonzero(m):
        nums, good = {}, True
        for loc in locations:
            j = table.locations.index(loc)
            for h in orders:
                a = [float(x[s, h - 1, j]) for x in A]
                nums[f"{h}X {loc}"] = a
                good &= a[0] > a[1] > a[2]
        rows.append({"speed_rpm": float(table.speeds_rpm[s]), "holds": bool(good), "amps": nums})
    return _verdict("clearance", quantity, rows)


def misalignment_finding(table: AmplitudeTable, quantity: str = "q", *, require_periodic: bool = True,
                         require_contact: bool = False, locations=LOCATIONS, spread: float = ONE_F_SPREAD) -> Finding:
    """Dai 2025 §5.3.2: as δ grows (0.5 → 1 → 2 mm) 1X stays essentially unchanged (spread
    ≤ ``spread``) while 2X and 3X increase (strictly), at every location."""
    cases = ("mis0.5", "base", "mis2")
    A = [table.amp(quantity, c) for c in cases]
    m = _mask(table, cases, require_periodic, require_contact)
    rows = []
    for s in np.flatnonzero(m):
        nums, good = {}, True
        parts = {"1X flat": True, "2X up": True, "3X up": True}
        for loc in locations:
            j = table.locations.index(loc)
            one = [float(x[s, 0, j]) for x in A]
            sp = max(one) / min(one) - 1 if min(one) > 0 else math.inf
            parts["1X flat"] &= sp <= spread
            nums[f"1X spread {loc}"] = sp
            for h in (2, 3):
                a = [float(x[s, h - 1, j]) for x in A]
                nums[f"{h}X {loc}"] = a
                parts[f"{h}X up"] &= a[0] < a[1] < a[2]
        good = all(parts.values())
        rows.append({"speed_rpm": float(table.speeds_rpm[s]), "holds": bool(good), "parts": parts, "amps": nums})
    return _verdict("misalignment", quantity, rows)


def tilt_finding(table: AmplitudeTable, quantity: str = "v", *, require_periodic: bool = True,
                 require_contact: bool = False, locations=("disk2.y", "s.y"), markedly: float = MARKEDLY) -> Finding:
    """Dai 2025 §5.2: ignoring the tilt markedly lowers the harmonics: Σ 3X–5X without tilt
    ≤ ``markedly`` × with tilt at every location in ``locations`` (y velocity by default, as the
    paper's Figs. 12/16)."""
    cases = ("base", "notilt")
    A = [table.amp(quantity, c) for c in cases]
    if A[0].shape[1] < 5:
        raise InputError("tilt_finding: needs orders 1..5")
    m = _mask(table, cases, require_periodic, require_contact)
    rows = []
    for s in np.flatnonzero(m):
        nums, good = {}, True
        for loc in locations:
            j = table.locations.index(loc)
            on, off = float(A[0][s, 2:5, j].sum()), float(A[1][s, 2:5, j].sum())
            nums[f"3X–5X {loc}"] = [on, off]
            good &= off <= markedly * on
        rows.append({"speed_rpm": float(table.speeds_rpm[s]), "holds": bool(good), "amps": nums})
    return _verdict("tilt", quantity, rows)


def evaluate(table: AmplitudeTable, *, require_periodic: bool = True, require_contact: bool = False) -> dict:
    """All findings of one variant: ``{name: Finding}``; clearance and misalignment in displacement
    (the paper's Figs. 18–19) and velocity, tilt in velocity (Figs. 12/16) and displacement.
    ``require_contact``: only speeds where the reference case collides (the paper attributes all
    three findings to the collision between bearing and support)."""
    out = {}
    kw = {"require_periodic": require_periodic, "require_contact": require_contact}
    for q in ("q", "v"):
        out[f"clearance_{q}"] = clearance_finding(table, q, **kw)
        out[f"misalignment_{q}"] = misalignment_finding(table, q, **kw)
        out[f"tilt_{q}"] = tilt_finding(table, q, **kw)
    return out


# ---------------------------------------------------------------------------------------------
# the study: speeds and one-at-a-time variants (ranges argued in reports/published/study-sensitivity.md)
# ---------------------------------------------------------------------------------------------

#: the first third of the paper's 'high speed' range of §5.3.1 (band H1 of rotor.studies.section5), in
#: 1 500 rpm steps; 10 500 rpm is its point B. Above 12 000 rpm the scene's reading has no periodic steady
#: state within 1 500 revolutions on either mesh (study-findings.md: from 12 900 rpm on the paper's mesh), so
#: 13 500 and 15 000 rpm decide nothing on periodic states and cost ~70 s per (variant, speed) against ~18 s
#: (every case runs the full 1 500 revolutions); the former study's five speeds are kept as :data:`FORMER_SPEEDS_RPM`.
SPEEDS_RPM = (9000.0, 10500.0, 12000.0)
FORMER_SPEEDS_RPM = (9000.0, 10500.0, 12000.0, 13500.0, 15000.0)

#: steady-state options of the study (as tests/rotor/studies/test_study_paper.py: 16-revolution spectrum records)
STUDY_OPTIONS = {"spectrum_revs": 16}


def one_at_a_time() -> list:
    """The reference scene and one-at-a-time factors on each unstated input (see :data:`GROUPS`)."""
    v = [Variant("base", {}, "scene as published (paper-table4.toml)")]
    for f in (0.01, 0.1, 10.0, 100.0):
        v.append(Variant(f"ks_theta-x{f:g}", {"ks_theta": f},
                         "support tilt stiffness/damping k_s,θ, c_s,θ (b² from 10 mm to 1 m)"))
    for f in (0.1, 3.0):
        v.append(Variant(f"js-x{f:g}", {"js": f}, "support tilt inertia J_s (radius of gyration 44–240 mm for 100 kg)"))
    for f in (0.01, 0.1, 10.0, 100.0):
        v.append(Variant(f"a0-x{f:g}", {"a0": f}, "transition-shaft angular stiffness a0 (5e4 … 5e8 N m/rad)"))
    for f in (0.0, 10.0, 100.0):
        v.append(Variant(f"a1-x{f:g}", {"a1": f}, "transition-shaft cubic stiffness a1 (0 = linear joint)"))
    for f in (0.1, 10.0):
        v.append(Variant(f"ks-x{f:g}", {"ks": f}, "support-to-ground k_s, c_s (1.5e6 … 1.5e8 N/m)"))
    for f in (0.1, 0.3, 3.0):
        v.append(Variant(f"msp-x{f:g}", {"msp": f}, "transition-shaft mass m_sp (2X force ∝ m_sp L)"))
    for f in (0.33, 2.0):
        v.append(Variant(f"lever-x{f:g}", {"lever": f}, "transition-shaft lever L (25 … 150 mm; 2X force ∝ L, moment ∝ L²)"))
    for f in (0.01, 0.1, 10.0):
        v.append(Variant(f"cc-x{f:g}", {"cc": f}, "collision factor c_c (0.1 … 1000 s/m)"))
    for f in (0.2, 5.0):
        v.append(Variant(f"muN-x{f:g}", {"preload": f}, "end-face friction limit μN (only the product enters)"))
    return v


def study_tasks(variants, *, scene: str = "paper-table4", speeds_rpm=SPEEDS_RPM, options=None) -> list:
    """All :class:`sweep.Task` of a list of variants (variant-major order: the first
    variants finish first, so an interrupted study has whole variants on disk)."""
    names = [v.name for v in variants]
    if len(set(names)) != len(names):
        raise InputError(f"variants: duplicate names {sorted({n for n in names if names.count(n) > 1})}")
    out = []
    for v in variants:
        out += variant_tasks(scene, v, speeds_rpm, options=STUDY_OPTIONS if options is None else options)
    return out


def combinations() -> list:
    """Combinations the former study (reading ``inertial-at-joint``) tried after its one-at-a-time results:
    ``ks-x10``, ``muN-x0.2`` and ``ks_theta-x0.01`` kept the bearing colliding over 9 000–15 000 rpm."""
    why = "combination suggested by the one-at-a-time results"
    return [Variant("ks-x3", {"ks": 3.0}, "support-to-ground k_s, c_s ×3 (between ks-x1 and ks-x10)"),
            Variant("ks-x3+muN-x0.2", {"ks": 3.0, "preload": 0.2}, why),
            Variant("ks-x10+muN-x0.2", {"ks": 10.0, "preload": 0.2}, why),
            Variant("ks-x10+ks_theta-x0.01", {"ks": 10.0, "ks_theta": 0.01}, why),
            Variant("ks_theta-x0.01+muN-x0.2", {"ks_theta": 0.01, "preload": 0.2}, why),
            Variant("ks-x10+ks_theta-x0.01+muN-x0.2", {"ks": 10.0, "ks_theta": 0.01, "preload": 0.2}, why)]


def reading_variants(scene: str = "paper-table4") -> list:
    """Every reading of Eq. 34 (rotor.studies.readings), the scene's included, as it is and with m_sp and L
    varied (×0.3, ×3; ×0.5, ×2), so that m_sp and L are varied under every reading, not only the scene's.
    The scene's own reading is named ``base``, ``msp-x…``, ``lever-x…`` (its one-at-a-time rows)."""
    from rotor.model.scene import load_scene
    from rotor.studies.readings import READINGS, scene_reading

    current = scene_reading(load_scene(scene))
    out = []
    for r in sorted(READINGS, key=lambda r: r.name != current):      # the scene's reading first
        why = f"reading {r.name} of Eq. 34 ({r.excitation}, m_sp {r.shaft_mass_kg:g} kg, L {r.lever_m * 1e3:g} mm)"
        own = r.name == current
        out.append(Variant("base" if own else f"reading-{r.name}", {},
                           f"scene as published (paper-table4.toml): {why}" if own else why,
                           reading=None if own else r.name))
        for g, f in (("msp", 0.3), ("msp", 3.0), ("lever", 0.5), ("lever", 2.0)):
            out.append(Variant(f"{g}-x{f:g}" if own else f"reading-{r.name}+{g}-x{f:g}", {g: f},
                               f"{why}; {g} ×{f:g}", reading=None if own else r.name))
    return out


#: the other one-at-a-time inputs under the scene's reading, one factor each side of the scene's value
#: (the study of the former reading had 2–4 factors each; trimmed to keep the study within ~40 CPU-min)
OTHER_FACTORS = {"ks_theta": (0.01, 100.0), "a0": (0.01, 100.0), "a1": (0.0, 100.0), "ks": (0.1, 10.0),
                 "cc": (0.01,), "preload": (0.2, 5.0), "js": (0.1, 3.0)}


def study_variants() -> list:
    """The variants of the study: every reading of Eq. 34 with m_sp and L varied (:func:`reading_variants`),
    then the other unstated inputs under the scene's reading (:data:`OTHER_FACTORS`). The former study's
    variants stay available by name (:func:`one_at_a_time`, :func:`combinations`) through ``--variants``."""
    known = {v.name: v for v in one_at_a_time()}
    names = {"ks_theta": "ks_theta", "a0": "a0", "a1": "a1", "ks": "ks", "cc": "cc", "preload": "muN", "js": "js"}
    other = [known[f"{names[g]}-x{f:g}"] for g, fs in OTHER_FACTORS.items() for f in fs]
    return reading_variants() + other


def all_variants() -> list:
    """Every variant a name may select: :func:`study_variants`, then the former study's one-at-a-time and
    combination variants not among them."""
    out = study_variants()
    seen = {v.name for v in out}
    return out + [v for v in one_at_a_time() + combinations() if v.name not in seen]
