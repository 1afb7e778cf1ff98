"""`study map` figures and note with a point beyond the conformal law's neat-fit limit (reports/studies/regime_map.py).

Under the scene's reading of Eq. 34 the smallest clearances at 15 231 rpm drive the ring past the law's domain
(rotor.studies.steady_state.beyond_law_record: no record, label "beyond law"); the map drew every point's label
as one of four regimes and stopped with an internal error there. Two synthetic points: one impact, one beyond."""
import numpy as np

from reports.studies.regime_map import REGIMES, map_figures, map_note
from sweep import Task
from sweep.store import ResultStore


def _never(**params):            # the tasks only name the stored points
    raise AssertionError("not computed")


def test_a_point_beyond_the_law_is_its_own_cell_with_empty_csv_cells(tmp_path):
    store = ResultStore(tmp_path / "run")
    pa = {"scene": "paper-table4", "speed_rpm": 9000.0, "clearance_m": 5e-5}
    pb = {"scene": "paper-table4", "speed_rpm": 15230.8, "clearance_m": 1e-5}
    store.save("a", pa, {"x": np.zeros(1)}, {"label": "impact", "contact_fraction": 0.5, "stick_fraction": 0.0,
                                             "max_r_over_clearance": 1.01, "converged": True, "period_revs": 1})
    store.save("b", pb, {"x": np.zeros(1)}, {"label": "beyond law", "converged": False, "period_revs": 0,
                                             "outside_law_domain": "neat-fit limit"})
    tasks = [Task("a", _never, pa), Task("b", _never, pb)]
    files = map_figures(tmp_path / "run", tmp_path / "figs", tasks=tasks)
    csv = (tmp_path / "figs" / "study-map.csv").read_text().splitlines()
    assert csv[2] == "15230.8,0.01,beyond law,,,,0,0" and csv[1].startswith("9000,0.05,impact,0.5,0,1.01,1,1")
    assert "beyond law" in REGIMES and {f.suffix for f in files} == {".png", ".svg", ".csv"}
    from reports.studies.common import load_points
    note = map_note(load_points(tmp_path / "run", tasks))
    assert "beyond law 1, impact 1 of 2 points" in note and "Integrator:" in note and "paper-table4" in note
