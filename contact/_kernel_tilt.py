"""Compiled (numba) tilt correction of a calibrated law's slice-integrated patch; see
:mod:`contact.calibrate.tilt_correction` (the fit, the readable numpy form and why).

Private module of ``contact._kernel``: :func:`tilt_correction` gives the log corrections ``a`` (patch load) and
``b`` (patch moment) with their exact derivatives in the patch's edge penetration and tilt. Its slots are the
last :data:`N_TILT_SLOTS` of a parameter tuple of ``contact._kernel.N_PARAMS_TILT`` slots, from :data:`TILT_SLOT`:
``n``, ``m`` (the surfaces' intervals in ξ and ψ, always :data:`TILT_XI_INTERVALS` and :data:`TILT_PSI_INTERVALS`),
``ln r_lo``, ``ln r_hi`` (r in m), then the ``(n+1)(m+1)`` force coefficients row by row, then the moment's.

Cost: a dynamic index into a numba tuple is a switch over all its slots, so every coefficient is read at a fixed
slot (:func:`_static`, written out) and every B-spline weight is evaluated, instead of the 4 x 4 that are not
zero. :func:`tilt_correction` is resolved when the kernel compiles: for a tuple of ``N_PARAMS_TILT`` slots it is
:func:`_static`; for any other (every law without a correction) it is a constant zero that the compiler removes,
so those laws compile to the code they had.
"""
from __future__ import annotations

import math

import numba
import numpy as np
from numba import types
from numba.extending import overload

from contact.compiled_cache import compiled_with

compiled_with(__file__, [])  # cached in the user's cache folder (contact.compiled_cache)

#: first slot of the tilt correction (contact._kernel checks it is its N_PARAMS: the correction comes last)
TILT_SLOT = 88
TILT_XI_INTERVALS = 4
TILT_PSI_INTERVALS = 6
TILT_BLOCK = (TILT_XI_INTERVALS + 1) * (TILT_PSI_INTERVALS + 1)
N_TILT_SLOTS = 4 + 2 * TILT_BLOCK
#: ψ = φ / PSI_SPAN_RAD (contact.calibrate.tilt_correction)
PSI_SPAN_RAD = 0.75 * math.pi


@numba.njit(cache=True, inline="always")
def _centred(x):
    """The uniform cubic B-spline centred at 0 (knot spacing 1) and its derivative at ``x`` (de Boor 1978), without
    branches (a mispredicted branch costs more than the arithmetic): with ``u = max(0, 2 − |x|)``,
    ``v = max(0, 1 − |x|)``, ``B = (u³ − 4 v³)/6`` and ``B' = sign(x) (2 v² − u²/2)``."""
    ax = abs(x)
    u = max(0.0, 2.0 - ax)
    v = max(0.0, 1.0 - ax)
    return (u * u * u - 4.0 * v * v * v) / 6.0, math.copysign(1.0, x) * (2.0 * v * v - 0.5 * u * u)


@numba.njit(cache=True, inline="always")
def _folded(u, i, n):
    """Weight of coefficient ``i`` (0..n) at ``u`` in [0, 1] on n intervals, with the mirrored end coefficients
    (``c[−1] = c[1]``, ``c[n+1] = c[n−1]``) folded in, and its derivative ``d/du``."""
    x = u * n
    w, dw = _centred(x - i)
    if i == 1:
        v, dv = _centred(x + 1.0)
        w, dw = w + v, dw + dv
    if i == n - 1:
        v, dv = _centred(x - n - 1.0)
        w, dw = w + v, dw + dv
    return w, dw * n


