"""Compiled (numba) point kernel of the loose-support force; see :mod:`contact.loose_support`.

Private module: the public entry points and the sign conventions are documented in
:mod:`contact.loose_support`. The same scalar kernel serves the vectorized array path
(:func:`many_points`) and the integrator's step loop (:func:`point_force`,
:func:`point_force_jacobian`), so both always agree.

Parameter tuple ``p`` (all floats, built by ``LooseSupportParams.kernel_args``):

====  ==================================================================
 0    clearance δ0 (m)
 1    ring width l0 (m)
 2    law code: 0 conformal, 1 Pereira (power law C·Δr^n), 2 elastic foundation
      (calibrated law of contact.calibrate: h = k_f R e (ε − sin ε cos ε), slot 6 = k_f R;
      a tilted patch is integrated slice by slice, see _slices, instead of l·h(Δr_edge)),
      3 foundation-spline (contact.calibrate.spline: the foundation law with slot 6 = R times
      exp(c(ln Δr)), c the cubic Hermite spline of slots 15 on; tilted patches slice by slice as code 2)
 3    conformal constant 2π E* δ0 (N/m per unit b²(1+b²)/D)
 4    Dundurs α
 5    β coefficient c_β of the denominator (0 for the "zero" reading)
 6    Pereira C (N / m / m^n)
 7    Pereira exponent n
 8    collision factor c_c (s/m)
 9    1.0: clip (1 + c_c v_n) at zero; 0.0: raw product
10    μN, sliding friction force of one end face (N)
11    1.0: tilt ignored (line contact, translation-only friction)
12    friction smoothing velocity ε (m/s); 0 = ideal Coulomb
13    edge-transition width ε_e (m) of the one-point selection; 0 = the paper's sharp rule
14    bilateral offset o (m); 0 (always, except below) = the law as published. With o > 0 an edge counts
      as touching from ``Δr > −o`` and the law's linear extension ``h'(0⁺) Δr`` pulls it for ``Δr < 0``:
      the *contact piece* of the map extended across grazing, which the grazing analysis of
      rotor/periodic/grazing.py differentiates (di Bernardo et al. 2008: each smooth piece of a
      piecewise-smooth system continued past its switching surface)
15…   law code 3 only (else 0): the number of knots K (2 <= K <= SPLINE_MAX_KNOTS), then the knots' ln Δr,
      their values c and slopes dc/d ln Δr (SPLINE_MAX_KNOTS slots each, the first K used); c linear beyond
88…   only in a tuple of N_PARAMS_TILT slots (law codes 2 and 3): a tilt correction of the slice-integrated
      patch fitted to 3D tilted points, P exp(a) and moment × exp(b) (contact._kernel_tilt,
      contact.calibrate.tilt_correction). The usual tuple of N_PARAMS slots has none, and compiles as before
====  ==================================================================

Edge selection (Dai et al. 2025 Eqs. 18–19, regularised; :func:`selection`): with the centre
outside the clearance the paper loads only the edge with the larger penetration, so at
``Δr1 = Δr2`` the force direction and the moment arm ``±d`` jump; at ``|r| = δ0`` the rule
jumps from both penetrating edges (two-point) to the larger one. With ``ε_e > 0`` both
switches become C² smooth steps of width ``ε_e`` (see :func:`_smooth_step`); ``ε_e = 0``
is the sharp rule exactly (with the Q8 tie: the mean of the two edges at ``Δr1 = Δr2``).
"""
from __future__ import annotations

import math

import numba
import numpy as np

from contact._kernel_friction import _face_friction
from contact._kernel_tilt import N_TILT_SLOTS, TILT_SLOT, slices_fixed, tilt_correction, tilt_present
from contact.compiled_cache import compiled_with
from contact.errors import OutsideDomainError

compiled_with(__file__, ["contact._kernel_friction", "contact._kernel_tilt"])  # cached in the user's cache folder

SPLINE_MAX_KNOTS = 24
SPLINE_SLOT = 15                                   # first slot of a code-3 law's spline
N_SPLINE_SLOTS = 1 + 3 * SPLINE_MAX_KNOTS
N_PARAMS = SPLINE_SLOT + N_SPLINE_SLOTS
N_PARAMS_TILT = N_PARAMS + N_TILT_SLOTS            # a law with a tilt correction: its slots after the others
assert TILT_SLOT == N_PARAMS
STATE_NONE, STATE_EDGE1, STATE_EDGE2, STATE_TWO_POINT, STATE_LINE = 0, 1, 2, 3, 4


