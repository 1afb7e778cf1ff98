"""Exact steady state of Den Hartog's (1931) oscillator with Coulomb and viscous damping.

    m ẍ + c ẋ + k x + F sgn(ẋ) = P0 cos(ω t)

Den Hartog (1931, "Forced vibrations with combined Coulomb and viscous friction",
Trans. ASME APM-53-9) builds the steady state from the closed-form solution of the
linear ODE on each half cycle of one-signed velocity, with the symmetry
``x(t + T/2) = −x(t)``, including motions with a stop (stick) at the extremes. This module
does the same: closed-form piecewise solutions, joined by root finding on the two
unknowns (start of the upward slip ``t_b`` and amplitude ``X0``). No time stepping.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq, fsolve


class DenHartog:
    def __init__(self, m, c, k, F, P0, omega):
        self.m, self.c, self.k, self.F, self.P0, self.w = m, c, k, F, P0, omega
        self.H = 1.0 / (k - m * omega ** 2 + 1j * c * omega)
        self.sig = c / (2 * m)
        self.wd = math.sqrt(k / m - self.sig ** 2)
        self.T = 2 * math.pi / omega

    def _xp(self, t, s):
        e = self.P0 * self.H * np.exp(1j * self.w * t)
        return e.real - s * self.F / self.k, (1j * self.w * e).real

    def slip(self, tb, x0, s, t):
        """Closed-form x, ẋ at times t >= tb of a slip phase with velocity sign s from rest at x0."""
        xp0, vp0 = self._xp(tb, s)
        C1 = x0 - xp0
        C2 = (0.0 - vp0 + self.sig * C1) / self.wd
        tau = np.asarray(t) - tb
        e = np.exp(-self.sig * tau)
        cs, sn = np.cos(self.wd * tau), np.sin(self.wd * tau)
        xh = e * (C1 * cs + C2 * sn)
        vh = e * (-self.sig * (C1 * cs + C2 * sn) + self.wd * (-C1 * sn + C2 * cs))
        xp, vp = self._xp(np.asarray(t), s)
        return xp + xh, vp + vh

    def half_cycle(self, ts, X):
        """Half-cycle map: at rest at x = −X from time ts; stuck until the net force
        P0 cos ωt + kX reaches F, then slides upward until ẋ = 0.
        Returns (t_b breakaway, t_c stop, x_c)."""
        net = lambda t: self.P0 * math.cos(self.w * t) + self.k * X - self.F
        if net(ts) >= 0:
            tb = ts
        else:
            tt = ts + np.linspace(0, self.T, 4001)
            vals = self.P0 * np.cos(self.w * tt) + self.k * X - self.F
            j = np.nonzero(vals >= 0)[0]
            if j.size == 0:
                raise RuntimeError("permanent stick: P0 too small against F")
            tb = brentq(net, tt[j[0] - 1], tt[j[0]], xtol=1e-15, rtol=1e-15)
        tgrid = tb + np.linspace(0, self.T, 8001)[1:]
        _, v = self.slip(tb, -X, +1.0, tgrid)
        idx = np.nonzero(v < 0)[0]
        i = idx[0]
        lo = tgrid[i - 1] if i > 0 else tb + 1e-12
        tc = brentq(lambda t: self.slip(tb, -X, 1.0, t)[1], lo, tgrid[i], xtol=1e-15, rtol=1e-15)
        xc = float(self.slip(tb, -X, 1.0, tc)[0])
        return tb, tc, xc

    def steady_state(self):
        """Amplitude X0 (m), stop instant ts (s, mod T), stick time per half cycle (s).

        Iterates the exact half-cycle map (symmetry: a downward half cycle from (t, x) is
        the negative of an upward one from (t − T/2, −x)) to its fixed point, then polishes
        the fixed point with fsolve."""
        X = abs(self.P0 * self.H)
        ts = 0.0
        for _ in range(200):
            tb, tc, xc = self.half_cycle(ts, X)
            ts, X = tc - self.T / 2, xc

        def eqs(z):
            tb, tc, xc = self.half_cycle(z[0], z[1])
            return [(tc - self.T / 2 - z[0]) / self.T, (xc - z[1]) / z[1]]

        sol = fsolve(eqs, [ts, X], xtol=1e-14)
        if max(abs(v) for v in eqs(sol)) > 1e-10:
            raise RuntimeError("Den Hartog steady state: fixed point not found")
        ts, X = sol
        tb, tc, xc = self.half_cycle(ts, X)
        return X, ts % self.T, tb - ts