@numba.njit(cache=True, inline="always")
def _coordinates(pen, t, l0, log_r_lo, log_r_hi):
    """``(ξ, ∂ξ/∂Δr, ∂ξ/∂t, ψ, ∂ψ/∂Δr, ∂ψ/∂t)`` of a patch (edge penetration Δr in m, tilt t in rad, width l0 in m),
    each clamped to [0, 1] (its derivatives 0 there): ``r² = (Δr − q)² + q²``, ``φ = atan2(q, Δr − q)``,
    ``q = t l0/2`` (contact.calibrate.tilt_correction)."""
    q = 0.5 * l0 * t
    mid = pen - q
    r2 = mid * mid + q * q
    if r2 <= 0.0:
        r2 = 1e-300
    span = log_r_hi - log_r_lo
    xi = (0.5 * math.log(r2) - log_r_lo) / span
    if 0.0 < xi < 1.0:
        dxi_p, dxi_t = mid / (r2 * span), 0.5 * l0 * (q - mid) / (r2 * span)
    else:
        xi, dxi_p, dxi_t = min(max(xi, 0.0), 1.0), 0.0, 0.0
    psi = math.atan2(q, mid) / PSI_SPAN_RAD
    if 0.0 < psi < 1.0:
        dpsi_p, dpsi_t = -q / (r2 * PSI_SPAN_RAD), 0.5 * l0 * pen / (r2 * PSI_SPAN_RAD)
    else:
        psi, dpsi_p, dpsi_t = min(max(psi, 0.0), 1.0), 0.0, 0.0
    return xi, dxi_p, dxi_t, psi, dpsi_p, dpsi_t


@numba.njit(cache=True, inline="always")
def _straight(pen, p):
    """:func:`_static` at zero tilt: ``a = 0`` there with its derivatives (the surface's slope across ψ = 0 is zero
    and its value on that edge is zero), and only ``b`` is needed, its derivatives multiplying a zero moment arm
    (``contact._kernel._edge``); ``b`` is the ψ = 0 edge of the surface, whose weights are 2/3 and 1/3 on its first
    two coefficients, the same sum as :func:`_static` less the terms that are exactly zero."""
    xi = (0.5 * math.log(pen * pen) - p[TILT_SLOT + 2]) / (p[TILT_SLOT + 3] - p[TILT_SLOT + 2])
    xi = min(max(xi, 0.0), 1.0)
    wx0, _d0 = _folded(xi, 0, 4)
    wx1, _d1 = _folded(xi, 1, 4)
    wx2, _d2 = _folded(xi, 2, 4)
    wx3, _d3 = _folded(xi, 3, 4)
    wx4, _d4 = _folded(xi, 4, 4)
    w0, w1 = _folded(0.0, 0, 6)[0], _folded(0.0, 1, 6)[0]
    b = wx0 * (w0 * p[127] + w1 * p[128]) + wx1 * (w0 * p[134] + w1 * p[135]) + wx2 * (w0 * p[141] + w1 * p[142]) \
        + wx3 * (w0 * p[148] + w1 * p[149]) + wx4 * (w0 * p[155] + w1 * p[156])
    return 0.0, 0.0, 0.0, b, 0.0, 0.0