@numba.njit(cache=True, inline="always")
def _law(pen, p):
    """Force per unit contact length h(Δr) (N/m), dh/dΔr, and 1 if inside the domain; below zero penetration
    (only with a bilateral offset, slot 14) the linear extension ``h'(0⁺) Δr`` (0 where ``h'(0⁺)`` is not
    finite)."""
    if pen < 0.0:
        _, dh0, _ok = _law_on(0.0, p)
        if not math.isfinite(dh0):
            dh0 = 0.0
        return dh0 * pen, dh0, 1
    return _law_on(pen, p)


@numba.njit(cache=True, inline="always")
def _law_on(pen, p):
    """:func:`_law` at ``pen >= 0``."""
    if p[2] == 0.0:
        d0 = p[0]
        q = 2.0 * d0 + pen
        s = pen / q
        ds = 2.0 * d0 / (q * q)
        one_m_a = 1.0 - p[4]
        D = 2.0 - one_m_a * (math.log1p(s) + 2.0 * s * s) + p[5] * s * (1.0 + s)
        if D <= 0.0:
            return 0.0, 0.0, 0
        dD = -one_m_a * (1.0 / (1.0 + s) + 4.0 * s) + p[5] * (1.0 + 2.0 * s)
        g = s * (1.0 + s) / D
        dg = ((1.0 + 2.0 * s) * D - s * (1.0 + s) * dD) / (D * D)
        return p[3] * g, p[3] * dg * ds, 1
    if p[2] == 2.0:
        # --- additive hook for contact.calibrate (issue 5): Winkler elastic foundation ---
        # h = k_f R e (ε − sin ε cos ε), e = δ0 + Δr, cos ε = δ0/e; dh/dΔr = k_f R (ε + sin ε cos ε)
        e = p[0] + pen
        sn = math.sqrt(pen * (2.0 * p[0] + pen)) / e
        cs = p[0] / e
        eps = math.atan2(sn, cs)
        return p[6] * e * (eps - sn * cs), p[6] * (eps + sn * cs), 1
    if p[2] == 3.0:
        return _spline_law(pen, p)
    n = p[7]
    return p[6] * pen ** n, p[6] * n * pen ** (n - 1.0), 1


@numba.njit(cache=True, inline="always")
def _spline_law(pen, p):
    """Law code 3 at ``pen >= 0``: ``h = R e (ε − sin ε cos ε) exp(c(ln Δr))``, dh/dΔr (slots: module docstring);
    at Δr = 0, h = 0 and h' = 0 where ``h ~ Δr^(1.5 + c'(−∞))`` has a finite slope, else inf."""
    nk = int(p[SPLINE_SLOT])
    x0 = SPLINE_SLOT + 1
    y0 = x0 + SPLINE_MAX_KNOTS
    m0 = y0 + SPLINE_MAX_KNOTS
    if pen <= 0.0:
        return 0.0, (0.0 if p[m0] > -0.5 else math.inf), 1
    e = p[0] + pen
    sn = math.sqrt(pen * (2.0 * p[0] + pen)) / e
    cs = p[0] / e
    eps = math.atan2(sn, cs)
    hb = p[6] * e * (eps - sn * cs)
    dhb = p[6] * (eps + sn * cs)
    u = math.log(pen)
    if u <= p[x0]:
        c = p[y0] + p[m0] * (u - p[x0])
        dc = p[m0]
    elif u > p[x0 + nk - 1]:
        c = p[y0 + nk - 1] + p[m0 + nk - 1] * (u - p[x0 + nk - 1])
        dc = p[m0 + nk - 1]
    else:
        k = 0                    # bisection: the interval [x_k, x_k+1] holding u (x_0 < u < x_nk-1)
        hi = nk - 1
        while hi - k > 1:
            mid = (k + hi) // 2
            if u > p[x0 + mid]:
                k = mid
            else:
                hi = mid
        h = p[x0 + k + 1] - p[x0 + k]
        t = (u - p[x0 + k]) / h
        t2 = t * t
        ya = p[y0 + k]
        yb = p[y0 + k + 1]
        ma = p[m0 + k]
        mb = p[m0 + k + 1]
        c = (2.0 * t2 * t - 3.0 * t2 + 1.0) * ya + (t2 * t - 2.0 * t2 + t) * h * ma + (3.0 * t2 - 2.0 * t2 * t) * yb \
            + (t2 * t - t2) * h * mb
        dc = (6.0 * t2 - 6.0 * t) * (ya - yb) / h + (3.0 * t2 - 4.0 * t + 1.0) * ma + (3.0 * t2 - 2.0 * t) * mb
    g = math.exp(c)
    return hb * g, (dhb + hb * dc / pen) * g, 1


