"""How far a stuck loose support is from slipping: the end faces' force demand of the locked steady state.

While both end faces stick, the bearing and its support move as one body (Dai et al. 2025 §3: "the support moves
together with the rotor"), the rotor is linear apart from the transition shaft's cubic spring, and the faces carry
what the support's own dynamics need: ``F = M_s q̈_s + D_s q̇_s + K_s (q_s − Δq_s) − Q_s`` on the support node's
four DOFs (force y, z and moment θy, θz), split over the two faces by
:func:`rotor.dynamics.constraints.face_force_demand`. A face slips once its demand reaches ``μN``
(:class:`rotor.dynamics.system.LooseSupport`), and the ring can meet the bore (``r > δ0``) only after a face
slipped: while stuck the relative motion ``u`` is zero. :func:`stick_margin` computes the largest demand over a
period of the locked steady state (:func:`rotor.dynamics.linear_response.periodic_response`, exact harmonics;
the transition shaft's cubic remainder left out) over ``μN``: below 1 the faces cannot slip in that steady state,
whatever the clearance. The Section 6 study scans it over the paper's stated rig data
(rotor/studies/testrig_scan.py).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class StickMargin:
    """The stuck state's end-face demand at one operating point.

    Attributes
    ----------
    peak_face_force_N : float
        Largest force (N) either face must carry over a period of the locked steady state.
    static_face_force_N : float
        The same of the static part alone (N): the misalignment offset's load.
    limit_N : float
        A face's friction limit ``μN`` (N).
    """

    peak_face_force_N: float
    static_face_force_N: float
    limit_N: float

    @property
    def ratio(self) -> float:
        """Peak demand over the friction limit (–): the faces slip somewhere in the period when ≥ 1."""
        return self.peak_face_force_N / self.limit_N if self.limit_N > 0 else math.inf


def support_load(system, n_samples: int = 256) -> tuple[np.ndarray, np.ndarray]:
    """``(t (n,), F (n, 4))``: the load the faces pass to the support node (N, N, N m, N m on y, z, θy, θz) over one
    revolution of the locked steady state of ``system`` (its support locked to the bearing)."""
    from rotor.dynamics.linear_response import locked_system, periodic_response

    sup = system.support
    if sup is None or sup.support_dofs is None:
        raise ValueError("stick_margin: the system has no loose support on a support node")
    omega = system.omega_rad_s
    t = np.arange(n_samples) * (2 * math.pi / omega) / n_samples
    q, v = periodic_response(system, t)
    k = np.fft.rfftfreq(n_samples, d=1.0 / n_samples)                  # orders of Ω
    a = np.fft.irfft(np.fft.rfft(v, axis=0) * (1j * k * omega)[:, None], n=n_samples, axis=0)
    lin = locked_system(system)
    s = list(sup.support_dofs)
    f = lin.force
    ph = np.outer(t, f.orders * f.omega_rad_s)
    Q = f.static[s] + np.cos(ph) @ f.cos[:, s] + np.sin(ph) @ f.sin[:, s]
    F = a @ lin.M[s].T + v @ lin.D[s].T + (q - lin.offset) @ lin.K[s].T - Q
    return t, F


def stick_margin(system, n_samples: int = 256) -> StickMargin:
    """:class:`StickMargin` of ``system`` (a :class:`rotor.dynamics.system.RotorSystem` with a loose support)."""
    from rotor.dynamics.constraints import face_force_demand

    sup = system.support
    _, F = support_load(system, n_samples)
    peak = 0.0
    for row in F:
        r, left = face_force_demand(row[:2], row[2:], sup.width_m)
        peak = max(peak, float(np.hypot(*r)), float(np.hypot(*left)))
    mean = F.mean(axis=0)
    r, left = face_force_demand(mean[:2], mean[2:], sup.width_m)
    return StickMargin(peak, max(float(np.hypot(*r)), float(np.hypot(*left))), float(sup.mu_N))