def _static(pen, t, l0, p):
    """:func:`tilt_correction` of a tuple of ``N_PARAMS_TILT`` slots, every coefficient at a fixed slot."""
    if t == 0.0:
        return _straight(pen, p)
    xi, dxi_p, dxi_t, psi, dpsi_p, dpsi_t = _coordinates(pen, t, l0, p[TILT_SLOT + 2], p[TILT_SLOT + 3])
    wx0, dx0 = _folded(xi, 0, 4)
    wx1, dx1 = _folded(xi, 1, 4)
    wx2, dx2 = _folded(xi, 2, 4)
    wx3, dx3 = _folded(xi, 3, 4)
    wx4, dx4 = _folded(xi, 4, 4)
    wy0, dy0 = _folded(psi, 0, 6)
    wy1, dy1 = _folded(psi, 1, 6)
    wy2, dy2 = _folded(psi, 2, 6)
    wy3, dy3 = _folded(psi, 3, 6)
    wy4, dy4 = _folded(psi, 4, 6)
    wy5, dy5 = _folded(psi, 5, 6)
    wy6, dy6 = _folded(psi, 6, 6)
    ar0 = wy0 * p[92] + wy1 * p[93] + wy2 * p[94] + wy3 * p[95] + wy4 * p[96] + wy5 * p[97] + wy6 * p[98]
    ad0 = dy0 * p[92] + dy1 * p[93] + dy2 * p[94] + dy3 * p[95] + dy4 * p[96] + dy5 * p[97] + dy6 * p[98]
    ar1 = wy0 * p[99] + wy1 * p[100] + wy2 * p[101] + wy3 * p[102] + wy4 * p[103] + wy5 * p[104] + wy6 * p[105]
    ad1 = dy0 * p[99] + dy1 * p[100] + dy2 * p[101] + dy3 * p[102] + dy4 * p[103] + dy5 * p[104] + dy6 * p[105]
    ar2 = wy0 * p[106] + wy1 * p[107] + wy2 * p[108] + wy3 * p[109] + wy4 * p[110] + wy5 * p[111] + wy6 * p[112]
    ad2 = dy0 * p[106] + dy1 * p[107] + dy2 * p[108] + dy3 * p[109] + dy4 * p[110] + dy5 * p[111] + dy6 * p[112]
    ar3 = wy0 * p[113] + wy1 * p[114] + wy2 * p[115] + wy3 * p[116] + wy4 * p[117] + wy5 * p[118] + wy6 * p[119]
    ad3 = dy0 * p[113] + dy1 * p[114] + dy2 * p[115] + dy3 * p[116] + dy4 * p[117] + dy5 * p[118] + dy6 * p[119]
    ar4 = wy0 * p[120] + wy1 * p[121] + wy2 * p[122] + wy3 * p[123] + wy4 * p[124] + wy5 * p[125] + wy6 * p[126]
    ad4 = dy0 * p[120] + dy1 * p[121] + dy2 * p[122] + dy3 * p[123] + dy4 * p[124] + dy5 * p[125] + dy6 * p[126]
    a = wx0 * ar0 + wx1 * ar1 + wx2 * ar2 + wx3 * ar3 + wx4 * ar4
    a_x = dx0 * ar0 + dx1 * ar1 + dx2 * ar2 + dx3 * ar3 + dx4 * ar4
    a_y = wx0 * ad0 + wx1 * ad1 + wx2 * ad2 + wx3 * ad3 + wx4 * ad4
    br0 = wy0 * p[127] + wy1 * p[128] + wy2 * p[129] + wy3 * p[130] + wy4 * p[131] + wy5 * p[132] + wy6 * p[133]
    bd0 = dy0 * p[127] + dy1 * p[128] + dy2 * p[129] + dy3 * p[130] + dy4 * p[131] + dy5 * p[132] + dy6 * p[133]
    br1 = wy0 * p[134] + wy1 * p[135] + wy2 * p[136] + wy3 * p[137] + wy4 * p[138] + wy5 * p[139] + wy6 * p[140]
    bd1 = dy0 * p[134] + dy1 * p[135] + dy2 * p[136] + dy3 * p[137] + dy4 * p[138] + dy5 * p[139] + dy6 * p[140]
    br2 = wy0 * p[141] + wy1 * p[142] + wy2 * p[143] + wy3 * p[144] + wy4 * p[145] + wy5 * p[146] + wy6 * p[147]
    bd2 = dy0 * p[141] + dy1 * p[142] + dy2 * p[143] + dy3 * p[144] + dy4 * p[145] + dy5 * p[146] + dy6 * p[147]
    br3 = wy0 * p[148] + wy1 * p[149] + wy2 * p[150] + wy3 * p[151] + wy4 * p[152] + wy5 * p[153] + wy6 * p[154]
    bd3 = dy0 * p[148] + dy1 * p[149] + dy2 * p[150] + dy3 * p[151] + dy4 * p[152] + dy5 * p[153] + dy6 * p[154]
    br4 = wy0 * p[155] + wy1 * p[156] + wy2 * p[157] + wy3 * p[158] + wy4 * p[159] + wy5 * p[160] + wy6 * p[161]
    bd4 = dy0 * p[155] + dy1 * p[156] + dy2 * p[157] + dy3 * p[158] + dy4 * p[159] + dy5 * p[160] + dy6 * p[161]
    b = wx0 * br0 + wx1 * br1 + wx2 * br2 + wx3 * br3 + wx4 * br4
    b_x = dx0 * br0 + dx1 * br1 + dx2 * br2 + dx3 * br3 + dx4 * br4
    b_y = wx0 * bd0 + wx1 * bd1 + wx2 * bd2 + wx3 * bd3 + wx4 * bd4
    return (a, a_x * dxi_p + a_y * dpsi_p, a_x * dxi_t + a_y * dpsi_t,
            b, b_x * dxi_p + b_y * dpsi_p, b_x * dxi_t + b_y * dpsi_t)