# Gauss–Legendre nodes/weights on [0, 1] (8 points) for the slice integral of law codes 2 and 3.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)
_GL_X = 0.5 * (_GL_X + 1.0)
_GL_W = 0.5 * _GL_W


@numba.njit(cache=True)
def _slices(pen, t, l0, partial, p):
    """Slice-integrated load of a tilted patch for law codes 2 and 3 (additive hook for contact.calibrate, issue 5).

    A Winkler bed has independent axial slices, so the patch load is ``P = ∫_0^l h(pen − t s) ds``
    (s from the loaded edge, l = pen/t for a partial patch, l0 otherwise) and its first moment about
    the edge ``S = ∫_0^l s h(pen − t s) ds``; with ``s = l (1 − w²)`` both integrands are smooth on
    w ∈ [0, 1] (also at the open end of a partial patch, where h ~ Δ^1.5) and 8 Gauss points give
    ~1e-10 relative accuracy. Returns ``P, S, ∂P/∂pen, ∂P/∂t, ∂S/∂pen, ∂S/∂t``.
    """
    if t == 0.0:                 # straight ring: uniform slices, no quadrature needed
        h, dh, _ok = _law(pen, p)
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
            h, dh, _ok = _law(dlv, p)
            c = 2.0 * _GL_W[i] * wv
            P += c * lv * h
            S += c * lv * lv * q * h
            Pp += c * (h / t + lv * dh * wv * wv)
            Sp += c * q * (2.0 * lv / t * h + lv * lv * dh * wv * wv)
        else:
            dlv = pen - t * l0 * q
            h, dh, _ok = _law(dlv, p)
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


@numba.njit(cache=True, inline="always")
def _smooth_step(x, half_width, tie):
    """Smooth step ``S`` and ``dS/dx`` of a switch at ``x = 0`` (x in m).

    Quintic ``S = 1/2 + (15u − 10u³ + 3u⁵)/16`` with ``u = x/half_width`` on ``|u| < 1``, 0 below,
    1 above: C² (S' and S'' vanish at ``u = ±1``), ``S(0) = 1/2``, and exactly the sharp step
    outside ``|x| < half_width``. ``half_width = 0``: the sharp step, ``S(0) = tie``.
    """
    if half_width == 0.0:
        if x > 0.0:
            return 1.0, 0.0
        if x < 0.0:
            return 0.0, 0.0
        return tie, 0.0
    u = x / half_width
    if u >= 1.0:
        return 1.0, 0.0
    if u <= -1.0:
        return 0.0, 0.0
    u2 = u * u
    q = 1.0 - u2
    return 0.5 + u * (15.0 - u2 * (10.0 - 3.0 * u2)) / 16.0, 15.0 * q * q / (16.0 * half_width)


