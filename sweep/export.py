"""Results as labelled datasets (xarray, the ``xarray`` extra) and their netCDF / CSV files.

- :func:`table_to_xarray`: rows of named values (FEM reference points, per-point scalars of a
  sweep) as variables along one dimension; list-valued columns become a second dimension (ragged
  ones padded with NaN), units go into each variable's ``units`` attribute;
- :func:`fem_to_xarray`: a FEM reference dataset (:mod:`contact.dataset`) that way, its metadata
  (scenes, mesh, solver, code revision, package versions) as attributes;
- :func:`write`: ``netcdf`` or ``csv``, atomically, mode 0644.

netCDF backend: ``scipy.io.netcdf`` (xarray's ``engine="scipy"``, netCDF-3 64-bit offset). scipy
is already a dependency of the suite and installs from wheels everywhere, so exporting adds only
xarray (pure Python; numpy and pandas wheels). netCDF-4/HDF5 (h5netcdf + h5py, or netCDF4) would
add compiled HDF5 libraries for features these files do not need: the datasets are a few MB at
most, have no groups, and complex amplitudes are stored as amplitude and phase. Attributes that
are not a string or number (nested scenes, provenance) are stored as JSON strings.
"""
from __future__ import annotations

import io
import json
import os
from pathlib import Path

import numpy as np

from contact.errors import InputError
from contact.files import atomic_write_bytes, atomic_write_text

FORMATS = ("netcdf", "csv")


def xarray():
    """The xarray module, or an InputError naming the extra to install."""
    try:
        import xarray as xr
    except ImportError:
        raise InputError("export: xarray is not installed; install the xarray extra "
                         "(pip install 'ringcontact[xarray]')") from None
    return xr


def attr(value):
    """A netCDF-3 attribute: strings and finite numbers as they are, anything else as JSON."""
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if isinstance(value, (str, int, float, np.integer, np.floating)):
        return value
    return json.dumps(value, sort_keys=True, default=str)


def _column(values: list):
    """One column as an array: numbers (None -> NaN), strings (None -> ''), or padded 1D lists."""
    present = [v for v in values if v is not None]
    if not present:
        return None
    if all(isinstance(v, (bool, np.bool_)) for v in present):
        return np.array([bool(v) if v is not None else False for v in values])
    if all(isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool) for v in present):
        if all(isinstance(v, (int, np.integer)) for v in present) and len(present) == len(values):
            return np.array(values, dtype=np.int64)
        return np.array([np.nan if v is None else float(v) for v in values])
    if all(isinstance(v, str) for v in present):
        return np.array(["" if v is None else v for v in values], dtype=str)
    if all(isinstance(v, (list, tuple)) and all(isinstance(x, (int, float)) or x is None for x in v) for v in present):
        n = max(len(v) for v in present)
        out = np.full((len(values), n), np.nan)
        for i, v in enumerate(values):
            for j, x in enumerate(v or []):
                out[i, j] = np.nan if x is None else x
        return out
    return None  # nested (maps, lists of lists): left to the JSON source


def table_to_xarray(rows: list[dict], units: dict | None = None, dim: str = "point", coords: dict | None = None,
                    attrs: dict | None = None):
    """Rows of named values as an ``xarray.Dataset`` along ``dim`` (see the module docstring).

    Columns that cannot be labelled (nested maps, ragged 2D lists) are listed in the attribute
    ``columns_not_exported``.
    """
    xr = xarray()
    units = units or {}
    names = list(dict.fromkeys(k for r in rows for k in r))
    data, skipped = {}, []
    for name in names:
        col = _column([r.get(name) for r in rows])
        if col is None:
            skipped.append(name)
            continue
        dims = (dim,) if col.ndim == 1 else (dim, f"{name}_index")
        data[name] = xr.Variable(dims, col, attrs={"units": units[name]} if units.get(name) not in (None, "") else {})
    ds = xr.Dataset(data, coords=coords or {})
    ds.attrs.update({k: attr(v) for k, v in (attrs or {}).items()})
    ds.attrs["columns_not_exported"] = attr(skipped)
    return ds


def fem_to_xarray(path: str | os.PathLike):
    """A FEM reference dataset (``fem_reference/data/*.json``) as an ``xarray.Dataset`` along ``point``,
    with the dataset's metadata as attributes."""
    from contact.dataset import read_dataset

    ds = read_dataset(path)
    units = {k: (None if u == "-" else u) for k, u in ds.columns.items()}
    attrs = {f"metadata_{k}": v for k, v in ds.metadata.items()}
    attrs.update({"source": str(Path(path).name), "kind": "ringcontact FEM reference dataset"})
    return table_to_xarray(ds.points, units, attrs=attrs)


def write(ds, path: str | os.PathLike, fmt: str) -> Path:
    """Write a labelled dataset as ``netcdf`` (scipy backend, netCDF-3) or ``csv`` (one row per
    combination of the dimensions, attributes as leading ``# name: value`` lines)."""
    if fmt not in FORMATS:
        raise InputError(f"format = {fmt!r}: choose one of {', '.join(FORMATS)}")
    if fmt == "netcdf":
        return atomic_write_bytes(path, ds.to_netcdf(None, engine="scipy"))
    buf = io.StringIO()
    for k, v in ds.attrs.items():
        buf.write(f"# {k}: {str(v).replace(chr(10), ' ')}\n")
    _flat(ds).to_dataframe().to_csv(buf, lineterminator="\n")
    return atomic_write_text(path, buf.getvalue())


def _flat(ds):
    """Rows over the dimensions of the widest variable without list columns (rotor: speed x station x
    direction x harmonic; FEM: point); any other dimension becomes columns ``<name>_<label>``, so a CSV
    row is not repeated for every combination of unrelated indices."""
    plain = [ds[v].dims for v in ds.data_vars if not any(str(d).endswith("_index") for d in ds[v].dims)]
    rows = set(max(plain, key=len)) if plain else set()
    out = ds.drop_vars([v for v in ds.data_vars if not set(ds[v].dims) <= rows])
    out = out.drop_dims([d for d in out.dims if d not in rows])
    for v in ds.data_vars:
        extra = [d for d in ds[v].dims if d not in rows]
        if not extra:
            continue
        stacked = ds[v].stack(_col=extra)
        for i in range(stacked.sizes["_col"]):
            label = "_".join(str(x) for x in np.atleast_1d(stacked["_col"].values[i]))
            out[f"{v}_{label}"] = stacked.isel(_col=i, drop=True)
    return out