@numba.njit(cache=True, inline="always")
def spline_law_fixed(pen, p):
    """``contact._kernel._spline_law`` (law code 3) of a tuple of ``N_PARAMS_TILT`` slots, with every slot read at a
    fixed index (the knot found by a chain of comparisons over the 24 knot slots instead of a bisection over a
    dynamic index, each a switch over the tuple's slots): the same arithmetic in the same order, so the same numbers
    (the tests compare them bit for bit). A bisection written out with fixed slots (depth 5) compiled 2.7x slower
    (211 s against 79 s cold, beside a benchmark on both cores): every call site of the law inlines it."""
    nk = int(p[15])
    if pen <= 0.0:
        return 0.0, (0.0 if p[64] > -0.5 else math.inf), 1
    e = p[0] + pen
    sn = math.sqrt(pen * (2.0 * p[0] + pen)) / e
    cs = p[0] / e
    eps = math.atan2(sn, cs)
    hb = p[6] * e * (eps - sn * cs)
    dhb = p[6] * (eps + sn * cs)
    u = math.log(pen)
    if u <= p[16]:
        c = p[40] + p[64] * (u - p[16])
        dc = p[64]
    else:
        # the last knot k below u, of the first nk (a chain of fixed slots): beyond the last knot (k = nk − 1)
        # the correction is the straight line of its slope, else the cubic of [k, k + 1]
        k = 0
        xa, xb, ya, yb, ma, mb = p[16], p[17], p[40], p[41], p[64], p[65]
        if nk > 1 and u > p[17]:
            k = 1
            xa, xb, ya, yb, ma, mb = p[17], p[18], p[41], p[42], p[65], p[66]
        if nk > 2 and u > p[18]:
            k = 2
            xa, xb, ya, yb, ma, mb = p[18], p[19], p[42], p[43], p[66], p[67]
        if nk > 3 and u > p[19]:
            k = 3
            xa, xb, ya, yb, ma, mb = p[19], p[20], p[43], p[44], p[67], p[68]
        if nk > 4 and u > p[20]:
            k = 4
            xa, xb, ya, yb, ma, mb = p[20], p[21], p[44], p[45], p[68], p[69]
        if nk > 5 and u > p[21]:
            k = 5
            xa, xb, ya, yb, ma, mb = p[21], p[22], p[45], p[46], p[69], p[70]
        if nk > 6 and u > p[22]:
            k = 6
            xa, xb, ya, yb, ma, mb = p[22], p[23], p[46], p[47], p[70], p[71]
        if nk > 7 and u > p[23]:
            k = 7
            xa, xb, ya, yb, ma, mb = p[23], p[24], p[47], p[48], p[71], p[72]
        if nk > 8 and u > p[24]:
            k = 8
            xa, xb, ya, yb, ma, mb = p[24], p[25], p[48], p[49], p[72], p[73]
        if nk > 9 and u > p[25]:
            k = 9
            xa, xb, ya, yb, ma, mb = p[25], p[26], p[49], p[50], p[73], p[74]
        if nk > 10 and u > p[26]:
            k = 10
            xa, xb, ya, yb, ma, mb = p[26], p[27], p[50], p[51], p[74], p[75]
        if nk > 11 and u > p[27]:
            k = 11
            xa, xb, ya, yb, ma, mb = p[27], p[28], p[51], p[52], p[75], p[76]
        if nk > 12 and u > p[28]:
            k = 12
            xa, xb, ya, yb, ma, mb = p[28], p[29], p[52], p[53], p[76], p[77]
        if nk > 13 and u > p[29]:
            k = 13
            xa, xb, ya, yb, ma, mb = p[29], p[30], p[53], p[54], p[77], p[78]
        if nk > 14 and u > p[30]:
            k = 14
            xa, xb, ya, yb, ma, mb = p[30], p[31], p[54], p[55], p[78], p[79]
        if nk > 15 and u > p[31]:
            k = 15
            xa, xb, ya, yb, ma, mb = p[31], p[32], p[55], p[56], p[79], p[80]
        if nk > 16 and u > p[32]:
            k = 16
            xa, xb, ya, yb, ma, mb = p[32], p[33], p[56], p[57], p[80], p[81]
        if nk > 17 and u > p[33]:
            k = 17
            xa, xb, ya, yb, ma, mb = p[33], p[34], p[57], p[58], p[81], p[82]
        if nk > 18 and u > p[34]:
            k = 18
            xa, xb, ya, yb, ma, mb = p[34], p[35], p[58], p[59], p[82], p[83]
        if nk > 19 and u > p[35]:
            k = 19
            xa, xb, ya, yb, ma, mb = p[35], p[36], p[59], p[60], p[83], p[84]
        if nk > 20 and u > p[36]:
            k = 20
            xa, xb, ya, yb, ma, mb = p[36], p[37], p[60], p[61], p[84], p[85]
        if nk > 21 and u > p[37]:
            k = 21
            xa, xb, ya, yb, ma, mb = p[37], p[38], p[61], p[62], p[85], p[86]
        if nk > 22 and u > p[38]:
            k = 22
            xa, xb, ya, yb, ma, mb = p[38], p[39], p[62], p[63], p[86], p[87]
        if nk > 23 and u > p[39]:
            k = 23
            xa, xb, ya, yb, ma, mb = p[39], p[39], p[63], p[63], p[87], p[87]
        if k == nk - 1:
            c = ya + ma * (u - xa)
            dc = ma
        else:
            h = xb - xa
            t = (u - xa) / h
            t2 = t * t
            c = (2.0 * t2 * t - 3.0 * t2 + 1.0) * ya + (t2 * t - 2.0 * t2 + t) * h * ma \
                + (3.0 * t2 - 2.0 * t2 * t) * yb + (t2 * t - t2) * h * mb
            dc = (6.0 * t2 - 6.0 * t) * (ya - yb) / h + (3.0 * t2 - 4.0 * t + 1.0) * ma + (3.0 * t2 - 2.0 * t) * mb
    g = math.exp(c)
    return hb * g, (dhb + hb * dc / pen) * g, 1