@numba.njit(cache=True, inline="always")
def selection(rr, pen1, pen2, d0, eps_e):
    """Edge weights of Dai et al. (2025) Eqs. 18–19 with the Q8 tie, regularised over ``eps_e`` (m).

    Sharp rule (``eps_e = 0``): centre inside the clearance (``|r| <= δ0``) → every penetrating
    edge carries load (two-point contact); outside → only the edge with the larger penetration
    (``w = 1``), a tie → the mean (``w1 = w2 = 1/2``). Regularised: ``s = S(Δr1 − Δr2)`` over the
    band ``|Δr1 − Δr2| < ε_e/2`` (width ε_e, so ``s = 1/2`` at a tie as the Q8 rule), and the
    hand-over ``λ = S(δ0 − ε_e/2 − |r|)`` from the two-point to the one-point branch over the band
    ``δ0 − ε_e < |r| < δ0`` (inside the clearance, so that with θ = 0, where no edge penetrates
    for ``|r| <= δ0``, nothing changes); ``w_k = λ c_k + (1 − λ) s_k`` with ``c_k = [Δr_k > 0]``,
    ``s_1 = s``, ``s_2 = 1 − s``.

    Returns ``(w1, w2, state, ds, dlam)``: ``ds = ds/d(Δr1 − Δr2)``, ``dlam = dλ/d(δ0 − |r|)``
    (1/m), and the state of the sharp rule (0 none, 1 edge 1, 2 edge 2, 3 two-point, 4 tie).
    """
    if pen1 <= 0.0 and pen2 <= 0.0:
        return 0.0, 0.0, STATE_NONE, 0.0, 0.0
    c1 = 1.0 if pen1 > 0.0 else 0.0
    c2 = 1.0 if pen2 > 0.0 else 0.0
    if rr <= d0:
        if c1 > 0.0 and c2 > 0.0:
            state = STATE_TWO_POINT
        elif c1 > 0.0:
            state = STATE_EDGE1
        else:
            state = STATE_EDGE2
    elif pen1 > pen2:
        state = STATE_EDGE1
    elif pen2 > pen1:
        state = STATE_EDGE2
    else:
        state = STATE_LINE
    s, ds = _smooth_step(pen1 - pen2, 0.5 * eps_e, 0.5)
    if eps_e == 0.0:
        lam = 1.0 if rr <= d0 else 0.0
        dlam = 0.0
    else:
        lam, dlam = _smooth_step(d0 - 0.5 * eps_e - rr, 0.5 * eps_e, 0.5)
    w1 = lam * c1 + (1.0 - lam) * s
    w2 = lam * c2 + (1.0 - lam) * (1.0 - s)
    if c1 == 0.0:
        w1 = 0.0
    if c2 == 0.0:
        w2 = 0.0
    return w1, w2, state, ds, dlam


