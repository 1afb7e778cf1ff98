"""What every result object of :mod:`ringcontact` can do: ``to_dict``, ``to_csv``, ``to_xarray``, ``to_dataframe``,
``save`` and ``plot``.

A result is a frozen dataclass whose field names carry their unit (``frequency_rad_s``, ``speeds_rpm``,
``peak_contact_force_N``). Fields marked ``metadata={"internal": True}`` hold the objects the result was made
from (the assembled model, the raw solver result): kept for plotting and further work, left out of
``to_dict`` and the files. Each result names its table (one row per mode, speed or time sample) through
``_rows()`` and the dimension of those rows through ``_dim``.
"""
from __future__ import annotations

import csv
import dataclasses
import io
import json
import math
import os
from pathlib import Path

import numpy as np

from contact.errors import InputError
from contact.files import atomic_write_bytes, atomic_write_text

INTERNAL = {"internal": True}


def internal(default=None):
    """A dataclass field holding a source object: not compared, not shown, not exported."""
    return dataclasses.field(default=default, compare=False, repr=False, metadata=INTERNAL)


def plain(value):
    """``value`` as JSON-ready Python: arrays to lists, complex numbers to ``[re, im]``, non-finite to None."""
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, (complex, np.complexfloating)):
        return [plain(float(value.real)), plain(float(value.imag))]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


class ResultMethods:
    """Methods shared by the result dataclasses (mixed into each of them)."""

    _dim = "point"

    def to_dict(self) -> dict:
        """Every exported field (SI, unit in the key) as JSON-ready Python; ``result`` names the kind."""
        out = {"result": type(self).__name__}
        for f in dataclasses.fields(self):
            if not f.metadata.get("internal"):
                out[f.name] = plain(getattr(self, f.name))
        for name in getattr(self, "_summary", ()):       # summary attributes computed from the fields
            out[name] = plain(getattr(self, name))
        return out

    def _rows(self) -> list[dict]:
        raise NotImplementedError

    def rows(self) -> list[dict]:
        """The result's table: one dict per row (mode, speed or time sample), columns with units."""
        return [plain(r) for r in self._rows()]

    def to_csv(self, path: str | os.PathLike) -> Path:
        """Write :meth:`rows` as CSV (header of unit-carrying names; written to a temporary name, then renamed)."""
        rows = self.rows()
        names = list(dict.fromkeys(k for r in rows for k in r))
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(names)
        for r in rows:
            w.writerow(["" if r.get(k) is None else _cell(r.get(k)) for k in names])
        return atomic_write_text(Path(path), buf.getvalue())

    def to_xarray(self):
        """The table as an ``xarray.Dataset`` along the result's dimension (the ``xarray`` extra:
        ``pip install 'ringcontact[xarray]'``); the scalar fields as attributes."""
        from sweep.export import table_to_xarray
        scalars = {k: v for k, v in self.to_dict().items() if isinstance(v, (str, int, float, bool))}
        return table_to_xarray(self.rows(), dim=self._dim, attrs={**scalars, **law_validity_attrs(self)})

    def to_dataframe(self):
        """The table as a ``pandas.DataFrame``, when pandas is installed (it is not a dependency of
        ringcontact: without it use :meth:`rows`, :meth:`to_csv` or :meth:`to_xarray`)."""
        try:
            import pandas as pd
        except ImportError:
            raise InputError(f"{type(self).__name__}.to_dataframe: pandas is not installed (ringcontact does not "
                             "depend on it); use .rows(), .to_csv(path) or .to_xarray(), or pip install pandas") from None
        return pd.DataFrame(self.rows())

    def save(self, path: str | os.PathLike) -> Path:
        """Write the result to ``path``: ``.json`` (:meth:`to_dict`) or ``.npz`` (every numeric field as an array
        by its name, the rest as the JSON text ``summary_json``); written to a temporary name, then renamed.

        Raises
        ------
        contact.errors.InputError
            Any other suffix.
        """
        path = Path(path)
        if path.suffix == ".json":
            return atomic_write_text(path, json.dumps(self.to_dict(), indent=1, allow_nan=False) + "\n")
        if path.suffix == ".npz":
            arrays, rest = {}, {}
            for k, v in self.to_dict().items():
                a = np.asarray(getattr(self, k, v)) if k != "result" else None
                if a is not None and a.dtype.kind in "fciub" and a.size:
                    arrays[k] = a
                else:
                    rest[k] = v
            buf = io.BytesIO()
            np.savez_compressed(buf, summary_json=np.array(json.dumps(rest, allow_nan=False)), **arrays)
            return atomic_write_bytes(path, buf.getvalue())
        raise InputError(f"{type(self).__name__}.save: path = {str(path)!r}: the suffix must be .json or .npz")

    def plot(self, ax=None):
        """Draw the result on the matplotlib Axes ``ax`` (a new figure when None); returns the Axes."""
        if ax is None:
            import matplotlib.pyplot as plt
            _, ax = plt.subplots(figsize=(7.0, 4.5))
        self._draw(ax)
        ax.grid(alpha=0.3)
        return ax

    def _draw(self, ax) -> None:
        raise NotImplementedError


def law_validity_attrs(result) -> dict:
    """A result's validity record (``law_validity``, :mod:`rotor.model.law_validity`) as netCDF attributes: the
    whole record as JSON text ``law_validity``, and its verdict and contact-time shares as numbers and text of
    their own (``law_validity_verdict``, ``law_validity_contact_time_share_below`` …; NaN where None)."""
    rec = getattr(result, "law_validity", None)
    if not rec:
        return {}
    out = {"law_validity": json.dumps(plain(rec), allow_nan=False), "law_validity_verdict": str(rec["verdict"])}
    for key in ("contact_time_share_below", "contact_time_share_inside", "contact_time_share_above",
                "largest_tilt_rad"):
        if key in rec:
            out[f"law_validity_{key}"] = math.nan if rec[key] is None else float(rec[key])
    return out


def _cell(value):
    return json.dumps(value) if isinstance(value, (list, dict)) else value


def load_result(path: str | os.PathLike) -> dict:
    """A result written by ``.save(path)`` back as a dict: the JSON, or an NPZ's arrays and ``summary_json`` fields."""
    path = Path(path)
    if path.suffix == ".json":
        return json.loads(path.read_text(encoding="utf-8"))
    with np.load(path, allow_pickle=False) as z:
        out = json.loads(str(z["summary_json"]))
        out.update({k: z[k] for k in z.files if k != "summary_json"})
    return out