@numba.njit(cache=True, inline="always")
def _law_on_fixed(pen, p):
    """``contact._kernel._law_on`` (``pen >= 0``) of law code 2 or 3, the spline by :func:`spline_law_fixed`."""
    if p[2] == 3.0:
        return spline_law_fixed(pen, p)
    e = p[0] + pen
    sn = math.sqrt(pen * (2.0 * p[0] + pen)) / e
    cs = p[0] / e
    eps = math.atan2(sn, cs)
    return p[6] * e * (eps - sn * cs), p[6] * (eps + sn * cs), 1


@numba.njit(cache=True, inline="always")
def law_fixed(pen, p):
    """``contact._kernel._law`` of a law with a tilt correction (law code 2 or 3): the same operations in the same
    order, every slot at a fixed index."""
    if pen < 0.0:
        _, dh0, _ok = _law_on_fixed(0.0, p)
        if not math.isfinite(dh0):
            dh0 = 0.0
        return dh0 * pen, dh0, 1
    return _law_on_fixed(pen, p)


# Gauss–Legendre nodes/weights on [0, 1] (8 points), as contact._kernel's
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)
_GL_X = 0.5 * (_GL_X + 1.0)
_GL_W = 0.5 * _GL_W


@numba.njit(cache=True)
def slices_fixed(pen, t, l0, partial, p):
    """``contact._kernel._slices`` of a law with a tilt correction: the same quadrature and operations, the law by
    :func:`law_fixed` (no dynamic index into the long tuple). Returns ``P, S, ∂P/∂pen, ∂P/∂t, ∂S/∂pen, ∂S/∂t``."""
    if t == 0.0:                 # straight ring: uniform slices, no quadrature needed
        h, dh, _ok = law_fixed(pen, p)
        return l0 * h, 0.5 * l0 * l0 * h, l0 * dh, -0.5 * l0 * l0 * dh, 0.5 * l0 * l0 * dh, -l0 * l0 * l0 * dh / 3.0
    P = 0.0
    S = 0.0
    Pp = 0.0
    Pt = 0.0
    Sp = 0.0
    St = 0.0
    for i in range(_GL_X.shape[0]):
        wv = _GL_X[i]
        q = 1.0 - wv * wv
        if partial:
            lv = pen / t
            dlv = pen * wv * wv                 # Δ = pen w², independent of t
            h, dh, _ok = law_fixed(dlv, p)
            c = 2.0 * _GL_W[i] * wv
            P += c * lv * h
            S += c * lv * lv * q * h
            Pp += c * (h / t + lv * dh * wv * wv)
            Sp += c * q * (2.0 * lv / t * h + lv * lv * dh * wv * wv)
        else:
            dlv = pen - t * l0 * q
            h, dh, _ok = law_fixed(dlv, p)
            c = 2.0 * _GL_W[i] * wv
            P += c * l0 * h
            S += c * l0 * l0 * q * h
            Pp += c * l0 * dh
            Pt += -c * l0 * dh * l0 * q
            Sp += c * l0 * l0 * q * dh
            St += -c * l0 * l0 * q * dh * l0 * q
    if partial:
        Pt = -P / t
        St = -2.0 * S / t
    return P, S, Pp, Pt, Sp, St



