"""Contact onset and loss inside the step: an edge penetration that changes sign over a step is located, and the
step split there (``NewmarkOptions.locate_events``, driven by :func:`rotor.dynamics.production_loop.step_loop`).

The loose support's law (Dai et al. 2025; docs/reference/contact-laws.md) acts on each ring edge through its
penetration ``Δr_k = |r_k| − δ0``, ``r_1 = (y + θz l0/2, z − θy l0/2)`` (right edge), ``r_2`` with ``−l0/2``
(:func:`rotor.dynamics.constraints.edge_offsets`). The conformal law has a finite stiffness at zero penetration:
the force is continuous where ``Δr_k`` crosses zero but its derivative jumps, so the plain step's map is only
piecewise smooth in its start state there (its trapezoidal force sees the kink at the step's ends only).

A step whose start and end penetrations of an edge differ in sign (:func:`edge_crossing`, a sign test on the
relative displacements the step already has) is redone up to the crossing and the rest of the step follows. The
crossing is the root, refined to round-off, of the penetration along the cubic Hermite interpolant of the
relative displacement over the plain step (its ends' displacements and velocities, :func:`crossing_fraction`):
a smooth function of the step's start while the crossing stays inside the step, so the located map is smooth
there too. One crossing per step is located (the earliest); a step that enters and leaves within itself (grazing
inside one step) has no sign change and is not located.
"""
from __future__ import annotations

import math

from numba import njit

from contact.compiled_cache import compiled_with

compiled_with(__file__, [])


@njit(cache=True, inline="always")
def _penetration(y, z, thy, thz, k, half_l0, d0, tilt_ignored):
    """``Δr_k`` (m) of edge ``k`` (0: right, +l0/2; 1: left) at the relative displacement ``(y, z, θy, θz)``."""
    if tilt_ignored:
        return math.sqrt(y * y + z * z) - d0
    sg = 1.0 if k == 0 else -1.0
    ry = y + sg * half_l0 * thz
    rz = z - sg * half_l0 * thy
    return math.sqrt(ry * ry + rz * rz) - d0


@njit(cache=True)
def edge_crossing(u0, u1, params):
    """True if an edge penetration changes sign between the relative displacements ``u0`` and ``u1`` (m, rad;
    ``[:4]`` used) of a step's ends; ``params`` the law's array (``[0]`` δ0, ``[1]`` l0, ``[11]`` tilt ignored)."""
    d0, hl, ti = params[0], 0.5 * params[1], params[11] != 0.0
    for k in range(2):
        a = _penetration(u0[0], u0[1], u0[2], u0[3], k, hl, d0, ti)
        b = _penetration(u1[0], u1[1], u1[2], u1[3], k, hl, d0, ti)
        if (a > 0.0) != (b > 0.0):
            return True
    return False


@njit(cache=True, inline="always")
def _hermite(x0, v0, x1, v1, h, s):
    """Cubic Hermite interpolant at fraction ``s`` of a step of length ``h`` (s)."""
    s2 = s * s
    s3 = s2 * s
    return ((2.0 * s3 - 3.0 * s2 + 1.0) * x0 + (s3 - 2.0 * s2 + s) * h * v0 + (-2.0 * s3 + 3.0 * s2) * x1
            + (s3 - s2) * h * v1)


@njit(cache=True)
def _pen_at(u0, w0, u1, w1, h, s, k, hl, d0, ti):
    return _penetration(_hermite(u0[0], w0[0], u1[0], w1[0], h, s), _hermite(u0[1], w0[1], u1[1], w1[1], h, s),
                        _hermite(u0[2], w0[2], u1[2], w1[2], h, s), _hermite(u0[3], w0[3], u1[3], w1[3], h, s),
                        k, hl, d0, ti)


@njit(cache=True)
def crossing_fraction(u0, w0, u1, w1, h, params):
    """Fraction ``θ ∈ (0, 1)`` of a step of length ``h`` (s) at which an edge penetration first crosses zero along
    the cubic Hermite interpolant of the relative displacement (``u0, w0``: start displacement and velocity, ``u1,
    w1``: end; m, rad, m/s, rad/s), the earliest over the edges whose end penetrations differ in sign; 2 if none.
    Each root is bracketed by the ends and refined by the Illinois rule to round-off."""
    d0, hl, ti = params[0], 0.5 * params[1], params[11] != 0.0
    theta = 2.0
    for k in range(2):
        fa = _pen_at(u0, w0, u1, w1, h, 0.0, k, hl, d0, ti)
        fb = _pen_at(u0, w0, u1, w1, h, 1.0, k, hl, d0, ti)
        if (fa > 0.0) == (fb > 0.0):
            continue
        a, b = 0.0, 1.0
        side = 0
        s = 0.5
        for _ in range(100):
            s = (a * fb - b * fa) / (fb - fa) if fb != fa else 0.5 * (a + b)
            if not (a < s < b):
                s = 0.5 * (a + b)
            fs = _pen_at(u0, w0, u1, w1, h, s, k, hl, d0, ti)
            if (fs > 0.0) == (fb > 0.0):
                b, fb = s, fs
                if side == 1:
                    fa *= 0.5
                side = 1
            else:
                a, fa = s, fs
                if side == -1:
                    fb *= 0.5
                side = -1
            if b - a <= 1e-15 or fs == 0.0:
                break
        theta = min(theta, s)
    return theta
