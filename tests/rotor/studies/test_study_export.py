"""A study's result directory as one labelled dataset (rotor.studies.export.to_xarray, `study export`)."""
import json

import numpy as np
import pytest

from contact.errors import DatasetError
from rotor.studies.export import to_xarray
from rotor.studies.steady_state import sweep_tasks
from sweep import ResultStore, run_sweep

xr = pytest.importorskip("xarray")  # the test extra installs it
RPM = (1500.0, 3000.0)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("export") / "cascade"
    tasks = sweep_tasks("paper-table4", RPM, options={"steps_per_rev": 64, "max_revs": 100})
    s = run_sweep(tasks, out, max_workers=2, progress=False, manifest={"study": "cascade", "scene_name": "paper-table4",
                                                                      "scene": {"clearance_m": 5e-5}})
    assert sorted(s.computed) == ["rpm1500.0", "rpm3000.0"]
    return out


def test_speed_station_direction_harmonic_equal_the_stored_points(run):
    ds = to_xarray(run)
    assert dict(ds.sizes) == {"speed_rpm": 2, "station": 6, "direction": 2, "harmonic": 5, "support_dof": 4}
    assert list(ds.speed_rpm.values) == list(RPM) and ds.speed_rpm.attrs["units"] == "rpm"
    st = ResultStore(run)
    for rpm in RPM:
        p = st.load(f"rpm{rpm:.1f}")
        col = list(p.arrays["channels"]).index("disk2.z")
        sel = {"speed_rpm": rpm, "station": "disk2", "direction": "z"}
        np.testing.assert_array_equal(ds.velocity_amplitude.sel(sel).values, np.abs(p.arrays["harm_v"][:, col]))
        np.testing.assert_array_equal(ds.displacement_phase.sel(sel).values, np.angle(p.arrays["harm_q"][:, col]))
        np.testing.assert_array_equal(ds.support_motion_amplitude.sel(speed_rpm=rpm).values, np.abs(p.arrays["harm_u"]))
        assert ds.worker_host.sel(speed_rpm=rpm).item() == p.record["run"]["worker"]["host"]
        assert ds.worker_git_commit.sel(speed_rpm=rpm).item() == p.record["run"]["worker"]["git_commit"]
        assert ds.transient_revs.sel(speed_rpm=rpm).item() == p.info["transient_revs"]
    assert ds.velocity_amplitude.sel(speed_rpm=3000.0, station="disk1", direction="y", harmonic=1) > 0
    assert ds.velocity_amplitude.attrs["units"] == "m/s" and ds.clearance_m.attrs["units"] == "m"
    assert json.loads(ds.attrs["scene"]) == {"clearance_m": 5e-5} and ds.attrs["study"] == "cascade"
    assert ds.attrs["client_git_commit"] == st.read_manifest()["git_commit"]


def test_netcdf_and_csv_files_round_trip(run, tmp_path, capsys):
    from reports.cli.study import main

    assert main(["export", str(run), "--format", "netcdf", "--out", str(tmp_path / "c.nc")]) == 0
    assert main(["export", str(run), "--format", "csv", "--out", str(tmp_path / "c.csv")]) == 0
    ds = to_xarray(run)
    back = xr.open_dataset(tmp_path / "c.nc", engine="scipy")
    np.testing.assert_array_equal(back.velocity_amplitude.values, ds.velocity_amplitude.values)
    assert list(back.station.values) == list(ds.station.values) and back.attrs["scene"] == ds.attrs["scene"]
    back.close()
    lines = (tmp_path / "c.csv").read_text().splitlines()
    body = [ln for ln in lines if not ln.startswith("#")]
    assert any(ln.startswith("# scene: ") for ln in lines)
    header = body[0].split(",")
    assert header[:4] == ["speed_rpm", "station", "direction", "harmonic"] and "support_motion_amplitude_θy" in header
    assert len(body) - 1 == 2 * 6 * 2 * 5  # one row per speed x station x direction x harmonic
    row = dict(zip(header, next(b for b in body[1:] if b.startswith("3000.0,disk1,y,1,")).split(",")))
    assert float(row["velocity_amplitude"]) == pytest.approx(
        ds.velocity_amplitude.sel(speed_rpm=3000.0, station="disk1", direction="y", harmonic=1).item(), rel=1e-15)
    assert (tmp_path / "c.nc").stat().st_mode & 0o777 == 0o644


def test_export_refuses_a_damaged_point(run, tmp_path):
    import shutil

    bad = tmp_path / "bad"
    shutil.copytree(run, bad)
    (bad / "points" / "rpm1500.0.npz").write_bytes(b"damaged")
    with pytest.raises(DatasetError, match=r"rpm1500.0 \(corrupt"):
        to_xarray(bad)