def _none(pen, t, l0, p):
    return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0


def tilt_correction(pen, t, l0, p):
    """``(a, ∂a/∂Δr, ∂a/∂t, b, ∂b/∂Δr, ∂b/∂t)`` (–, 1/m, 1/rad) of a patch: edge penetration Δr (m), tilt t >= 0
    (rad), width l0 (m), parameter tuple ``p``. ``a``, ``b`` are the tensor-product uniform cubic B-splines of the
    slots (module docstring) at ``ξ = (ln r − ln r_lo)/(ln r_hi − ln r_lo)``, ``ψ = φ/(3π/4)``. Plain Python here (the
    tests' reference); compiled code gets :func:`_static` or zero (module docstring)."""
    if len(p) != TILT_SLOT + N_TILT_SLOTS:
        return _none(pen, t, l0, p)
    return _static(pen, t, l0, p)


@overload(tilt_correction, inline="always")
def _tilt_correction_compiled(pen, t, l0, p):
    if isinstance(p, types.BaseTuple) and len(p) == TILT_SLOT + N_TILT_SLOTS:
        return _static
    return _none


def tilt_present(p):
    """True if the parameter tuple ``p`` carries a tilt correction (slot :data:`TILT_SLOT` of a long tuple != 0)."""
    return len(p) == TILT_SLOT + N_TILT_SLOTS and p[TILT_SLOT] != 0.0


@overload(tilt_present, inline="always")
def _tilt_present_compiled(p):
    if isinstance(p, types.BaseTuple) and len(p) == TILT_SLOT + N_TILT_SLOTS:
        return lambda p: p[TILT_SLOT] != 0.0
    return lambda p: False
