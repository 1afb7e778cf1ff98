"""A rotor study's result directory as one labelled dataset: speed x station x direction x harmonic.

:func:`to_xarray` reads the verified points of a sweep (a damaged or missing one is refused by
name, see :func:`sweep.load_sweep`) into an ``xarray.Dataset``:

- dimensions ``speed_rpm`` (or ``point`` when speeds repeat, e.g. several clearances, with the
  speed, clearance and misalignment of each point as coordinates), ``station`` and ``direction``
  (from the channel names ``<station>.<y|z>``), ``harmonic`` (1X–5X), ``support_dof``;
- velocity and displacement harmonics as amplitude (m/s, m) and phase (rad); the loose support's
  relative motion (m for y, z; rad for θy, θz);
- each point's scalar results (convergence, regime, transient, wall time) and the host, pid and
  commit of the worker that computed it along the point dimension;
- the study's description, the scene's parameters and the client's code revision as attributes.

Written to netCDF or CSV by :func:`sweep.export.write` (``ringcontact study export``).
"""
from __future__ import annotations

import os

import numpy as np

from contact.errors import DatasetError
from sweep import ResultStore, load_sweep
from sweep.export import attr, table_to_xarray, xarray

SUPPORT_DOFS = ("y", "z", "θy", "θz")


def _stations(channels) -> tuple[list[str], list[str]]:
    names = [str(c) for c in channels]
    stations = list(dict.fromkeys(c.rsplit(".", 1)[0] for c in names))
    directions = list(dict.fromkeys(c.rsplit(".", 1)[1] for c in names if "." in c))
    if len(stations) * len(directions) != len(names) or any("." not in c for c in names):
        raise DatasetError(f"channels {names[:4]}…: not all of the form <station>.<direction>")
    return stations, directions


def _harmonics(points, stations, directions):
    """(P, S, D, H) complex velocity and displacement amplitudes, (P, H, 4) support motion."""
    S, D = len(stations), len(directions)
    H = points[0].arrays["harm_v"].shape[0]
    out = {q: np.zeros((len(points), S, D, H), complex) for q in ("v", "q")}
    u = np.zeros((len(points), H, len(SUPPORT_DOFS)), complex)
    for i, p in enumerate(points):
        col = {str(c): j for j, c in enumerate(p.arrays["channels"])}
        for s, st in enumerate(stations):
            for d, di in enumerate(directions):
                for q in ("v", "q"):
                    out[q][i, s, d] = p.arrays[f"harm_{q}"][:, col[f"{st}.{di}"]]
        u[i] = p.arrays["harm_u"]
    return out["v"], out["q"], u, H


def _point_rows(points) -> list[dict]:
    rows = []
    for p in points:
        row = {k: v for k, v in p.info.items() if not isinstance(v, dict)}
        w = p.record.get("run", {}).get("worker", {})
        row.update({"worker_host": w.get("host", p.record.get("run", {}).get("host")), "worker_pid": w.get("pid"),
                    "worker_git_commit": w.get("git_commit", p.record.get("run", {}).get("git_commit")),
                    "worker_blas_threads": w.get("blas_threads"), "point_key": p.key})
        rows.append(row)
    return rows


def to_xarray(run: str | os.PathLike, tasks=None):
    """The sweep in ``run`` as an ``xarray.Dataset`` (see the module docstring)."""
    xr = xarray()
    store = ResultStore(run)
    res = load_sweep(store, tasks, complete=True)
    points = sorted(res.values(), key=lambda p: (p.params.get("speed_rpm", 0.0), p.key))
    points = [p for p in points if "harm_v" in p.arrays]
    if not points:
        raise DatasetError(f"{store.root}: no steady-state points to export")
    stations, directions = _stations(points[0].arrays["channels"])
    v, q, u, H = _harmonics(points, stations, directions)
    rpm = np.array([p.params.get("speed_rpm", np.nan) for p in points], float)
    dim = "speed_rpm" if len(set(rpm)) == len(rpm) else "point"
    coords = {"station": stations, "direction": directions, "harmonic": np.arange(1, H + 1),
              "support_dof": list(SUPPORT_DOFS)}
    coords[dim] = rpm if dim == "speed_rpm" else np.arange(len(points))
    rows = _point_rows(points)
    if dim == "speed_rpm":
        rows = [{k: v for k, v in r.items() if k != "speed_rpm"} for r in rows]
    units = {"clearance_m": "m", "misalignment_m": "m", "wall_s": "s", "speed_rpm": "rpm", "peak_contact_force_N": "N",
             "mean_contact_force_N": "N", "peak_contact_moment_Nm": "N m", "peak_contact_force_t_s": "s"}
    ds = table_to_xarray(rows, units, dim=dim, coords=coords)
    if dim == "point":
        ds = ds.set_coords([c for c in ("speed_rpm", "clearance_m", "misalignment_m") if c in ds])
    pdims = (dim, "station", "direction", "harmonic")
    for name, a, unit, what in (("velocity", v, "m/s", "velocity"), ("displacement", q, "m", "displacement")):
        ds[f"{name}_amplitude"] = xr.Variable(pdims, np.abs(a), {"units": unit, "long_name": f"|{what}| of the harmonic"})
        ds[f"{name}_phase"] = xr.Variable(pdims, np.angle(a), {"units": "rad"})
    udims = (dim, "harmonic", "support_dof")
    ds["support_motion_amplitude"] = xr.Variable(udims, np.abs(u), {"units": "m (y, z), rad (θy, θz)",
                                                                      "long_name": "bearing minus support"})
    ds["support_motion_phase"] = xr.Variable(udims, np.angle(u), {"units": "rad"})
    ds[dim].attrs["units"] = "rpm" if dim == "speed_rpm" else ""
    ds.attrs.update(_attrs(store))
    return ds


def _attrs(store: ResultStore) -> dict:
    man = store.read_manifest(required=False) or {}
    out = {"kind": "ringcontact rotor study", "source": str(store.root)}
    for k in ("study", "scene_name", "scene", "description", "created_utc", "updated_utc", "git_commit",
              "git_dirty", "environment", "elements_per_segment"):
        if k in man:
            out[k if k not in ("git_commit", "git_dirty") else f"client_{k}"] = attr(man[k])
    return out
