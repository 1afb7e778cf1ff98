"""A :class:`~rotor.dynamics.system.RotorSystem` from the rotor model of a scene (``rotor.model``)."""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from contact import plausible
from contact.errors import InputError
from contact.units import check_positive
from rotor.dynamics.kernels import support_law_from_params
from rotor.dynamics.system import HarmonicForce, LooseSupport, RotorSystem, SupportLaw


def system_from_model(model, scene, speed_rad_s: float, *, law: SupportLaw | None = None, law_name: str | None = None,
                      tilt_ignored: bool = False,
                      mu: float | None = None, preload_N: float | None = None, clearance_m: float | None = None,
                      misalignment_m: float | None = None, nonlinear_coupling: bool = True) -> RotorSystem:
    """The loose-support rotor of a scene at spin speed ``speed_rad_s`` (rad/s).

    Uses the rotor model API (``rotor.model.assembly``): ``K + K_c`` with the misalignment offset
    ``Δq_m`` (the ``K_c Δq_m`` term moves to the static load, since the coupling spring is
    not shifted), unbalance (1X) and misalignment excitation (2X), the two linear 3a/3b rows
    ``model.B`` (not the squared g5), the cubic coupling remainder, and the loose support with
    the contact law of the scene (its ``[loose_support] law``: an analytic law of
    ``contact.loose_support``, the paper's conformal law as published by default, or a calibrated
    law, :func:`calibrated_support_law`). Overrides: ``law`` (any :class:`SupportLaw`, e.g. a calibrated one
    wrapped by :func:`rotor.dynamics.kernels.support_law_from_params`), ``law_name`` (a law of
    ``contact.loose_support`` by name: "conformal", "pereira"; None: the scene's), ``tilt_ignored`` (paper §5.2,
    Fig. 16: no moment of any kind between bearing and support, neither from the contact law nor
    from the end faces, whose stick lock then has no tilt rows), ``mu``, ``preload_N``, ``clearance_m``, ``misalignment_m`` (δ, scales
    Δq_m and the 2X excitation, which are both linear in δ for small angles; 0 removes both).
    """
    from rotor.model import assembly as rm
    from rotor.model.static_load import static_load
    from rotor.model.topology import require_ground

    ls = scene.loose_support
    n = model.n_dofs
    check_positive("speed_rad_s", speed_rad_s, "rad/s", allow_zero=True,
                   upper=plausible.top("run_speed_rpm") * math.pi / 30)     # the command line's top speed
    if not np.any(model.M):      # every DOF massless: nothing moves in time (a condensed system of 0 DOFs)
        raise InputError(f"scene {scene.name!r}: no mass anywhere (every material density and disk mass is 0), so "
                         "nothing to integrate in time; give the shaft a density_kg_m3 or a disk a mass_kg")
    model = model.at_speed(speed_rad_s)          # bearings with a speed table (rotor.model.scene.Bearing)
    require_ground(model, "time integration")   # a free rotor has no rest position (rotor.model.topology)
    sup = None if ls is None else _loose_support(model, ls, law, law_name, tilt_ignored, mu, preload_N, clearance_m)
    if ls is None:
        given = {"law": law, "mu": mu, "preload_N": preload_N, "clearance_m": clearance_m,
                 "tilt_ignored": tilt_ignored or None}
        for k, v in given.items():
            if v is not None:
                raise InputError(f"{k} = {getattr(v, 'name', v)!r}: scene {scene.name!r} has no [loose_support] to apply it to")
    off = rm.misalignment_offset(model)
    loads = rm.harmonic_loads(model, speed_rad_s)
    delta0 = scene.misalignment.offset_m if getattr(scene, "misalignment", None) is not None else 0.0
    scale = 1.0
    if misalignment_m is not None:
        check_positive("misalignment_m", misalignment_m, "m", allow_zero=True, upper=0.05)
        if delta0 == 0.0 and misalignment_m > 0:
            raise InputError("misalignment_m: the scene has no misalignment to scale; set it in the scene")
        scale = misalignment_m / delta0 if delta0 else 0.0
    off = off * scale
    orders = np.array(sorted(loads), dtype=float)
    cos = np.array([loads[k][0] * (scale if k == 2 else 1.0) for k in sorted(loads)]).reshape(len(orders), n)
    sin = np.array([loads[k][1] * (scale if k == 2 else 1.0) for k in sorted(loads)]).reshape(len(orders), n)
    static = -model.K_c @ off + static_load(model)     # gravity and [[static_loads]] (rotor.model.static_load)
    force = HarmonicForce(static, orders, cos, sin, float(speed_rad_s))
    L = np.asarray(model.B, dtype=float)  # the two linear 3a/3b rows (not the squared g5)
    coupling = None
    if nonlinear_coupling and model.couplings:
        cp = model.couplings[0]
        if cp.a1_n_m_rad3 != 0.0:
            coupling = ((cp.a[2], cp.a[3]), (cp.b[2], cp.b[3]), float(cp.a1_n_m_rad3))
    return RotorSystem(model.M, model.C, model.G, model.K + model.K_c, float(speed_rad_s), force, off, L, sup,
                       tuple(model.dof_names), coupling)


