"""Labelled datasets (sweep.export): tables and the FEM reference datasets, netCDF (scipy) and CSV."""
import numpy as np
import pytest

from contact.dataset import read_dataset
from contact.errors import InputError
from fem_reference.plane.sweep import DATASET_PATH as FEM2D
from fem_reference.solid.sweep import DATASET_PATH as FEM3D
from sweep.export import fem_to_xarray, table_to_xarray, write

xr = pytest.importorskip("xarray")  # the test extra installs it


def test_table_columns_become_labelled_variables():
    rows = [{"a_m": 1.0, "n": 2, "name": "x", "levels": [1.0, 2.0], "ok": True, "nested": {"k": 1}},
            {"a_m": None, "n": 3, "name": None, "levels": [1.0, 2.0, 4.0], "ok": False, "nested": {"k": 2}}]
    ds = table_to_xarray(rows, {"a_m": "m"}, attrs={"scene": {"r_m": 0.1}, "study": "t"})
    assert ds.a_m.attrs["units"] == "m" and np.isnan(ds.a_m.values[1]) and ds.n.dtype == np.int64
    assert list(ds.name.values) == ["x", ""] and list(ds.ok.values) == [True, False]
    np.testing.assert_array_equal(ds.levels.values, [[1.0, 2.0, np.nan], [1.0, 2.0, 4.0]])
    assert ds.attrs["scene"] == '{"r_m": 0.1}' and ds.attrs["columns_not_exported"] == '["nested"]'


@pytest.mark.parametrize("path", [FEM2D, FEM3D], ids=["fem2d", "fem3d"])
def test_fem_dataset_exports_with_units_and_metadata(path, tmp_path):
    src = read_dataset(path)
    ds = fem_to_xarray(path)
    assert ds.sizes["point"] == len(src.points)
    np.testing.assert_array_equal(ds.force_n.values, [p["force_n"] for p in src.points])
    assert ds.force_n.attrs["units"] == "N" and list(ds.scene.values) == [p["scene"] for p in src.points]
    assert ds.attrs["metadata_code_revision"] == src.metadata["code_revision"]
    lv = ds.force_levels_n.values
    for i, p in enumerate(src.points):
        np.testing.assert_array_equal(lv[i, : len(p["force_levels_n"])], p["force_levels_n"])
        assert np.isnan(lv[i, len(p["force_levels_n"]):]).all()
    write(ds, tmp_path / "d.nc", "netcdf")
    back = xr.open_dataset(tmp_path / "d.nc", engine="scipy")
    np.testing.assert_array_equal(back.force_n.values, ds.force_n.values)
    back.close()
    write(ds, tmp_path / "d.csv", "csv")
    body = [ln for ln in (tmp_path / "d.csv").read_text().splitlines() if not ln.startswith("#")]
    assert len(body) == 1 + len(src.points) and "force_levels_n_0" in body[0].split(",")
    with pytest.raises(InputError, match="format"):
        write(ds, tmp_path / "d.x", "hdf5")