@numba.njit(cache=True, inline="always")
def _edge(sgn, w, ry, rz, rho, vy, vz, wy, wz, thy, thz, t, p, jac):
    """The contact force of edge ``sgn`` (+1 right, −1 left), unweighted, and ``w`` × its Jacobian.

    ``(ry, rz)`` is the edge's relative displacement and ``rho`` its length.
    Returns ``(fy, fz, sd, ok)``: the force, the signed moment arm ``sd = sgn·d`` (the moment
    is ``(sd·(−fz), sd·fy)``) and ok = 1 inside the law's domain (or without contact), 0
    otherwise; adds ``w`` × the Jacobian of force and moment to ``jac`` unless ``jac`` is None
    (the derivatives of the weight itself are the caller's).
    """
    d0 = p[0]
    l0 = p[1]
    a = sgn * 0.5 * l0
    pen = rho - d0
    if pen <= -p[14]:
        return 0.0, 0.0, 0.0, 1
    inv_rho = 1.0 / rho
    ny = ry * inv_rho
    nz = rz * inv_rho
    vky = vy + a * wz
    vkz = vz - a * wy
    vn = ny * vky + nz * vkz
    corr = p[2] >= 2.0 and tilt_present(p)     # False at compile time for N_PARAMS slots (contact._kernel_tilt)
    if corr:                                    # the slices evaluate the law (a slice law is defined for Δr >= 0)
        hv, dh, ok = 0.0, 0.0, 1
    else:
        hv, dh, ok = _law(pen, p)
    if ok == 0:
        return 0.0, 0.0, 0.0, 0
    partial = 0.0 < pen < t * l0       # (a bilateral edge below zero penetration: the full width)
    if partial:
        l = pen / t
    else:
        l = l0
    slices = p[2] >= 2.0
    ea = eb = 1.0
    ca_p = ca_t = cb_p = cb_t = 0.0
    if slices:
        P, S, Pp, Pt, Sp, St = slices_fixed(pen, t, l0, partial, p) if corr else _slices(pen, t, l0, partial, p)
        # P = 0 where the slice length pen/t underflows (t = inf: a shooting trial state with |θ| ~ 1e155 rad,
        # rejected by its line search): no load, the arm of the analytic laws, no division by zero
        d = 0.5 * l0 - S / P if P > 0.0 else 0.5 * (l0 - l)
        P_s, d_s = P, d                 # the slices' patch, before the tilt correction of a law that has one
        if corr:                        # P exp(a), moment P d exp(b): contact._kernel_tilt, fitted to 3D points
            ca, ca_p, ca_t, cb, cb_p, cb_t = tilt_correction(pen, t, l0, p)
            ea = math.exp(ca)
            eb = math.exp(cb - ca)
            P, d = P * ea, d * eb
    else:
        P = l * hv
        d = 0.5 * (l0 - l)
        P_s, d_s = P, d
    damp = 1.0 + p[8] * vn
    clipped = False
    if p[9] != 0.0 and damp < 0.0:
        damp = 0.0
        clipped = True
    fy = -P * damp * ny
    fz = -P * damp * nz
    if jac is None:
        return fy, fz, sgn * d, 1
    # derivatives of r_k (and of r_k-dot w.r.t. velocities) w.r.t. (y, z, thy, thz)
    dry = (1.0, 0.0, 0.0, a)
    drz = (0.0, 1.0, -a, 0.0)
    for j in range(4):
        dpen = ny * dry[j] + nz * drz[j]
        dny = ((1.0 - ny * ny) * dry[j] - ny * nz * drz[j]) / rho
        dnz = (-ny * nz * dry[j] + (1.0 - nz * nz) * drz[j]) / rho
        if slices:
            dt = 0.0
            if t > 0.0:
                if j == 2:
                    dt = thy / t
                elif j == 3:
                    dt = thz / t
            dP = Pp * dpen + Pt * dt
            dd = -((Sp * dpen + St * dt) * P_s - S * dP) / (P_s * P_s) if P_s > 0.0 else 0.0
            if corr:
                da = ca_p * dpen + ca_t * dt
                dd = eb * (dd + d_s * (cb_p * dpen + cb_t * dt - da))
                dP = ea * (dP + P_s * da)
        else:
            if partial:
                dt = 0.0
                if j == 2:
                    dt = thy / t
                elif j == 3:
                    dt = thz / t
                dl = dpen / t - pen / (t * t) * dt
            else:
                dl = 0.0
            dP = dl * hv + l * dh * dpen
            dd = -0.5 * dl
        dvn = vky * dny + vkz * dnz
        ddamp = 0.0 if clipped else p[8] * dvn
        dfy = -(dP * damp * ny + P * ddamp * ny + P * damp * dny)
        dfz = -(dP * damp * nz + P * ddamp * nz + P * damp * dnz)
        jac[0, j] += w * dfy
        jac[1, j] += w * dfz
        jac[2, j] += w * sgn * (dd * (-fz) + d * (-dfz))
        jac[3, j] += w * sgn * (dd * fy + d * dfy)
        # velocity columns: r_k-dot depends on (vy, vz, wy, wz) exactly as r_k on (y, z, thy, thz)
        dvn_v = ny * dry[j] + nz * drz[j]
        ddamp_v = 0.0 if clipped else p[8] * dvn_v
        dfy_v = -P * ddamp_v * ny
        dfz_v = -P * ddamp_v * nz
        jac[0, 4 + j] += w * dfy_v
        jac[1, 4 + j] += w * dfz_v
        jac[2, 4 + j] += w * sgn * d * (-dfz_v)
        jac[3, 4 + j] += w * sgn * d * dfy_v
    return fy, fz, sgn * d, 1


