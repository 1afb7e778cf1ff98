"""Total loose-support force and moment on the bearing (Dai et al. 2025 Eqs. 1–25), fast.

One function, :func:`loose_support_force`, gives the interaction force ``(Fy, Fz)`` and
moment ``(My, Mz)`` that the support exerts on the bearing outer ring, vectorized over
arrays of relative displacement, tilt, velocity and angular velocity. It is the sum of

* the radial contact force of the ring edges/line (conformal law of Dai et al. 2025 Eq. 5,
  or Pereira et al. 2015), with Lankarani–Nikravesh damping ``(1 + c_c v_n)`` and the
  point / two-point tilt geometry of Eqs. 8–19 (:mod:`contact.tilt` is the readable
  numpy reference of the same geometry; tests check that both agree), and
* the Coulomb friction of the two preloaded end faces and its moments (Eqs. 20–24,
  :mod:`contact.friction`).

Sign conventions (the one place they are written; docs/reference/contact-laws.md §1, §8, §9)
--------------------------------------------------------------------------------------------
* Inputs are **relative** quantities, bearing minus support, SI units:
  ``y = y_b − y_s``, ``z = z_b − z_s`` (m), ``θy = θ_b,y − θ_s,y``, ``θz`` (rad), their time
  derivatives ``vy, vz`` (m/s) and ``ωy = θ̇y, ωz = θ̇z`` (rad/s).
* A point of the bearing at axial position x (x along the shaft, right end face at
  ``x = +l0/2``, "edge/face 1"; left at ``x = −l0/2``, "edge/face 2") has relative lateral
  displacement ``(y + x θz, z − x θy)``, i.e. ``r(x) = r + x θ e^{−iπ/2}`` with ``r = y + iz``
  and ``θ = θy + iθz``.
* A force ``(Fy, Fz)`` acting at axial position x gives the moment
  ``My = −x Fz``, ``Mz = +x Fy`` (``M = x F e^{+iπ/2}``).
* Outputs ``Fy, Fz, My, Mz`` act **on the bearing** node; the support node receives the
  opposite. The contact force points from the contact towards the centre
  (``−P r_k/|r_k|``); friction opposes the face's relative velocity.

Model choices (open questions of docs/reference/contact-laws.md)
----------------------------------------------------------------
* Q8 selection: with the centre inside the clearance (``|r| <= δ0``) the two edges touch
  opposite sides and both forces add (two-point contact). With ``|r| > δ0`` only the edge
  with the larger penetration acts (one patch; capped at the full width l0 it is the line
  contact). A tie (``Δr1 = Δr2``, e.g. θ = 0 exactly) takes the **mean** of the two edge
  forces, not the paper's sum, so the force is continuous across θ = 0 and never doubled.
* Edge transition (a regularisation of Eqs. 18–19, ``edge_transition_m`` = ε_e): the sharp
  one-edge rule jumps where the penetrations cross (``Δr1 = Δr2`` with ``|r| > δ0``: the
  moment arm changes sign, the force direction jumps) and at ``|r| = δ0`` (both penetrating
  edges → the larger one), so an implicit time step across those points may have no root.
  With ε_e > 0 the weights are ``w1 = S(Δr1 − Δr2)``, ``w2 = 1 − w1`` (C² smooth step of width
  ε_e, ``S = 1/2`` at a tie: the Q8 mean) and the two-point branch hands over to the
  one-point branch smoothly over ``δ0 − ε_e < |r| < δ0`` (:func:`contact._kernel.selection`).
  Outside those bands the result is the sharp rule to the last bit; ε_e = 0 is the sharp rule
  everywhere. The default ε_e (:data:`contact.tilt.EDGE_TRANSITION_M`) and why it is chosen
  are documented in :mod:`contact.tilt`.
* Patch length ``l_k = Δr_k/|θ|`` capped at l0; moment arm ``(l0 − l_k)/2`` (small-angle
  forms of Eqs. 8 and 17, consistent with the linearised kinematics above).
* Damping ``max(0, 1 + c_c v_n)`` by default (``clip_damping_at_zero``), c_c in s/m (Q6).
* Friction: each face carries the full preload N, sliding force μN per face (Q12); at zero
  face velocity the face friction is zero here (stick is the integrator's constraint, see
  :func:`contact.friction.stick_test`). ``friction_smoothing_m_s > 0`` replaces ``v/|v|`` by
  ``v/sqrt(|v|² + ε²)`` for integrators that want a smooth Jacobian (default 0: exact).
* ``tilt_ignored=True`` is the paper's "neglecting angular deflection" model: line contact
  at the centre plane (Eq. 1), translation-only friction, zero moments.

Outside the law's domain
------------------------
The conformal law diverges at the neat-fit limit ``D(b) = 0`` (≈ 10 δ0 of penetration
for equal materials). :func:`loose_support_force` raises
:class:`~contact.errors.OutsideDomainError` there by default, or with
``on_outside="flag"`` returns NaN forces with ``in_domain = False`` for those points.

Fast scalar path for a numba-compiled step loop
-----------------------------------------------
::

    from contact.loose_support import LooseSupportParams, point_force, point_force_jacobian
    p = LooseSupportParams.paper_table4().kernel_args      # tuple of N_PARAMS floats
    @numba.njit
    def step(..., p):
        Fy, Fz, My, Mz = point_force(y, z, thy, thz, vy, vz, wy, wz, p)
        jac = np.empty((4, 8))
        Fy, Fz, My, Mz = point_force_jacobian(y, z, thy, thz, vy, vz, wy, wz, p, jac)

``jac[i, j] = ∂(Fy, Fz, My, Mz)[i] / ∂(y, z, θy, θz, vy, vz, ωy, ωz)[j]`` (analytic). Both
raise ``OutsideDomainError`` (constant message) beyond the neat-fit limit. They do not check
for NaN inputs (the vectorized path does). The same compiled kernel is used by
:func:`loose_support_force`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from contact import laws
from contact._kernel import (N_PARAMS, N_PARAMS_TILT, N_SPLINE_SLOTS, N_TILT_SLOTS, SPLINE_MAX_KNOTS, SPLINE_SLOT,  # noqa: F401
                             TILT_SLOT,
                             STATE_EDGE1, STATE_EDGE2, STATE_LINE, STATE_NONE, STATE_TWO_POINT, many_points, many_points_parallel, point_force, point_force_jacobian)
from contact.errors import InputError, OutsideDomainError
from contact.tilt import EDGE_TRANSITION_M
from contact.units import check_finite, check_positive

__all__ = ["LooseSupportParams", "LooseSupportForce", "loose_support_force", "loose_support_jacobian",
           "point_force", "point_force_jacobian", "STATE_NAMES", "INPUT_NAMES"]

LOOSE_SUPPORT_LAWS = ("conformal", "pereira")
STATE_NAMES = {STATE_NONE: "none", STATE_EDGE1: "edge1", STATE_EDGE2: "edge2",
               STATE_TWO_POINT: "two_point", STATE_LINE: "line"}
INPUT_NAMES = ("y_m", "z_m", "theta_y_rad", "theta_z_rad", "vy_m_s", "vz_m_s", "omega_y_rad_s", "omega_z_rad_s")
_INPUT_UNITS = ("m", "m", "rad", "rad", "m/s", "m/s", "rad/s", "rad/s")


@dataclass(frozen=True)
class LooseSupportParams:
    """Parameters of the loose support (SI). Validated on construction.

    Attributes
    ----------
    clearance_m : float
        Radial clearance δ0 (m).
    width_m : float
        Axial width of the bearing outer ring l0 (m).
    bearing_E_Pa, bearing_nu, support_E_Pa, support_nu : float
        Elastic constants of ring and support (Pa, –).
    c_c_s_per_m : float
        Lankarani–Nikravesh collision factor c_c (s/m), >= 0.
    mu : float
        End-face friction coefficient μ (–), >= 0.
    preload_N : float
        Axial nut preload N (N) pressing each end face, >= 0.
    law : {"conformal", "pereira"}
        Radial contact law (Johnson's has no solution beyond 0.54 δ0 and is not offered).
    modulus : {"plane_stress", "plane_strain"} or None
        2D idealisation of E*; None = the law's default (conformal: plane stress,
        Pereira: plane strain).
    beta_reading : str
        Reading of the conformal law's β term (see :mod:`contact.laws`).
    clip_damping_at_zero : bool
        Use ``max(0, 1 + c_c v_n)`` (default) instead of the raw factor.
    tilt_ignored : bool
        Line contact and translation-only friction (the paper's tilt-neglecting model).
    friction_smoothing_m_s : float
        ε of ``v/sqrt(|v|²+ε²)``; 0 (default) is ideal Coulomb friction.
    edge_transition_m : float
        Width ε_e (m) of the smooth edge transition that regularises the one-point selection of
        Dai et al. (2025) Eqs. 18–19 (see the module docstring); 0 is the paper's sharp rule.
        Default :data:`contact.tilt.EDGE_TRANSITION_M`.
    radius_m : float or None
        Outer radius of the ring, only to catch a clearance typed in mm.
    """

    clearance_m: float
    width_m: float
    bearing_E_Pa: float
    bearing_nu: float
    support_E_Pa: float
    support_nu: float
    c_c_s_per_m: float = 0.0
    mu: float = 0.0
    preload_N: float = 0.0
    law: str = "conformal"
    modulus: str | None = None
    beta_reading: str = "zero"
    clip_damping_at_zero: bool = True
    tilt_ignored: bool = False
    friction_smoothing_m_s: float = 0.0
    radius_m: float | None = field(default=None)
    edge_transition_m: float = EDGE_TRANSITION_M

    def __post_init__(self):
        laws.check_clearance(self.clearance_m, self.radius_m)
        laws.check_width(self.width_m)
        laws.check_material("bearing", self.bearing_E_Pa, self.bearing_nu)
        laws.check_material("support", self.support_E_Pa, self.support_nu)
        check_positive("c_c_s_per_m", self.c_c_s_per_m, "s/m", allow_zero=True)
        check_positive("mu", self.mu, "(dimensionless)", allow_zero=True, upper=10.0)
        check_positive("preload_N", self.preload_N, "N", allow_zero=True)
        check_positive("friction_smoothing_m_s", self.friction_smoothing_m_s, "m/s", allow_zero=True)
        check_positive("edge_transition_m", self.edge_transition_m, "m", allow_zero=True)
        if self.law not in LOOSE_SUPPORT_LAWS:
            raise InputError(f"law = {self.law!r}: must be one of {', '.join(LOOSE_SUPPORT_LAWS)}")
        if self.modulus is not None and self.modulus not in laws.MODULI:
            raise InputError(f"modulus = {self.modulus!r}: must be one of {', '.join(laws.MODULI)} or None")
        if self.beta_reading not in laws.BETA_READINGS:
            raise InputError(f"beta_reading = {self.beta_reading!r}: must be one of {', '.join(laws.BETA_READINGS)}")
        if self.law == "pereira":
            laws.pereira_exponent(self.clearance_m)

    @classmethod
    def paper_table4(cls, **overrides) -> "LooseSupportParams":
        """The 3# loose support of Dai et al. (2025) Table 4 (δ0 0.05 mm, l0 30 mm, 204 GPa, c_c 100, μ 0.3, N 5000 N)."""
        values = dict(clearance_m=0.05e-3, width_m=30e-3, bearing_E_Pa=204e9, bearing_nu=0.3,
                      support_E_Pa=204e9, support_nu=0.3, c_c_s_per_m=100.0, mu=0.3, preload_N=5000.0)
        values.update(overrides)
        return cls(**values)

    @property
    def effective_modulus(self) -> str:
        """The 2D idealisation actually used."""
        if self.modulus is not None:
            return self.modulus
        return "plane_stress" if self.law == "conformal" else "plane_strain"

    @cached_property
    def e_star_Pa(self) -> float:
        """Composite modulus E* (Pa) of the chosen idealisation."""
        return laws.composite_modulus(self.bearing_E_Pa, self.bearing_nu, self.support_E_Pa, self.support_nu,
                                      self.effective_modulus)

    @cached_property
    def neat_fit_limit_m(self) -> float:
        """Largest penetration (m) the law accepts (``inf`` for Pereira)."""
        if self.law != "conformal":
            return math.inf
        alpha, beta = laws.dundurs_constants(self.bearing_E_Pa, self.bearing_nu, self.support_E_Pa,
                                             self.support_nu, self.effective_modulus)
        return laws.conformal_neat_fit_limit_m(self.clearance_m, alpha, laws.beta_coefficient(beta, self.beta_reading))

    @cached_property
    def kernel_args(self) -> tuple:
        """The parameters as a flat tuple of floats for :func:`point_force` (layout in ``contact._kernel``)."""
        alpha, beta = laws.dundurs_constants(self.bearing_E_Pa, self.bearing_nu, self.support_E_Pa,
                                             self.support_nu, self.effective_modulus)
        if self.law == "pereira":
            pc, pn = laws.pereira_coefficient(self.clearance_m, self.e_star_Pa)
        else:
            pc, pn = 0.0, 1.0
        args = (self.clearance_m, self.width_m, 0.0 if self.law == "conformal" else 1.0,
                2.0 * math.pi * self.e_star_Pa * self.clearance_m, alpha,
                laws.beta_coefficient(beta, self.beta_reading), pc, pn, self.c_c_s_per_m,
                1.0 if self.clip_damping_at_zero else 0.0, self.mu * self.preload_N,
                1.0 if self.tilt_ignored else 0.0, self.friction_smoothing_m_s, self.edge_transition_m, 0.0) \
            + (0.0,) * N_SPLINE_SLOTS             # a calibrated spline law's knots (contact.calibrate.law)
        assert len(args) == N_PARAMS
        return tuple(float(a) for a in args)


@dataclass(frozen=True)
class LooseSupportForce:
    """Result of :func:`loose_support_force` (arrays of the broadcast input shape).

    ``Fy_N, Fz_N`` (N) and ``My_Nm, Mz_Nm`` (N·m) act on the bearing. With ``with_state=True``:
    ``in_domain`` (bool), ``state`` (int8 codes, names in :data:`STATE_NAMES`: 0 none,
    1 right edge, 2 left edge, 3 two-point, 4 line/tie) and the edge penetrations
    ``penetration_1_m``, ``penetration_2_m`` (m, negative = gap). Otherwise those are None.
    """

    Fy_N: np.ndarray
    Fz_N: np.ndarray
    My_Nm: np.ndarray
    Mz_Nm: np.ndarray
    in_domain: np.ndarray | None = None
    state: np.ndarray | None = None
    penetration_1_m: np.ndarray | None = None
    penetration_2_m: np.ndarray | None = None


def _prepare(inputs):
    """Broadcast the inputs to one shape; flat, contiguous, writeable float64 (no copy when already so)."""
    arrays = [np.asarray(a, dtype=float) for a in inputs]
    try:
        shape = np.broadcast_shapes(*(a.shape for a in arrays))
    except ValueError as exc:
        raise InputError(f"inputs of shapes {[a.shape for a in arrays]} do not broadcast: {exc}") from exc
    flat = []
    for a in arrays:
        if a.shape != shape or not a.flags.writeable:
            a = np.array(np.broadcast_to(a, shape))          # a writeable copy: one compiled signature
        flat.append(np.ascontiguousarray(a).reshape(-1))
    return shape, flat


def _raise_bad(flat, idx):
    for name, unit, arr in zip(INPUT_NAMES, _INPUT_UNITS, flat):
        if not math.isfinite(arr[idx]):
            check_finite(name, arr[idx], unit)
    raise InputError(f"inputs at point {idx} are not finite")  # pragma: no cover (sum overflow only)


def _run(params, inputs, want_jac, want_state, on_outside, parallel=False):
    if on_outside not in ("raise", "flag"):
        raise InputError(f"on_outside = {on_outside!r}: must be 'raise' or 'flag'")
    if not isinstance(params, LooseSupportParams):
        raise InputError(f"params = {type(params).__name__}: must be LooseSupportParams")
    shape, flat = _prepare(inputs)
    n = flat[0].size
    F = np.empty((n, 4))
    J = np.empty((n, 4, 8)) if want_jac else np.empty((1, 4, 8))
    m = n if want_state else 1
    ok = np.empty(m, dtype=np.bool_)
    state = np.empty(m, dtype=np.int8)
    pen = np.empty((m, 2))
    if parallel and not want_jac:
        status = np.empty(n, dtype=np.int8)
        many_points_parallel(*flat, params.kernel_args, want_state, F, status, state, pen)
        bad = np.flatnonzero(status)
        idx, code = (int(bad[0]), int(status[bad[0]])) if bad.size else (-1, 0)
        if code == 2:
            nonfinite = np.flatnonzero(status == 1)
            if nonfinite.size:
                idx, code = int(nonfinite[0]), 1
        if want_state:
            ok[:] = status == 0
    else:
        idx, code = many_points(*flat, params.kernel_args, want_jac, want_state, F, J, ok, state, pen)
    if code == 1:
        _raise_bad(flat, idx)
    if code == 2 and on_outside == "raise":
        offset = math.hypot(flat[0][idx], flat[1][idx])
        hint = " (displacements given in mm? SI expected)" if offset > 100 * params.clearance_m else ""
        raise OutsideDomainError(
            f"loose support: point {idx} (y_m = {flat[0][idx]:g} m, z_m = {flat[1][idx]:g} m) penetrates beyond the "
            f"{params.law} law's neat-fit limit of {params.neat_fit_limit_m:g} m (D(b) <= 0){hint}; "
            "use on_outside='flag' to get NaN with in_domain=False")
    return shape, F, J, ok, state, pen


def loose_support_force(params: LooseSupportParams, y_m, z_m, theta_y_rad=0.0, theta_z_rad=0.0,
                        vy_m_s=0.0, vz_m_s=0.0, omega_y_rad_s=0.0, omega_z_rad_s=0.0, *,
                        with_state: bool = False, on_outside: str = "raise",
                        parallel: bool = False) -> LooseSupportForce:
    """Total loose-support force and moment on the bearing (Dai et al. 2025 Eq. 25), vectorized.

    Parameters
    ----------
    params : LooseSupportParams
    y_m, z_m : array_like
        Relative lateral displacement bearing − support (m).
    theta_y_rad, theta_z_rad : array_like
        Relative tilt (rad).
    vy_m_s, vz_m_s : array_like
        Relative lateral velocity (m/s).
    omega_y_rad_s, omega_z_rad_s : array_like
        Relative angular velocity (rad/s).
    with_state : bool
        Also return the contact state, domain mask and edge penetrations.
    on_outside : {"raise", "flag"}
        What to do at points beyond the law's domain (module docstring).
    parallel : bool
        Spread the points over all cores (numba threads). Default False: one thread, which
        is what a process-parallel sweep wants.

    Returns
    -------
    LooseSupportForce
        Arrays broadcast to the common shape of the inputs.

    Raises
    ------
    InputError
        naming the input (and its unit) holding a NaN or inf.
    OutsideDomainError
        if ``on_outside == "raise"`` and a point is beyond the neat-fit limit.
    """
    inputs = (y_m, z_m, theta_y_rad, theta_z_rad, vy_m_s, vz_m_s, omega_y_rad_s, omega_z_rad_s)
    shape, F, _, ok, state, pen = _run(params, inputs, False, with_state, on_outside, parallel)
    cols = [F[:, i].reshape(shape) for i in range(4)]
    if not with_state:
        return LooseSupportForce(*cols)
    return LooseSupportForce(*cols, in_domain=ok.reshape(shape), state=state.reshape(shape),
                             penetration_1_m=pen[:, 0].reshape(shape), penetration_2_m=pen[:, 1].reshape(shape))


def loose_support_jacobian(params: LooseSupportParams, y_m, z_m, theta_y_rad=0.0, theta_z_rad=0.0,
                           vy_m_s=0.0, vz_m_s=0.0, omega_y_rad_s=0.0, omega_z_rad_s=0.0, *,
                           on_outside: str = "raise") -> tuple[np.ndarray, np.ndarray]:
    """Forces and their analytic Jacobian.

    Returns
    -------
    forces : ndarray, shape (..., 4)
        ``(Fy, Fz, My, Mz)`` (N, N, N·m, N·m).
    jacobian : ndarray, shape (..., 4, 8)
        ``∂(Fy, Fz, My, Mz) / ∂(y, z, θy, θz, vy, vz, ωy, ωz)`` in SI units.
        At the non-smooth points of the model (first contact, the damping clip, zero face
        velocity, and the edge-selection switch when ``edge_transition_m = 0``) it is a
        one-sided or mean value; with ``edge_transition_m > 0`` it includes the derivatives of
        the smooth edge weights.
    """
    inputs = (y_m, z_m, theta_y_rad, theta_z_rad, vy_m_s, vz_m_s, omega_y_rad_s, omega_z_rad_s)
    shape, F, J, _, _, _ = _run(params, inputs, True, False, on_outside)
    return F.reshape(shape + (4,)), J.reshape(shape + (4, 8))
