"""Linear steady-state forced response to the unbalance (1X) and misalignment (2X) loads.

For a harmonic load ``f(t) = Re(f̂ e^{i n Ω t})`` the steady state is ``q = Re(q̂ e^{i n Ω t})``
with ``[K_total − (nΩ)² M + i nΩ (C − Ω G)] q̂ = f̂`` on the constraint null space (loose
support locked, transition-shaft spring linear ``a0``). The misalignment offset ``Δq_m`` only
adds a static deflection and is not part of these harmonic amplitudes.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
from rotor.model.assembly import RotorModel, constraint_basis, harmonic_loads
from rotor.model.topology import require_ground


@dataclass(frozen=True)
class ForcedResponse:
    """Complex amplitudes ``q̂`` (m, rad) of harmonic ``order`` at each speed.

    ``amplitudes[i, j]``: DOF ``j`` at ``speeds_rad_s[i]``; the physical response is
    ``Re(q̂ e^{i·order·Ω t})``.
    """

    order: int
    speeds_rad_s: np.ndarray
    amplitudes: np.ndarray

    def orbit(self, model: RotorModel, node: str) -> tuple[np.ndarray, np.ndarray]:
        """Semi-major and semi-minor axes (m) of the orbit of ``node`` at every speed.

        With ``y + i z = a_f e^{iωt} + a_b e^{−iωt}``, ``a_f = (ŷ + iẑ)/2``, ``a_b = conj(ŷ − iẑ)/2``,
        the ellipse has semi-axes ``|a_f| + |a_b|`` and ``||a_f| − |a_b||``.
        """
        iy, iz = model.dof_index(f"{node}.y"), model.dof_index(f"{node}.z")
        Y, Z = self.amplitudes[:, iy], self.amplitudes[:, iz]
        af, ab = np.abs(Y + 1j * Z) / 2, np.abs(Y - 1j * Z) / 2
        return af + ab, np.abs(af - ab)


def forced_response(model: RotorModel, speeds_rad_s, *, order: int = 1, lock_loose_support: bool = True) -> ForcedResponse:
    """Steady-state response to the ``order``-th harmonic load of :func:`rotor.model.assembly.harmonic_loads`.

    ``order = 1``: unbalance and skew (Dai et al. 2025, Eqs. 39–40); ``order = 2``: misalignment
    excitation (Eq. 34).
    """
    if order not in (1, 2):
        raise InputError(f"order = {order}: must be 1 (unbalance) or 2 (misalignment)")
    speeds = np.atleast_1d(np.asarray(speeds_rad_s, dtype=float))
    if not np.all(np.isfinite(speeds)) or np.any(speeds < 0):
        raise InputError("speeds_rad_s: must be finite and >= 0 rad/s")
    require_ground(model, "the forced response", lock_loose_support=lock_loose_support)
    T = constraint_basis(model, lock_loose_support=lock_loose_support)
    M, C, G, K = (T.T @ X @ T for X in (model.M, model.C, model.G, model.K_total))
    out = np.zeros((len(speeds), model.n_dofs), complex)
    for i, w in enumerate(speeds):
        if model.speed_bearings:                   # bearings with a speed table: K and C at this speed
            at_w = model.at_speed(w)
            C, K = T.T @ at_w.C @ T, T.T @ at_w.K_total @ T
        a, b = harmonic_loads(model, w)[order]
        fhat = a - 1j * b                      # a cos + b sin = Re((a − i b) e^{iωt})
        nw = order * w
        D = K - nw ** 2 * M + 1j * nw * (C - w * G)
        try:
            u = np.linalg.solve(D, T.T @ fhat)
        except np.linalg.LinAlgError:
            raise InputError(f"forced response singular at {w * 30 / math.pi:.3f} rpm (undamped resonance); "
                             f"add damping or move the speed") from None
        out[i] = T @ u
    return ForcedResponse(order=order, speeds_rad_s=speeds, amplitudes=out)
