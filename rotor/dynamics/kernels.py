"""The contact law as the integrators call it: a :class:`~rotor.dynamics.system.SupportLaw` from the
contact layer's :class:`contact.loose_support.LooseSupportParams`, with its compiled kernel.

:func:`support_law_from_params` gives both forms of the radial law: the Python ``force`` the
reference scheme evaluates (and its finite-difference Jacobian), and :func:`contact_kernel`, the
numba-compiled scalar path of :mod:`contact.loose_support` with its analytic Jacobian, which
the production scheme (:mod:`rotor.dynamics.production`) calls inside its compiled step loop.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numba import njit

from contact.compiled_cache import compiled_with
from contact.errors import InputError
from contact.loose_support import N_PARAMS, loose_support_force, point_force_jacobian
from rotor.dynamics.system import SupportLaw

# contact_kernel inlines contact._kernel: its cache entries are stale when that source changes too
# (numba itself only watches this file).
compiled_with(__file__, ["contact._kernel", "contact._kernel_friction", "contact._kernel_tilt"])


assert N_PARAMS == 88, "law_tuple spells out every slot of contact._kernel's parameter tuple"


@njit(cache=True, inline="always")
def law_tuple(p):
    """The law's parameter array (N_PARAMS,) as the tuple :func:`contact.loose_support.point_force_jacobian` takes
    (a calibrated spline law's knots in slots 15 on, ``contact._kernel``)."""
    return (p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9], p[10], p[11], p[12], p[13], p[14], p[15],
            p[16], p[17], p[18], p[19], p[20], p[21], p[22], p[23], p[24], p[25], p[26], p[27], p[28], p[29], p[30],
            p[31], p[32], p[33], p[34], p[35], p[36], p[37], p[38], p[39], p[40], p[41], p[42], p[43], p[44], p[45],
            p[46], p[47], p[48], p[49], p[50], p[51], p[52], p[53], p[54], p[55], p[56], p[57], p[58], p[59], p[60],
            p[61], p[62], p[63], p[64], p[65], p[66], p[67], p[68], p[69], p[70], p[71], p[72], p[73], p[74], p[75],
            p[76], p[77], p[78], p[79], p[80], p[81], p[82], p[83], p[84], p[85], p[86], p[87])


@njit(cache=True, inline="always")
def contact_point(y, z, thy, thz, vy, vz, wy, wz, p, jac):
    """The law at one relative state (m, rad; m/s, rad/s) writing ``∂f/∂(u, v)`` into ``jac`` (4, 8): returns
    ``(Fy, Fz, My, Mz)`` (N, N m). The step loop's form of :func:`contact_kernel` (nothing allocated)."""
    return point_force_jacobian(y, z, thy, thz, vy, vz, wy, wz, law_tuple(p), jac)


@njit(cache=True, inline="always")
def contact_point_jacobian(u, v, p, jac):
    """:func:`contact_point` at ``u[:4], v[:4]`` (longer arrays allowed)."""
    return contact_point(u[0], u[1], u[2], u[3], v[0], v[1], v[2], v[3], p, jac)


@njit(cache=True)
def contact_kernel(u, v, p):
    """``contact.loose_support`` scalar path as ``(u, v, params) -> (f, Ju, Jv)`` (analytic Jacobian)."""
    jac = np.empty((4, 8))
    fy, fz, my, mz = contact_point_jacobian(u, v, p, jac)
    f = np.empty(4)
    f[0] = fy
    f[1] = fz
    f[2] = my
    f[3] = mz
    return f, jac[:, :4].copy(), jac[:, 4:].copy()


def support_law_from_params(params) -> SupportLaw:
    """Wrap :class:`contact.loose_support.LooseSupportParams` as a :class:`SupportLaw`.

    End-face friction is removed from the law (μN = 0 in its kernel arguments): the
    integrators treat the faces as stick/slip constraints themselves. Everything else
    (law, modulus, damping ``c_c`` in s/m, tilt geometry or ``tilt_ignored``) is the
    contact layer's.
    """
    radial = dataclasses.replace(params, mu=0.0, preload_N=0.0, friction_smoothing_m_s=0.0)
    if len(radial.kernel_args) != N_PARAMS:
        raise InputError(f"law {getattr(params, 'calibration_name', '') or params.law!r} has a tilt correction "
                         f"({len(radial.kernel_args)} kernel slots, contact._kernel_tilt): the rotor's step loop "
                         f"takes laws of {N_PARAMS} slots only, so it would drop the correction; use the law without it")

    def force(u, v):
        r = loose_support_force(radial, u[0], u[1], u[2], u[3], v[0], v[1], v[2], v[3])
        return np.array([float(r.Fy_N), float(r.Fz_N), float(r.My_Nm), float(r.Mz_Nm)])

    law_label = getattr(params, "calibration_name", "") or params.law  # calibrated laws by their stored name
    name = f"{law_label}{' (tilt ignored)' if params.tilt_ignored else ''}"
    return SupportLaw(name, float(params.clearance_m), force, contact_kernel, np.array(radial.kernel_args, dtype=float),
                      bool(params.tilt_ignored))