@numba.njit(cache=True)
def _evaluate(y, z, thy, thz, vy, vz, wy, wz, p, jac):
    """Total force and moment on the bearing; Jacobian into ``jac`` (4, 8) unless it is None.

    Returns ``(Fy, Fz, My, Mz, in_domain, state, penetration_1, penetration_2)``.
    """
    if jac is not None:
        for i in range(4):
            for j in range(8):
                jac[i, j] = 0.0
    d0 = p[0]
    h = 0.5 * p[1]
    tilt_ignored = p[11] != 0.0
    if tilt_ignored:
        thy = 0.0
        thz = 0.0
        wy = 0.0
        wz = 0.0
    t = math.sqrt(thy * thy + thz * thz)
    r1y = y + h * thz
    r1z = z - h * thy
    r2y = y - h * thz
    r2z = z + h * thy
    rho1 = math.sqrt(r1y * r1y + r1z * r1z)
    rho2 = math.sqrt(r2y * r2y + r2z * r2z)
    pen1 = rho1 - d0
    pen2 = rho2 - d0
    rr = math.sqrt(y * y + z * z)
    w1, w2, state, ds, dlam = selection(rr, pen1 + p[14], pen2 + p[14], d0 - p[14], p[13])
    Fy = 0.0
    Fz = 0.0
    My = 0.0
    Mz = 0.0
    ok = 1
    if w1 > 0.0:
        fy1, fz1, sd1, o = _edge(1.0, w1, r1y, r1z, rho1, vy, vz, wy, wz, thy, thz, t, p, jac)
        Fy += w1 * fy1
        Fz += w1 * fz1
        My += w1 * sd1 * (-fz1)
        Mz += w1 * sd1 * fy1
        ok &= o
    else:
        fy1 = fz1 = sd1 = 0.0
    if w2 > 0.0:
        fy2, fz2, sd2, o = _edge(-1.0, w2, r2y, r2z, rho2, vy, vz, wy, wz, thy, thz, t, p, jac)
        Fy += w2 * fy2
        Fz += w2 * fz2
        My += w2 * sd2 * (-fz2)
        Mz += w2 * sd2 * fy2
        ok &= o
    else:
        fy2 = fz2 = sd2 = 0.0
    if jac is not None and (ds != 0.0 or dlam != 0.0):
        # derivatives of the weights (regularised selection): Σ_k E_k ∂w_k/∂(y, z, θy, θz)
        c1 = 1.0 if pen1 + p[14] > 0.0 else 0.0
        c2 = 1.0 if pen2 + p[14] > 0.0 else 0.0
        s, _ds = _smooth_step(pen1 - pen2, 0.5 * p[13], 0.5)
        lam, _dl = _smooth_step(d0 - p[14] - 0.5 * p[13] - rr, 0.5 * p[13], 0.5)
        n1y = r1y / rho1 if rho1 > 0.0 else 0.0
        n1z = r1z / rho1 if rho1 > 0.0 else 0.0
        n2y = r2y / rho2 if rho2 > 0.0 else 0.0
        n2z = r2z / rho2 if rho2 > 0.0 else 0.0
        ey = y / rr if rr > 0.0 else 0.0
        ez = z / rr if rr > 0.0 else 0.0
        # ∂Δr1/∂u = (n1y, n1z, −h n1z, h n1y), ∂Δr2/∂u = (n2y, n2z, h n2z, −h n2y), ∂|r|/∂u = (ey, ez, 0, 0)
        dpd = (n1y - n2y, n1z - n2z, -h * (n1z + n2z), h * (n1y + n2y))
        drr = (ey, ez, 0.0, 0.0)
        for j in range(4):
            dl_j = -dlam * drr[j]
            dw1 = dl_j * (c1 - s) + (1.0 - lam) * ds * dpd[j]
            dw2 = dl_j * (c2 - 1.0 + s) - (1.0 - lam) * ds * dpd[j]
            jac[0, j] += fy1 * dw1 + fy2 * dw2
            jac[1, j] += fz1 * dw1 + fz2 * dw2
            jac[2, j] += sd1 * (-fz1) * dw1 + sd2 * (-fz2) * dw2
            jac[3, j] += sd1 * fy1 * dw1 + sd2 * fy2 * dw2
    a, b, c, d = _face_friction(1.0, vy, vz, wy, wz, p, jac)
    Fy += a
    Fz += b
    My += c
    Mz += d
    a, b, c, d = _face_friction(-1.0, vy, vz, wy, wz, p, jac)
    Fy += a
    Fz += b
    My += c
    Mz += d
    if tilt_ignored:
        My = 0.0
        Mz = 0.0
        if jac is not None:
            for i in range(4):
                for j in (2, 3, 6, 7):
                    jac[i, j] = 0.0
            for j in range(8):
                jac[2, j] = 0.0
                jac[3, j] = 0.0
    return Fy, Fz, My, Mz, ok, state, pen1, pen2