@dataclass(frozen=True)
class SpeedFamily:
    """The rotor of a scene at any spin speed from one build: ``family(speed_rad_s)`` is a :class:`RotorSystem`.

    A system of :func:`system_from_model` depends on the speed in two places only (without speed-table bearings):
    ``G`` multiplies ``omega_rad_s``, and every harmonic load is ``∝ Ω²`` (unbalance, skew and the misalignment
    excitation: :func:`rotor.model.assembly.harmonic_loads`); matrices, static load and offset do not move. So the
    system at another speed is ``base`` with that speed and its harmonic load scaled by ``(Ω/Ω_base)²``, the built
    system's to round-off (``exact``; a harmonic-balance branch then takes its speed derivatives exactly:
    :func:`rotor.periodic.hb_aft.speed_blocks`). A model with a speed-table bearing (``rebuild``: speed ->
    system) is built at every speed asked for (``exact`` False).
    """

    base: RotorSystem
    rebuild: Callable | None = None

    @property
    def exact(self) -> bool:
        return self.rebuild is None

    def __call__(self, speed_rad_s: float) -> RotorSystem:
        if self.rebuild is not None:
            return self.rebuild(speed_rad_s)
        check_positive("speed_rad_s", speed_rad_s, "rad/s", upper=plausible.top("run_speed_rpm") * math.pi / 30)
        return at_speed(self.base, float(speed_rad_s))


def at_speed(system: RotorSystem, speed_rad_s: float) -> RotorSystem:
    """``system`` (built at a speed > 0) at ``speed_rad_s`` (rad/s): the same matrices, its harmonic load scaled by
    ``(speed_rad_s / system.omega_rad_s)²`` (see :class:`SpeedFamily`; no speed-table bearing)."""
    f = system.force
    if not system.omega_rad_s > 0.0:
        raise InputError(f"omega_rad_s = {system.omega_rad_s:g} rad/s: a system at rest holds no harmonic load to "
                         "scale; build it at a speed > 0")
    s2 = (float(speed_rad_s) / system.omega_rad_s) ** 2
    force = HarmonicForce(f.static, f.orders, f.cos * s2, f.sin * s2, float(speed_rad_s))
    return dataclasses.replace(system, omega_rad_s=float(speed_rad_s), force=force)


def _loose_support(model, ls, law, law_name, tilt_ignored, mu, preload_N, clearance_m) -> LooseSupport:
    """The scene's loose support ``ls`` with the overrides of :func:`system_from_model`."""
    from contact.loose_support import LooseSupportParams

    mu_v = ls.friction_coefficient if mu is None else mu
    pre_v = ls.preload_n if preload_N is None else preload_N
    calibrated = getattr(ls, "calibrated", None) if law_name is None else None
    if law is None and calibrated is not None:
        from rotor.model.loose_support_scene import geometry_mismatch
        bad = geometry_mismatch(vars(ls), calibrated)     # a scene edited after loading (dataclasses.replace)
        if bad is not None:
            raise InputError(f"{bad[0]} = {bad[1]:.6g} {bad[3]}: the scene's law {ls.law} holds for {bad[2]:.6g} "
                             f"{bad[3]} only")
        law = calibrated_support_law(calibrated, ls.law, ls.collision_factor_s_m, tilt_ignored, clearance_m)
    elif law is None:
        params = LooseSupportParams(
            clearance_m=ls.clearance_m if clearance_m is None else clearance_m, width_m=ls.ring_width_m,
            bearing_E_Pa=ls.bearing_modulus_pa, bearing_nu=ls.bearing_poisson,
            support_E_Pa=ls.support_modulus_pa, support_nu=ls.support_poisson,
            c_c_s_per_m=ls.collision_factor_s_m, tilt_ignored=tilt_ignored, law=law_name or ls.law)
        law = support_law_from_params(params)
    if law.tilt_ignored != bool(tilt_ignored) and tilt_ignored:
        raise InputError(f"tilt_ignored = True: the given law {law.name!r} passes moments; make it with tilt_ignored")
    return LooseSupport(tuple(model.loose_pair.bearing), tuple(model.loose_pair.support), law,
                        ls.ring_width_m, mu_v, pre_v, tilt_ignored=law.tilt_ignored)


def calibrated_support_law(cal, label: str, collision_factor_s_m: float, tilt_ignored: bool = False,
                           clearance_m: float | None = None) -> SupportLaw:
    """The loose-support law of a calibrated law ``cal`` (:class:`contact.calibrate.law.CalibratedLaw`).

    Clearance, width and materials are the calibration's; the collision factor ``c_c`` (s/m) is the
    scene's. ``clearance_m`` (m), if given, must be the calibration's (relative 1e-6): a calibrated law
    holds for its own geometry only. ``label`` names the law in that message (``calibrated:<name>`` or
    the law file as typed).
    """
    own = float(cal.geometry.clearance_m)
    if clearance_m is not None and not math.isclose(clearance_m, own, rel_tol=1e-6):
        raise InputError(f"clearance_mm = {clearance_m * 1e3:.6g} mm: the law {label} holds for clearance_mm = "
                         f"{own * 1e3:.6g} mm only (calibrate a law for that clearance, or use an analytic law)")
    params = cal.loose_support_params(c_c_s_per_m=collision_factor_s_m, tilt_ignored=bool(tilt_ignored))
    return support_law_from_params(params)
