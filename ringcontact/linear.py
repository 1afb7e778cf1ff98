"""Linear analyses of a rotor scene: natural frequencies, Campbell diagram, unbalance response.

The loose support, if the scene has one, is locked (bearing and support move together, both end faces stuck)
unless ``lock_loose_support=False``. Each function takes a :class:`ringcontact.Scene`, a scene file's path or a
bundled scene's name, and calls the functions the ``ringcontact rotor`` job calls (:mod:`rotor.linear.modes`,
:mod:`rotor.linear.unbalance`), so the numbers are the job's.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
import ringcontact._checks as _checks
from ringcontact.results import ResultMethods, internal
from ringcontact.scene import as_scene

RAD_S_PER_RPM = math.pi / 30.0


def _model(scene, elements: int | None):
    from rotor.model.assembly import assemble
    if elements is not None:
        _checks.whole("elements", elements, "--elements", "elements")
    sc = as_scene(scene)
    return sc, assemble(sc, elements_per_segment=elements)


def _n_modes(n_modes, sc) -> int:
    """``n_modes`` (None: the scene's ``[analysis] modes``) in the range of ``rotor modes --modes``."""
    return sc.analysis.modes if n_modes is None else _checks.whole("n_modes", n_modes, "--modes", "modes")


def _speeds_rpm(rpm, name: str = "rpm") -> np.ndarray:
    """1 to ``COUNTS["speeds"]`` speeds (``rotor campbell --points``), each in the range of ``--speed-rpm``."""
    return _checks.speed_list(name, rpm, "--speed-rpm", "speed_rpm", "speeds")


def _campbell_budget(func: str, model, speeds, accept_long) -> None:
    """The eigenproblems of ``rotor campbell`` against the jobs' budget (:func:`reports.cli._budget.campbell`)."""
    from reports.cli import _budget
    _checks.budget(func, _budget.campbell(model.n_dofs, len(speeds)), accept_long,
                   f"rpm: {len(speeds)} speeds of a {model.n_dofs}-DOF model", "fewer speeds or elements")


@dataclass(frozen=True)
class ModesResult(ResultMethods):
    """Whirl modes at one speed.

    Attributes
    ----------
    scene : str
        The scene's name.
    speed_rpm : float
        Spin speed (rpm).
    frequency_rad_s, frequency_hz : numpy.ndarray
        (k,) whirl frequencies, lowest first (rad/s; Hz).
    damping_ratio : numpy.ndarray
        (k,) ζ (0 for undamped modes).
    forward_fraction : numpy.ndarray
        (k,) share of forward whirl (–).
    whirl : tuple of str
        ``forward``, ``backward`` or ``mixed`` per mode.
    dof_names : tuple of str
        The model's degrees of freedom (``<node>.y`` …), the rows of ``shapes``.
    shapes : numpy.ndarray
        (n, k) complex mode shapes, largest lateral amplitude 1.
    """

    scene: str
    speed_rpm: float
    frequency_rad_s: np.ndarray
    frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    forward_fraction: np.ndarray
    whirl: tuple
    dof_names: tuple
    shapes: np.ndarray
    model: object = internal()
    modes: object = internal()
    _dim = "mode"

    def _rows(self) -> list[dict]:
        return [{"mode": j + 1, "frequency_rad_s": self.frequency_rad_s[j], "frequency_hz": self.frequency_hz[j],
                 "whirl": self.whirl[j], "forward_fraction": self.forward_fraction[j],
                 "damping_ratio": self.damping_ratio[j]} for j in range(len(self.frequency_hz))]

    def _draw(self, ax) -> None:
        from reports.rotor_plots import mode_shape_figure
        picks = [(f"mode {j + 1}: {self.frequency_rad_s[j]:.2f} rad/s, {self.whirl[j]}", self.modes, j)
                 for j in range(min(6, len(self.frequency_hz)))]
        mode_shape_figure(self.model, picks, f"Mode shapes at {self.speed_rpm:g} rpm: {self.scene}", ax=ax)


def modes(scene, speed_rpm: float = 0.0, *, n_modes: int | None = None, damped: bool = False,
          lock_loose_support: bool = True, elements: int | None = None) -> ModesResult:
    """Whirl frequencies and mode shapes at ``speed_rpm`` (rpm), as ``ringcontact rotor modes``.

    Parameters
    ----------
    scene : ringcontact.Scene or str
        The scene, a scene file's path or a bundled scene's name.
    speed_rpm : float
        Spin speed (rpm, >= 0).
    n_modes : int or None
        Modes kept (None: the scene's ``[analysis] modes``).
    damped : bool
        Include the viscous damping (damped frequencies and ζ).
    lock_loose_support : bool
        Join the loose support's bearing and support (default) or leave them unconnected.
    elements : int or None
        Elements per shaft segment (None: the scene's mesh).
    """
    from rotor.linear.modes import modes as solve
    speed_rpm = _checks.number("speed_rpm", speed_rpm, "--speed-rpm", "speed_rpm", si_unit="rpm")
    damped = _checks.flag_of("damped", damped)
    lock_loose_support = _checks.flag_of("lock_loose_support", lock_loose_support)
    sc, model = _model(scene, elements)
    res = solve(model, speed_rpm * RAD_S_PER_RPM, n_modes=_n_modes(n_modes, sc),
                lock_loose_support=lock_loose_support, damped=damped)
    return ModesResult(sc.name, float(speed_rpm), res.frequency_hz * 2 * math.pi, res.frequency_hz,
                       res.damping_ratio, res.forward_fraction, res.whirl, tuple(model.dof_names), res.shapes,
                       model, res)


@dataclass(frozen=True)
class CampbellResult(ResultMethods):
    """Whirl frequencies over speed: ``frequency_rad_s[i, j]``, mode j at ``speeds_rpm[i]`` (NaN where a speed
    has fewer modes), ``whirl[i][j]`` its direction, ``damping_ratio[i, j]`` its ζ."""

    scene: str
    speeds_rpm: np.ndarray
    frequency_rad_s: np.ndarray
    frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    whirl: tuple
    campbell: object = internal()
    _dim = "speed"

    def _rows(self) -> list[dict]:
        return [{"speed_rpm": s, "frequency_rad_s": list(self.frequency_rad_s[i]), "whirl": list(self.whirl[i]),
                 "damping_ratio": list(self.damping_ratio[i])} for i, s in enumerate(self.speeds_rpm)]

    def _draw(self, ax) -> None:
        from reports.rotor_plots import campbell_figure
        campbell_figure(self.campbell, f"Campbell diagram: {self.scene}", ax=ax)


def campbell(scene, rpm, *, n_modes: int | None = None, damped: bool = False, lock_loose_support: bool = True,
             elements: int | None = None, accept_long: bool = False) -> CampbellResult:
    """Whirl frequencies at every speed of ``rpm`` (rpm), as ``ringcontact rotor campbell``.

    The speeds (at most as many as ``--points`` takes) and the eigenproblems' work are checked as the job checks
    them; work beyond the jobs' budget is refused unless ``accept_long`` (the job's ``--accept-long``).
    """
    from rotor.linear.modes import campbell as solve
    speeds = _speeds_rpm(rpm)
    damped = _checks.flag_of("damped", damped)
    lock_loose_support = _checks.flag_of("lock_loose_support", lock_loose_support)
    sc, model = _model(scene, elements)
    n = _n_modes(n_modes, sc)
    _campbell_budget("campbell", model, speeds, accept_long)
    c = solve(model, speeds * RAD_S_PER_RPM, n_modes=n, lock_loose_support=lock_loose_support, damped=damped)
    return CampbellResult(sc.name, speeds, c.frequency_hz * 2 * math.pi, c.frequency_hz, c.damping_ratio, c.whirl, c)


@dataclass(frozen=True)
class UnbalanceResult(ResultMethods):
    """Steady linear response to the unbalance (order 1) or the misalignment (order 2) at each speed.

    ``semi_major_m[i, k]`` / ``semi_minor_m[i, k]``: orbit semi-axes (m) of ``stations[k]`` at ``speeds_rpm[i]``;
    ``amplitude_y_m``, ``phase_y_deg``, ``amplitude_z_m``, ``phase_z_deg``: the y and z motion
    ``A cos(order Ω t + φ)`` (m, degrees).
    """

    scene: str
    order: int
    speeds_rpm: np.ndarray
    stations: tuple
    semi_major_m: np.ndarray
    semi_minor_m: np.ndarray
    amplitude_y_m: np.ndarray
    phase_y_deg: np.ndarray
    amplitude_z_m: np.ndarray
    phase_z_deg: np.ndarray
    model: object = internal()
    response: object = internal()
    _dim = "speed"

    def _rows(self) -> list[dict]:
        rows = []
        for i, s in enumerate(self.speeds_rpm):
            row = {"speed_rpm": s}
            for k, st in enumerate(self.stations):
                row.update({f"{st}_semi_major_m": self.semi_major_m[i, k], f"{st}_semi_minor_m": self.semi_minor_m[i, k],
                            f"{st}_phase_y_deg": self.phase_y_deg[i, k]})
            rows.append(row)
        return rows

    def _draw(self, ax) -> None:
        from reports.rotor_plots import response_figure
        what = "unbalance" if self.order == 1 else "misalignment"
        response_figure(self.model, self.response, list(self.stations),
                        f"Linear {what} response ({self.order}X): {self.scene}", ax=ax)


def unbalance_response(scene, rpm, *, stations=None, order: int = 1, lock_loose_support: bool = True,
                       elements: int | None = None) -> UnbalanceResult:
    """Steady response to the disks' unbalance (``order`` 1) or to the misalignment (2) at each speed of ``rpm``,
    as ``ringcontact rotor unbalance``; ``stations``: names of stations, disks, bearings or supports (default
    the disks, else the first station)."""
    from rotor.linear.unbalance import forced_response
    speeds = _speeds_rpm(rpm)
    if isinstance(order, bool) or order not in (1, 2):
        raise InputError(f"order = {order!r}, i.e. --order = {order}: must be 1 (unbalance) or 2 (misalignment)")
    lock_loose_support = _checks.flag_of("lock_loose_support", lock_loose_support)
    sc, model = _model(scene, elements)
    if isinstance(stations, str):
        stations = [stations]
    names = tuple(stations or [d.name for d in sc.disks] or [sc.stations[0].name])
    for n in names:
        model.node_of(n)              # an unknown name: one InputError naming it, before any solving
    resp = forced_response(model, speeds * RAD_S_PER_RPM, order=order, lock_loose_support=lock_loose_support)
    shape = (len(speeds), len(names))
    major, minor, ay, py, az, pz = (np.zeros(shape) for _ in range(6))
    for k, n in enumerate(names):
        node = model.node_of(n)
        major[:, k], minor[:, k] = resp.orbit(model, n)
        y, z = resp.amplitudes[:, model.dof_index(f"{node}.y")], resp.amplitudes[:, model.dof_index(f"{node}.z")]
        ay[:, k], py[:, k], az[:, k], pz[:, k] = np.abs(y), np.degrees(np.angle(y)), np.abs(z), np.degrees(np.angle(z))
    return UnbalanceResult(sc.name, int(order), speeds, names, major, minor, ay, py, az, pz, model, resp)
