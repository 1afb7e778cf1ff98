"""Tilted ring: edge contact points, patch lengths, one-/two-point selection, forces and moments.

Readable numpy reference of Dai et al. (2025) Eqs. 8–19 (point and two-point contact of a
tilted bearing ring in its support). :mod:`contact.loose_support` evaluates the same model
in a compiled kernel for speed; the tests check that both agree.

Conventions (docs/reference/contact-laws.md §1, §8; written out in :mod:`contact.loose_support`): relative
bearing − support quantities in SI; edge 1 is the right edge at ``x = +l0/2``, edge 2 the
left edge at ``x = −l0/2``; a point at x moves by ``(y + x θz, z − x θy)``; a force F at x
gives ``My = −x Fz``, ``Mz = x Fy``; forces and moments act on the bearing.

Model (small-angle forms, consistent with the linearised kinematics):

* edge displacement ``r_k = r ± (l0/2) θ e^{−iπ/2}``, penetration ``Δr_k = |r_k| − δ0``;
* patch length ``l_k = Δr_k/|θ|`` when ``Δr_k < |θ| l0``, else ``l0`` (Eq. 15 capped);
* edge force ``f_k = −l_k p(Δr_k) (r_k/|r_k|) (1 + c_c v_k,n)`` with p the law's force per
  unit length (Eq. 16), moment arm ``d_k = (l0 − l_k)/2`` (Eq. 17);
* selection (Eqs. 18–19 with the Q8 fix): ``|r| <= δ0`` → both edges (opposite sides);
  ``|r| > δ0`` → only the edge with the larger penetration; a tie → the mean of the two
  (at θ = 0 both equal the line-contact force of Eq. 1, so it is not doubled);
* edge transition (a regularisation of Eqs. 18–19 with width ε_e, ``edge_transition_m``):
  the sharp rule jumps where the penetrations cross (moment arm ±d, force direction) and at
  ``|r| = δ0`` (both penetrating edges → the larger one). :func:`selection_weights` replaces
  both switches by a C² quintic step ``S`` of width ε_e: ``w1 = S(Δr1 − Δr2)``, ``w2 = 1 − w1``
  outside, and a hand-over ``λ = S(δ0 − ε_e/2 − |r|)`` over ``δ0 − ε_e < |r| < δ0``,
  ``w_k = λ [Δr_k > 0] + (1 − λ) w_k,outside``. ``S = 1/2`` at a tie (the Q8 mean, so θ = 0
  is unchanged), the sharp rule is kept to the last bit outside the bands, ε_e = 0 gives it
  everywhere. Default :data:`EDGE_TRANSITION_M`.

Choice of ε_e (the default, 0.2 µm)
-----------------------------------
*Physical bound.* Inside the bands the rule decides how two edges share the load when their
penetrations differ by less than ε_e/2 = 0.1 µm, i.e. a relative tilt below ε_e/l0 = 6.7 µrad
(0.023′) across the 30 mm ring of Table 4, some 20 times below the smallest tilt of the
paper's Table 3 (0.5′) and below the roughness of ground ring and seat surfaces (Ra of a few
tenths of a µm), where the rigid-ring model of Eqs. 8–19 cannot tell which edge touches
first anyway. The regularisation therefore adds no error the model does not already have.
*Numerical bound.* The width must let an implicit step find a root where the edges cross.
Measured on the 14 hard-case runs of issue 7 (Table 4 rotor, 10 revolutions at 10 500 rpm,
Δt = T/256, 7 cases × 2 starts, former stick-onset rule; ``benchmarks/bench_integrators.py``
section 4 has the current table): steps kept at the least residual 203 with the sharp rule,
1 each at ε_e = 10 nm and 30 nm, none from 50 nm up to 1 µm; the 15 steady-state 1X–5X amplitudes at 10 500 rpm (T/256, T/512, T/1024) are
bit-for-bit those of the sharp rule for ε_e <= 0.5 µm (the steady orbit never enters the
bands), while 1 µm moves them by 1 % (a different path into the stuck position). 0.2 µm
sits 4× above the lower and 2.5× below the upper measured limit. It is an absolute length:
at a 1 µm clearance the hand-over band is a fifth of δ0 (still only where both edges touch).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contact import laws
from contact.errors import InputError
from contact.units import check_finite

STATE_NONE, STATE_EDGE1, STATE_EDGE2, STATE_TWO_POINT, STATE_LINE = 0, 1, 2, 3, 4

#: Default width ε_e (m) of the smooth edge transition (module docstring: what it is, why this value).
EDGE_TRANSITION_M = 0.2e-6


@dataclass(frozen=True)
class TiltedContact:
    """Contact force and moment on the bearing, with the geometry that produced them.

    Attributes
    ----------
    Fy_N, Fz_N : ndarray
        Contact force on the bearing (N).
    My_Nm, Mz_Nm : ndarray
        Contact moment on the bearing about its centre (N·m).
    penetration_1_m, penetration_2_m : ndarray
        Edge penetrations Δr1 (right), Δr2 (left) (m); negative = gap.
    width_1_m, width_2_m : ndarray
        Patch lengths l1, l2 (m), capped at l0 (0 without contact at that edge).
    weight_1, weight_2 : ndarray
        Weight of each edge in the total from the selection rule (0, 0.5 or 1 for the sharp rule;
        between 0 and 1 inside the bands of the edge transition).
    state : ndarray of int8
        0 none, 1 right edge, 2 left edge, 3 two-point, 4 line/tie.
    in_domain : ndarray of bool
        False where the law has no value at a selected edge (forces NaN there).
    """

    Fy_N: np.ndarray
    Fz_N: np.ndarray
    My_Nm: np.ndarray
    Mz_Nm: np.ndarray
    penetration_1_m: np.ndarray
    penetration_2_m: np.ndarray
    width_1_m: np.ndarray
    width_2_m: np.ndarray
    weight_1: np.ndarray
    weight_2: np.ndarray
    state: np.ndarray
    in_domain: np.ndarray

    @property
    def force_N(self) -> np.ndarray:
        """Magnitude of the contact force (N)."""
        return np.hypot(self.Fy_N, self.Fz_N)

    @property
    def moment_Nm(self) -> np.ndarray:
        """Magnitude of the contact moment (N·m)."""
        return np.hypot(self.My_Nm, self.Mz_Nm)

    @property
    def contact_width_m(self) -> np.ndarray:
        """Length of the acting patch (m): the weighted patch lengths (l0 for line contact)."""
        return self.weight_1 * self.width_1_m + self.weight_2 * self.width_2_m


def edge_displacements(y_m, z_m, theta_y_rad, theta_z_rad, width_m: float):
    """Relative lateral displacements of the right (1) and left (2) ring edges (Dai et al. 2025 Eq. 10).

    Returns ``(r1y, r1z, r2y, r2z)`` (m): ``r_1,2 = (y ± θz l0/2, z ∓ θy l0/2)``.
    """
    h = 0.5 * width_m
    return y_m + h * theta_z_rad, z_m - h * theta_y_rad, y_m - h * theta_z_rad, z_m + h * theta_y_rad


def patch_length(penetration_m, tilt_magnitude_rad, width_m: float):
    """Axial patch length ``l = Δr/|θ|`` capped at ``l0`` (Dai et al. 2025 Eq. 15); 0 without contact (m)."""
    pen = np.asarray(penetration_m, dtype=float)
    t = np.asarray(tilt_magnitude_rad, dtype=float)
    partial = (pen > 0) & (pen < t * width_m)
    with np.errstate(divide="ignore", invalid="ignore"):
        l = np.where(partial, pen / np.where(partial, t, 1.0), width_m)
    return np.where(pen > 0, l, 0.0)


def smooth_step(x_m, half_width_m: float, tie: float = 0.5):
    """C² step ``S(x)`` and ``dS/dx`` (1/m): 0 for ``x <= −half_width``, 1 for ``x >= half_width``,
    ``1/2 + (15u − 10u³ + 3u⁵)/16`` with ``u = x/half_width`` between; ``half_width = 0`` is the
    sharp step with ``S(0) = tie``."""
    x = np.asarray(x_m, dtype=float)
    if half_width_m == 0.0:
        return np.where(x > 0, 1.0, np.where(x < 0, 0.0, tie)), np.zeros(x.shape)
    u = np.clip(x / half_width_m, -1.0, 1.0)
    u2 = u * u
    return 0.5 + u * (15.0 - u2 * (10.0 - 3.0 * u2)) / 16.0, 15.0 * (1.0 - u2) ** 2 / (16.0 * half_width_m)


def selection_weights(centre_offset_m, penetration_1_m, penetration_2_m, clearance_m: float,
                      edge_transition_m: float = EDGE_TRANSITION_M):
    """Weights of the two edges and the contact state (Dai et al. 2025 Eqs. 18–19 with the Q8 fix),
    regularised over ``edge_transition_m`` (m; 0 = the paper's sharp rule).

    Returns ``(w1, w2, state)``; see the module docstring for the rule. ``state`` is the
    classification of the sharp rule (0 none, 1 right edge, 2 left edge, 3 two-point, 4 tie)
    whatever ε_e, so that the reported contact state does not depend on the regularisation.
    """
    rho = np.asarray(centre_offset_m, dtype=float)
    p1 = np.asarray(penetration_1_m, dtype=float)
    p2 = np.asarray(penetration_2_m, dtype=float)
    eps = float(edge_transition_m)
    c1, c2 = p1 > 0, p2 > 0
    inside = rho <= clearance_m
    s, _ = smooth_step(p1 - p2, 0.5 * eps)
    if eps == 0.0:
        lam = inside.astype(float)
    else:
        lam, _ = smooth_step(clearance_m - 0.5 * eps - rho, 0.5 * eps)
    w1 = lam * c1 + (1.0 - lam) * s
    w2 = lam * c2 + (1.0 - lam) * (1.0 - s)
    w1 = np.where(c1, w1, 0.0).astype(float)
    w2 = np.where(c2, w2, 0.0).astype(float)
    state = np.full(np.shape(w1), STATE_NONE, dtype=np.int8)
    any_c = c1 | c2
    state[any_c & inside & c1 & ~c2] = STATE_EDGE1
    state[any_c & inside & c2 & ~c1] = STATE_EDGE2
    state[inside & c1 & c2] = STATE_TWO_POINT
    state[any_c & ~inside & (p1 > p2)] = STATE_EDGE1
    state[any_c & ~inside & (p2 > p1)] = STATE_EDGE2
    state[any_c & ~inside & (p1 == p2)] = STATE_LINE
    return w1, w2, state


def tilted_contact(y_m, z_m, theta_y_rad=0.0, theta_z_rad=0.0, vy_m_s=0.0, vz_m_s=0.0,
                   omega_y_rad_s=0.0, omega_z_rad_s=0.0, *, clearance_m: float, width_m: float,
                   force_per_width, c_c_s_per_m: float = 0.0, clip_damping_at_zero: bool = True,
                   edge_transition_m: float = EDGE_TRANSITION_M) -> TiltedContact:
    """Contact force and moment of a tilted ring in its support (Dai et al. 2025 Eqs. 8–19).

    Parameters
    ----------
    y_m, z_m, theta_y_rad, theta_z_rad, vy_m_s, vz_m_s, omega_y_rad_s, omega_z_rad_s : array_like
        Relative displacement (m), tilt (rad), velocity (m/s), angular velocity (rad/s).
    clearance_m, width_m : float
        Radial clearance δ0 and ring width l0 (m).
    force_per_width : callable
        ``penetration_m -> (N/m, in_domain)``, e.g. from :func:`contact.laws.force_per_width_function`.
    c_c_s_per_m : float
        Lankarani–Nikravesh collision factor (s/m).
    clip_damping_at_zero : bool
        Clip ``1 + c_c v_n`` at zero (see :func:`contact.laws.damping_factor`).
    edge_transition_m : float
        Width ε_e (m) of the smooth edge transition (module docstring); 0 = the paper's sharp rule.
    """
    laws.check_clearance(clearance_m)
    laws.check_width(width_m)
    names = ("y_m", "z_m", "theta_y_rad", "theta_z_rad", "vy_m_s", "vz_m_s", "omega_y_rad_s", "omega_z_rad_s")
    units = ("m", "m", "rad", "rad", "m/s", "m/s", "rad/s", "rad/s")
    vals = np.broadcast_arrays(*[np.asarray(v, dtype=float) for v in
                                 (y_m, z_m, theta_y_rad, theta_z_rad, vy_m_s, vz_m_s, omega_y_rad_s, omega_z_rad_s)])
    for name, unit, v in zip(names, units, vals):
        check_finite(name, v, unit)
    y, z, thy, thz, vy, vz, wy, wz = vals
    h = 0.5 * width_m
    t = np.hypot(thy, thz)
    r1y, r1z, r2y, r2z = edge_displacements(y, z, thy, thz, width_m)
    v1y, v1z, v2y, v2z = edge_displacements(vy, vz, wy, wz, width_m)   # same kinematics for velocities
    rho1, rho2 = np.hypot(r1y, r1z), np.hypot(r2y, r2z)
    pen1, pen2 = rho1 - clearance_m, rho2 - clearance_m
    check_finite("edge_transition_m", edge_transition_m, "m")
    if edge_transition_m < 0:
        raise InputError(f"edge_transition_m = {edge_transition_m:g} m: must be >= 0")
    w1, w2, state = selection_weights(np.hypot(y, z), pen1, pen2, clearance_m, edge_transition_m)
    out = np.zeros((4,) + y.shape)
    ok_all = np.ones(y.shape, dtype=bool)
    widths = []
    for sgn, w, ry, rz, vky, vkz, rho, pen in ((1.0, w1, r1y, r1z, v1y, v1z, rho1, pen1),
                                               (-1.0, w2, r2y, r2z, v2y, v2z, rho2, pen2)):
        l = patch_length(pen, t, width_m)
        widths.append(l)
        active = w > 0
        p_w, ok = force_per_width(np.where(active, pen, 0.0))
        ok_all &= ~active | np.asarray(ok, dtype=bool)
        with np.errstate(invalid="ignore", divide="ignore"):
            ny = np.where(active, ry / np.where(active, rho, 1.0), 0.0)
            nz = np.where(active, rz / np.where(active, rho, 1.0), 0.0)
        vn = ny * vky + nz * vkz
        damp = laws.damping_factor(vn, c_c_s_per_m, clip_at_zero=clip_damping_at_zero)
        P = np.where(active, l * np.nan_to_num(p_w, nan=0.0), 0.0)
        fy, fz = -P * damp * ny, -P * damp * nz
        d = 0.5 * (width_m - l)
        out += w * np.stack([fy, fz, sgn * d * (-fz), sgn * d * fy])
    out[:, ~ok_all] = np.nan
    return TiltedContact(out[0], out[1], out[2], out[3], pen1, pen2, widths[0], widths[1], w1, w2, state, ok_all)


def aligned_tilt_contact(penetration_m, tilt_rad, *, clearance_m: float, width_m: float,
                         force_per_width) -> TiltedContact:
    """Static contact at centre penetration Δr with the tilt aligned so that edge 1 penetrates most.

    The bearing centre sits at ``y = δ0 + Δr`` and the tilt is ``θz = tilt`` (``θy = 0``), so
    ``Δr1 = Δr + |θ| l0/2`` (the illustration of docs/reference/contact-laws.md §10 and the set-up of the
    paper's Table 3 read with centre penetration, Q9). Scalars or arrays that broadcast.
    """
    pen = np.asarray(penetration_m, dtype=float)
    check_finite("penetration_m", pen, "m")
    check_finite("tilt_rad", tilt_rad, "rad")
    return tilted_contact(clearance_m + pen, 0.0, 0.0, np.abs(tilt_rad), clearance_m=clearance_m,
                          width_m=width_m, force_per_width=force_per_width)