@numba.njit(cache=True)
def point_force(y, z, thy, thz, vy, vz, wy, wz, p):
    """Scalar path for a compiled step loop: ``(Fy, Fz, My, Mz)`` on the bearing (N, N·m).

    Allocation-free. Raises OutsideDomainError beyond the conformal law's neat-fit limit.
    """
    Fy, Fz, My, Mz, ok, state, pen1, pen2 = _evaluate(y, z, thy, thz, vy, vz, wy, wz, p, None)
    if ok == 0:
        raise OutsideDomainError("loose support: penetration beyond the conformal law's neat-fit limit D(b) <= 0")
    return Fy, Fz, My, Mz


@numba.njit(cache=True)
def point_force_jacobian(y, z, thy, thz, vy, vz, wy, wz, p, jac):
    """Like :func:`point_force`, and writes ∂(Fy,Fz,My,Mz)/∂(y,z,θy,θz,vy,vz,ωy,ωz) into ``jac`` (4, 8)."""
    Fy, Fz, My, Mz, ok, state, pen1, pen2 = _evaluate(y, z, thy, thz, vy, vz, wy, wz, p, jac)
    if ok == 0:
        raise OutsideDomainError("loose support: penetration beyond the conformal law's neat-fit limit D(b) <= 0")
    return Fy, Fz, My, Mz


@numba.njit(cache=True)
def many_points(y, z, thy, thz, vy, vz, wy, wz, p, want_jac, want_state, F, J, ok, state, pen):
    """Loop over 1-D arrays; fills F (n,4), J (n,4,8) if want_jac, ok/state (n,), pen (n,2) if want_state.

    Returns the index of the first non-finite input or first point outside the domain
    (-1 if none) and a code (0 fine, 1 non-finite, 2 outside domain).
    """
    n = y.shape[0]
    jac = np.empty((4, 8))
    first_bad = -1
    code = 0
    for i in range(n):
        a0 = y[i]; a1 = z[i]; a2 = thy[i]; a3 = thz[i]  # noqa: E702
        a4 = vy[i]; a5 = vz[i]; a6 = wy[i]; a7 = wz[i]  # noqa: E702
        if not math.isfinite(a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7):
            return i, 1
        if want_jac:
            fy, fz, my, mz, o, st, p1, p2 = _evaluate(a0, a1, a2, a3, a4, a5, a6, a7, p, jac)
            for r in range(4):
                for c in range(8):
                    J[i, r, c] = jac[r, c] if o != 0 else np.nan
        else:
            fy, fz, my, mz, o, st, p1, p2 = _evaluate(a0, a1, a2, a3, a4, a5, a6, a7, p, None)
        if o == 0:
            if first_bad < 0:
                first_bad = i
                code = 2
            fy = np.nan
            fz = np.nan
            my = np.nan
            mz = np.nan
        F[i, 0] = fy
        F[i, 1] = fz
        F[i, 2] = my
        F[i, 3] = mz
        if want_state:
            ok[i] = o != 0
            state[i] = st
            pen[i, 0] = p1
            pen[i, 1] = p2
    return first_bad, code


@numba.njit(cache=True, parallel=True)
def many_points_parallel(y, z, thy, thz, vy, vz, wy, wz, p, want_state, F, status, state, pen):
    """Multi-threaded :func:`many_points` without Jacobian: ``status[i]`` 0 fine, 1 non-finite, 2 outside."""
    n = y.shape[0]
    for i in numba.prange(n):
        a0 = y[i]; a1 = z[i]; a2 = thy[i]; a3 = thz[i]  # noqa: E702
        a4 = vy[i]; a5 = vz[i]; a6 = wy[i]; a7 = wz[i]  # noqa: E702
        if not math.isfinite(a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7):
            status[i] = 1
            F[i, 0] = np.nan
            F[i, 1] = np.nan
            F[i, 2] = np.nan
            F[i, 3] = np.nan
            continue
        fy, fz, my, mz, o, st, p1, p2 = _evaluate(a0, a1, a2, a3, a4, a5, a6, a7, p, None)
        if o == 0:
            status[i] = 2
            fy = np.nan
            fz = np.nan
            my = np.nan
            mz = np.nan
        else:
            status[i] = 0
        F[i, 0] = fy
        F[i, 1] = fz
        F[i, 2] = my
        F[i, 3] = mz
        if want_state:
            state[i] = st
            pen[i, 0] = p1
            pen[i, 1] = p2
