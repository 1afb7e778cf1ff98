"""The loose support's contact force and end-face stick in a recorded trajectory: named columns and a summary.

What a :class:`~rotor.dynamics.system.Trajectory` records about the support (both schemes, every recorded
sample; the production scheme evaluates them in :func:`rotor.dynamics.production_loop.step_loop`, the
reference scheme in :func:`rotor.dynamics.system.support_forces`):

* ``f_contact`` (N, 4) = ``(Fy, Fz, My, Mz)``: the radial contact force (N) and moment (N m) that the
  support's bore exerts **on the bearing outer ring**; the support receives the opposite. It is the
  support law (:func:`contact.loose_support.loose_support_force` with the end-face friction removed,
  :func:`rotor.dynamics.kernels.support_law_from_params`) at the recorded relative state ``u = B q``
  (bearing minus support: y, z in m, θy, θz in rad) and its rate ``w = B v`` (m/s, rad/s), damping
  included. Frame: the rotor's stationary (non-rotating) axes, x along the shaft, y and z lateral.
  The force points from the contact towards the bore's centre (``−P r_k/|r_k|``: it pushes the ring back
  into the clearance); the moment is about the bearing node, the ring's mid-plane: a force
  ``(Fy, Fz)`` at axial position x gives ``My = −x Fz``, ``Mz = +x Fy``.
* ``face_force`` (N, 2, 2): the end-face friction force on the bearing, ``[right (x = +l0/2), left
  (x = −l0/2)][y, z]`` (N): a stuck face's constraint force, a slipping face's ``μN`` against its slip.
  With the tilt ignored (Dai et al. 2025 §5.2) the first slot is the one centred face (limit ``2μN``)
  and the second is unused.
* ``modes`` (N, 2): 1 = the face sticks, 0 = it slips (right, left).

The kernel gives the edges' sum only (with the smooth edge selection, :mod:`contact.loose_support`), so no
per-edge force is recorded; the edge offsets ``r1``, ``r2`` say which edge is past the clearance.
"""
from __future__ import annotations

import numpy as np

from rotor.dynamics import constraints as cons

#: one sentence on the sign convention, written into run summaries beside the fields it explains
CONVENTION = ("contact_force_* / contact_moment_*: radial contact force (N) and moment (N m) of the support's bore "
              "ON the bearing outer ring (the support gets the opposite), stationary rotor axes (x along the shaft), "
              "moment about the ring's mid-plane (My = -x Fz, Mz = +x Fy), pointing from the contact towards the "
              "bore's centre; face_*_force_*: end-face friction on the bearing (N), right face at x = +l0/2; "
              "*_stuck / stick_share_*: 1 = the face sticks; shares are fractions of the recorded samples")


def contact_columns(f_contact, face_force=None, modes=None) -> dict:
    """Named columns (SI, unit in the name) of the recorded support force, face forces and face modes.

    Parameters
    ----------
    f_contact : (N, 4) array
        ``(Fy, Fz, My, Mz)`` on the bearing (N, N m), :class:`~rotor.dynamics.system.Trajectory`.
    face_force : (N, 2, 2) array or None
        End-face friction force on the bearing ``[right, left][y, z]`` (N).
    modes : (N, 2) array or None
        1 stick / 0 slip (right, left).

    Returns
    -------
    dict
        ``contact_force_y_N``, ``contact_force_z_N``, ``contact_force_N`` (magnitude of the radial force),
        ``contact_moment_y_Nm``, ``contact_moment_z_Nm``, ``contact_moment_Nm`` (magnitude), and with
        ``face_force`` ``face_right_force_y_N`` … ``face_left_force_z_N``, with ``modes``
        ``face_right_stuck``, ``face_left_stuck`` (0/1).
    """
    fc = np.asarray(f_contact, dtype=float)
    cols = {"contact_force_y_N": fc[:, 0], "contact_force_z_N": fc[:, 1],
            "contact_force_N": np.hypot(fc[:, 0], fc[:, 1]),
            "contact_moment_y_Nm": fc[:, 2], "contact_moment_z_Nm": fc[:, 3],
            "contact_moment_Nm": np.hypot(fc[:, 2], fc[:, 3])}
    if face_force is not None:
        ff = np.asarray(face_force, dtype=float)
        for k, side in enumerate(("right", "left")):
            cols[f"face_{side}_force_y_N"] = ff[:, k, 0]
            cols[f"face_{side}_force_z_N"] = ff[:, k, 1]
    if modes is not None:
        m = np.asarray(modes)
        cols["face_right_stuck"] = (m[:, 0] == cons.STICK).astype(int)
        cols["face_left_stuck"] = (m[:, 1] == cons.STICK).astype(int)
    return cols


def contact_summary(t_s, f_contact, modes, face_force=None, n_faces: int = 2) -> dict:
    """How hard and how often the ring hits its support, and how long each end face sticks, over a record.

    Parameters
    ----------
    t_s : (N,) array
        Sample times (s).
    f_contact : (N, 4) array
        ``(Fy, Fz, My, Mz)`` on the bearing (N, N m), as :func:`contact_columns` reads it.
    modes : (N, 2) array
        1 stick / 0 slip (right, left).
    face_force : (N, 2, 2) array or None
        End-face friction force on the bearing (N); None leaves ``peak_face_force_N`` out.
    n_faces : int
        Active end faces (1 with the tilt ignored: the centred face is reported as the right one and
        ``stick_share_left_face`` is None).

    Returns
    -------
    dict
        ``peak_contact_force_N`` (largest radial force magnitude, N) at ``peak_contact_force_t_s`` (s, None
        without contact), ``mean_contact_force_N`` (mean magnitude over the samples in contact, N; None without
        contact), ``peak_contact_moment_Nm`` (N m), ``contact_share`` (fraction of the samples with a radial
        force: an edge past the clearance and the Lankarani–Nikravesh factor not clipped to zero),
        ``separation_share`` (``1 − contact_share``: the ring clear of the bore), ``stick_share_right_face``,
        ``stick_share_left_face`` (fractions of the samples the face sticks) and, with ``face_force``,
        ``peak_face_force_N`` (largest end-face friction force of a face, N; a stuck face's constraint force
        may pass ``μN`` at a recorded step, the stick test bounding the step's mean force).
        Shares and peaks are over the samples given: a peak between two recorded samples is not seen.
    """
    fc = np.asarray(f_contact, dtype=float)
    t = np.asarray(t_s, dtype=float)
    m = np.asarray(modes)
    force = np.hypot(fc[:, 0], fc[:, 1])
    touching = (force > 0.0) | (np.hypot(fc[:, 2], fc[:, 3]) > 0.0)
    i = int(np.argmax(force)) if force.size else 0
    hit = bool(touching.any())
    share = float(touching.mean()) if force.size else 0.0
    out = {"peak_contact_force_N": float(force[i]) if force.size else 0.0,
           "peak_contact_force_t_s": float(t[i]) if hit else None,
           "mean_contact_force_N": float(force[touching].mean()) if hit else None,
           "peak_contact_moment_Nm": float(np.hypot(fc[:, 2], fc[:, 3]).max()) if force.size else 0.0,
           "contact_share": share, "separation_share": 1.0 - share,
           "stick_share_right_face": float((m[:, 0] == cons.STICK).mean()) if n_faces >= 1 else None,
           "stick_share_left_face": float((m[:, 1] == cons.STICK).mean()) if n_faces >= 2 else None}
    if face_force is not None:
        ff = np.asarray(face_force, dtype=float)
        out["peak_face_force_N"] = float(np.hypot(ff[..., 0], ff[..., 1]).max()) if ff.size else 0.0
    return out
