"""The published claims and the test that guards each: plain data, checked by tests/test_claims.py and listed in
reports/published/claims.md by benchmarks/list_claims.py.

:data:`CLAIMS`: one entry per claimed number. ``report`` is the file (relative to the repository root),
``claim`` a short quote of the number with its context exactly as the file has it (the check fails when the
report changes, so the registry follows it), ``test`` the pytest node id of the test that recomputes or checks
it (parametrized ids dropped) and ``tier`` ``"default"`` (run by ``python3 dev.py test``) or ``"slow"``
(``-m slow`` only).

:data:`NOT_CLAIMS`: Markdown reports of reports/published/ with no registered claim, each with the reason.

:data:`UNGUARDED`: numbers a report or README.md still states that no test guards, each with the reason (a stale
number or a wall time no test may assert); each must still be in its file, so fixing one removes its entry.
"""
from __future__ import annotations

_BLIND_TEST = "tests/reports/test_tilt_correction_report.py::test_blind_section_is_the_published_one_and_its_points_are_the_seed_s_draw"

CLAIMS = (
    # README.md: its numbers against the reports they come from (tests/test_readme_numbers.py) or recomputed
    dict(report="README.md",
         claim="the conformal and Pereira laws reproduce the paper's Table 2 percentages to 0.01 points",
         test="tests/test_readme_numbers.py::test_table2_agreement_is_the_laws_report_s", tier="default"),
    dict(report="README.md", claim="(clamped 10 mm rings are 4–10× stiffer)",
         test="tests/test_published_fem.py::test_paper_implied_loads_and_the_clamped_rings_stiffness_ratio",
         tier="default"),
    dict(report="README.md", claim="with the calibrated laws (held-out error ≤ 0.7 %)",
         test="tests/test_readme_numbers.py::test_held_out_error_bound_is_the_accuracy_report_s", tier="default"),
    dict(report="README.md", claim="the Table 1 file through the same job reproduces the committed datasets and calibrations exactly",
         test="tests/reports/test_bearing_job.py::test_table1_through_the_job_reproduces_the_committed_data",
         tier="slow"),
    dict(report="README.md", claim="(2X/1X 0.015 / 0.16 / 0.34 at disk 1 / disk 2 / support)",
         test="tests/test_readme_numbers.py::test_misalignment_ratios_are_the_rotor_misalignment_report_s",
         tier="default"),
    dict(report="README.md", claim="the former opposed pair on the locked joint cancels (4.6e-3 at the support)",
         test="tests/test_readme_numbers.py::test_misalignment_ratios_are_the_rotor_misalignment_report_s",
         tier="default"),
    dict(report="README.md",
         claim="puts the third forward critical speed at 9 608 rpm, +9.9 % on the converged 8 744 rpm; two elements per segment are within 0.63 %",
         test="tests/test_readme_numbers.py::test_critical_speed_mesh_numbers_are_the_rotor_mesh_report_s",
         tier="default"),
    dict(report="README.md", claim="2 converge the critical speeds to 1 %",
         test="tests/test_readme_numbers.py::test_critical_speed_mesh_numbers_are_the_rotor_mesh_report_s",
         tier="default"),
    dict(report="README.md", claim="a Table 4 cascade point takes a median 1.4 s",
         test="tests/test_readme_numbers.py::test_sweep_cost_follows_from_the_cascade_and_dask_reports",
         tier="default"),
    dict(report="README.md", claim="about 2 600 points per core-hour",
         test="tests/test_readme_numbers.py::test_sweep_cost_follows_from_the_cascade_and_dask_reports",
         tier="default"),
    dict(report="README.md", claim="measures dask at the local pool's throughput once workers are warm (0.999×)",
         test="tests/test_readme_numbers.py::test_sweep_cost_follows_from_the_cascade_and_dask_reports",
         tier="default"),
    dict(report="README.md", claim="about 39 core-hours",
         test="tests/test_readme_numbers.py::test_sweep_cost_follows_from_the_cascade_and_dask_reports",
         tier="default"),
    dict(report="README.md",
         claim="over about 67 colliding variant–speed pairs 2X rises with δ in 65 of 66, ignoring the tilt lowers 3X–5X by ≥ 30 % in 58 of 66, 3X rises with δ in 29 of 66 and the clearance trend holds in 16–18 of 67",
         test="tests/test_readme_numbers.py::test_sensitivity_counts_are_the_sensitivity_report_s", tier="default"),
    dict(report="README.md", claim="(16 min with 1 worker, resumable)",
         test="tests/test_readme_numbers.py::test_sensitivity_counts_are_the_sensitivity_report_s", tier="default"),
    dict(report="README.md",
         claim="Point A and the 3X–5X near the loose support agree on both meshes (61 of 62 high speeds), and 2X rises with δ in every band on both meshes",
         test="tests/test_readme_numbers.py::test_findings_that_hold_are_the_findings_report_s", tier="default"),
    dict(report="README.md",
         claim="The end faces slip from 5 400 rpm: 12 of the 14 speeds of 4 800–8 700 rpm on each mesh disagree",
         test="tests/test_readme_numbers.py::test_slip_numbers_are_the_findings_report_s", tier="default"),
    dict(report="README.md",
         claim="2X rises with δ0 by 0.9–4.7 % at 4 of 6 speeds on each mesh (threshold 0.8 %)",
         test="tests/test_readme_numbers.py::test_clearance_numbers_are_the_findings_report_s", tier="default"),
    dict(report="README.md", claim="ignoring the tilt is \"no effect\" at 37 of 40 speeds there",
         test="tests/test_readme_numbers.py::test_tilt_numbers_are_the_findings_report_s", tier="default"),
    dict(report="README.md",
         claim="at point B (10 500 rpm) the bearing collides 46 % of the time (56 % on the paper's mesh) and the support's 1X is 24.1 mm/s against the paper mesh's 7.71 mm/s",
         test="tests/test_readme_numbers.py::test_point_b_numbers_are_the_findings_report_s", tier="default"),

    # laws-vs-paper.md (demo report: rebuilt byte for byte)
    dict(report="reports/published/laws-vs-paper.md",
         claim="largest difference 0.009 points (tolerance ±0.05 points) — **met**",
         test="tests/reports/test_demo_reproducible.py::test_the_demo_rebuilds_the_committed_reports_byte_for_byte",
         tier="default"),
    dict(report="reports/published/laws-vs-paper.md",
         claim="Johnson's law has a solution only up to Δr = 4δ0/e² = 0.0271 mm",
         test="tests/contact/test_contact_laws.py::test_johnson_domain_matches_table2_blanks", tier="default"),
    dict(report="reports/published/laws-vs-paper.md", claim="| 0.01 | 33.56 | 0.3015 | 50 272 | 33 644 | 31 145 |",
         test="tests/contact/test_contact_laws.py::test_conformal_reproduces_reconstructed_loads", tier="default"),
    dict(report="reports/published/laws-vs-paper.md", claim="(differences -3.67, -0.38 points)",
         test="tests/reports/test_demo_reproducible.py::test_the_demo_rebuilds_the_committed_reports_byte_for_byte",
         tier="default"),

    # accuracy-table2.md (demo report)
    dict(report="reports/published/accuracy-table2.md",
         claim="`clamped` (clamped-foundation): 0.01 mm: 0.096 % < 12.01 %",
         test="tests/reports/test_accuracy_report.py::test_committed_held_out_cells_and_must_show_lines",
         tier="default"),
    dict(report="reports/published/accuracy-table2.md", claim="Overall: **met** for the 2D (Table 2) points",
         test="tests/reports/test_accuracy_report.py::test_committed_held_out_cells_and_must_show_lines",
         tier="default"),
    dict(report="reports/published/accuracy-table2.md",
         claim="largest held-out error 0.06 % over 15 of the paper's 15 cells",
         test="tests/reports/test_accuracy_report.py::test_committed_report_is_what_the_builder_writes_now",
         tier="default"),
    dict(report="reports/published/accuracy-table2.md", claim="held-out RMS 0.314 %, max 0.722 % over the whole range",
         test="tests/reports/test_accuracy_report.py::test_committed_report_is_what_the_builder_writes_now",
         tier="default"),
    dict(report="reports/published/accuracy-table2.md",
         claim="The fitted foundation modulus is 0.9988 × M/(h_b + h_s) = 1.373e+13 Pa/m",
         test="tests/contact/test_calibration.py::test_clamped_foundation_modulus_is_the_constrained_modulus_over_ring_thickness",
         tier="default"),

    # bearing-table1-reproduction.md
    dict(report="reports/published/bearing-table1-reproduction.md",
         claim="| 2D force, scene clamped | 12 | 0.00e+00 | 4.53e-04 | 0 |",
         test="tests/test_published_fem.py::test_table1_ring_file_reproduces_a_committed_2d_point", tier="default"),
    dict(report="reports/published/bearing-table1-reproduction.md", claim="| 3D force | 30 | 1.18e-14 | 6.47e-03 | 0 |",
         test="tests/reports/test_bearing_job.py::test_table1_through_the_job_reproduces_the_committed_data",
         tier="slow"),
    dict(report="reports/published/bearing-table1-reproduction.md",
         claim="| `clamped-foundation` | foundation / foundation | foundation_modulus_Pa_per_m | 1.37149162209e+13 | 1.37149162209e+13 | 0.0e+00 |",
         test="tests/contact/test_calibration.py::test_stored_calibrations_match_a_refit_of_the_committed_dataset",
         tier="default"),

    # bearing-steel-in-aluminium/accuracy-steel-in-aluminium.md
    dict(report="reports/published/bearing-steel-in-aluminium/accuracy-steel-in-aluminium.md",
         claim="Checks: holdout_max_rel_2d 0.062 %; fem2d_error_max_rel 0.074 %; holdout_max_rel_3d_zero_tilt 0.130 %",
         test="tests/test_published_fem.py::test_steel_in_aluminium_law_refits_from_its_committed_fem", tier="default"),
    dict(report="reports/published/bearing-steel-in-aluminium/accuracy-steel-in-aluminium.md",
         claim="`steel-in-aluminium-3d-foundation-spline` (foundation-spline), 6 knots from 0.004 to 0.04 mm",
         test="tests/test_published_fem.py::test_steel_in_aluminium_law_refits_from_its_committed_fem", tier="default"),

    # bearing-plane-choice.md (plane stress or strain by the 3D ring; the check's wall times are not claims)
    dict(report="reports/published/bearing-plane-choice.md",
         claim="| newcomer (issue 38) | 4 | clamped-axially-free | auto | 0.0126 | 44 749 ± 0.037 | -0.04 | +22.86 | stress (decisive) | stress |",
         test="tests/fem_reference/test_plane_check.py::test_the_newcomers_ring_follows_plane_stress_and_the_table1_rings_lie_between",
         tier="slow"),
    dict(report="reports/published/bearing-plane-choice.md",
         claim="| clamped | 3 | clamped | strain | 0.00707 | 167 810 ± 0.002 | -7.45 | +12.89 | stress (decisive) | strain |",
         test="tests/fem_reference/test_plane_check.py::test_the_newcomers_ring_follows_plane_stress_and_the_table1_rings_lie_between",
         tier="slow"),
    dict(report="README.md", claim="(axially free: plane stress within 0.04 %, plane strain 23 %",
         test="tests/fem_reference/test_plane_check.py::test_the_newcomers_ring_follows_plane_stress_and_the_table1_rings_lie_between",
         tier="slow"),
    dict(report="README.md", claim="plane stress 7.5 % below, plane strain 13.2 % above",
         test="tests/fem_reference/test_plane_check.py::test_the_newcomers_ring_follows_plane_stress_and_the_table1_rings_lie_between",
         tier="slow"),
    # perf-bearing.md (the stage times are wall times; the tilted run's law and its tilt correction's held-out table
    # are recomputed from the datasets the benchmark keeps in reports/published/perf-bearing/)
    dict(report="reports/published/perf-bearing.md",
         claim="Law of the tilted run: `steel-in-aluminium-3d-foundation-spline-tilt` (foundation-spline); checks: "
               "holdout_max_rel_2d 0.062 %",
         test="tests/reports/test_bearing_tilt.py::test_the_benchmark_s_tilted_run_is_recomputed_from_its_kept_datasets", tier="default"),
    dict(report="reports/published/perf-bearing.md",
         claim="| verification grid | force, tilted | 48 / 48 | 0.059 vs 0.207 | 47 / 48 |",
         test="tests/reports/test_bearing_tilt.py::test_the_benchmark_s_tilted_run_is_recomputed_from_its_kept_datasets", tier="default"),
    dict(report="reports/published/perf-bearing.md",
         claim="| verification grid | moment, tilted | 48 / 48 | 0.090 vs 0.355 | 0 / 48 |",
         test="tests/reports/test_bearing_tilt.py::test_the_benchmark_s_tilted_run_is_recomputed_from_its_kept_datasets", tier="default"),
    dict(report="reports/published/perf-bearing.md",
         claim="| 3D reference points | moment, tilted | 16 / 16 | 0.063 vs 0.242 | 0 / 16 |",
         test="tests/reports/test_bearing_tilt.py::test_the_benchmark_s_tilted_run_is_recomputed_from_its_kept_datasets", tier="default"),

    # fem-verification-dissimilar.md
    dict(report="reports/published/fem-verification-dissimilar.md",
         claim="| shrink fit, plane strain | 1.44915e+08 | 1.44916e+08 | 31829.2 | 895.019 | +6.18e-06 | yes |",
         test="tests/fem_reference/test_dissimilar_verification.py::test_shrink_fit_interface_pressure_within_its_error_estimate",
         tier="default"),
    dict(report="reports/published/fem-verification-dissimilar.md",
         claim="Deviation ratio per halving of h/R: 2.50, 3.57 (≥ 1: falls at every halving: yes)",
         test="tests/fem_reference/test_dissimilar_verification.py::test_thin_rings_tend_to_the_winkler_foundation_law",
         tier="default"),
    dict(report="reports/published/fem-verification-dissimilar.md",
         claim="| Winkler, h/R = 0.2, penetration_m 3e-05, half_angle_deg 58.6524 | 313132 | 313708 | 8.99922 | 576.222 | +1.84e-03 | limit |",
         test="tests/fem_reference/test_dissimilar_verification.py::test_thin_rings_at_a_wide_arc_are_within_two_per_mille_of_winkler",
         tier="slow"),
    dict(report="reports/published/fem-verification-dissimilar.md",
         claim="| Persson, plate 20, penetration_m 1.2e-05, half_angle_deg 21.0799 | 11105.8 | 11102.3 | 8.5026 | -3.57435 | -3.22e-04 | yes |",
         test="tests/fem_reference/test_dissimilar_verification.py::test_persson_dissimilar_load_vs_measured_angle_follows_the_law_with_alpha",
         tier="default"),
    dict(report="reports/published/fem-verification-dissimilar.md",
         claim="ratio 10 +1.36%, ratio 20 +0.39%, ratio 40 +0.11%, ratio 80 +0.14%",
         test="tests/fem_reference/test_dissimilar_verification.py::test_steel_in_aluminium_needs_the_beta_term",
         tier="default"),
    dict(report="reports/published/fem-verification-dissimilar.md",
         claim="| 2D scaling x2, plane strain, penetration_m 1e-05 | 212076 | 212066 | 48.1241 | -10.2913 | -4.85e-05 | yes |",
         test="tests/fem_reference/test_dissimilar_verification.py::test_doubling_every_length_quadruples_the_2d_force",
         tier="default"),
    dict(report="reports/published/fem-verification-dissimilar.md",
         claim="| 3D scaling x2, force, penetration_m 1e-05 | 178735 | 178735 | 1328.12 | 0 | +0.00e+00 | yes |",
         test="tests/fem_reference/test_dissimilar_verification.py::test_3d_scaling_on_the_reference_levels_within_stated_errors",
         tier="slow"),
    dict(report="reports/published/fem-verification-dissimilar.md",
         claim="| 3D fixed ends vs 2D plane strain, penetration_m 1e-05 | 53019.1 | 53012.6 | 46.3916 | -6.51499 | -1.23e-04 | yes |",
         test="tests/fem_reference/test_dissimilar_verification.py::test_3d_fixed_ends_equal_2d_plane_strain_on_reference_levels",
         tier="slow"),

    # fem2d-benchmark.md (its times are wall times)
    dict(report="reports/published/fem2d-benchmark.md",
         claim="**36/36** points with estimated force error ≤ 0.1 % (largest 8.5e-04)",
         test="tests/fem_reference/plane/test_fem_dataset.py::test_committed_dataset_is_complete", tier="default"),

    # law-family.md and its 20 mm ring run (issue 37, must-show 3; the kernel times are not claims: wall times). The
    # pairs' summary is the committed run's (its FEM points committed, reports/published/law-family-pairs/); a new
    # run of the benchmark (a new seed) changes it and this entry
    dict(report="reports/published/law-family.md",
         claim="Pairs solved: 30 of 30. At every midpoint within the target: the chosen law on 30 of 30 pairs, the "
               "flexible family on 30 of 30, some family on 30 of 30. Midpoints within the target: chosen 330 of 330",
         test="tests/reports/test_law_family_pairs.py::test_the_published_pairs_table_is_the_refit_of_its_kept_points",
         tier="default"),
    dict(report="reports/published/law-family.md", claim="| 2d | force | 9 / 10 | 8 / 8 | no | 0.771 | 0.381 |",
         test="tests/reports/test_bearing_job.py::test_the_20mm_ring_accuracy_is_the_published_one", tier="default"),
    dict(report="reports/published/law-family.md",
         claim="| 3d tilted (rotor kernel) | moment | 0 / 18 | – | no | 13.626 | 0.606 |",
         test="tests/reports/test_bearing_job.py::test_the_20mm_ring_accuracy_is_the_published_one", tier="default"),
    dict(report="reports/published/law-family-newcomer-20mm/accuracy-newcomer-20mm.md",
         claim="| 3d tilted (rotor kernel) | moment | 0 / 18 | – | no | 13.626 | 0.606 |",
         test="tests/reports/test_bearing_job.py::test_the_20mm_ring_accuracy_is_the_published_one", tier="default"),

    # law-tilt-correction.md (issue 37, must-show 3, the tilted part; its kernel times are wall times)
    dict(report="reports/published/law-tilt-correction.md",
         claim='| committed | moment, tilted | `newcomer-20mm-3d-foundation-spline-tilt` (slices + correction) | 16 / 16 | yes | 0.150 | 0.150 vs 0.261 |',
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim='| verification grid | moment, tilted | `newcomer-20mm-3d-foundation-spline-tilt` (slices + correction) | 48 / 48 | yes | 0.182 | 0.130 vs 0.209 |',
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim='| committed | moment, tilted | published `newcomer-20mm-3d-foundation-spline` (slices) | 0 / 16 | no | 13.626 | 13.626 vs 0.606 |',
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim='**newcomer-20mm: the law with its tilt correction meets the target at every held-out point, force and moment.**',
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim='**steel-in-aluminium: the law with its tilt correction meets the target at every held-out point, force and moment.**',
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim="Held out on both rings, force and moment: **met**.",
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),
    dict(report="reports/published/law-tilt-correction.md", claim="| 0.1 | **1.12** | 1.14 | 1.20 | 1.52 |",
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim="newcomer-20mm: one weight picks 0.0001 (cross-validated worst 1.41), one per direction 0.1/0.0001 (1.12); with one weight 0 held-out point(s) miss.",
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim="newcomer-20mm 0.337 → 0.313 (3 → 2 outside), 0.338 → 0.324 (2 → 2 outside), 0.354 → 0.317 (4 → 2 outside), 0.430 → 0.376 (4 → 3 outside)",
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim="steel-in-aluminium 0.156 → 0.170 (0 → 0 outside), 0.235 → 0.234 (2 → 2 outside), 0.191 → 0.193 (1 → 1 outside), 0.167 → 0.217 (0 → 2 outside)",
         test="tests/reports/test_tilt_correction_report.py::test_held_out_tables_are_the_published_ones", tier="default"),

    # law-tilt-correction.md's blind section (bench_tilt_correction.py --blind): one benchmark sample of the 20 mm ring,
    # drawn with a new seed each run (seed 206384725, at 42c4171); its points are kept, so the default test recomputes
    # the law's errors from them and checks they are the seed's draw, and a slow test solves three again
    dict(report="reports/published/law-tilt-correction.md",
         claim='| `newcomer-20mm-3d-foundation-spline-tilt` (slices + correction) | force, zero tilt | 6 / 6 | yes | 0.110 | 0.007 vs 0.229 |',
         test=_BLIND_TEST, tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim='| `newcomer-20mm-3d-foundation-spline-tilt` (slices + correction) | force, tilted | 48 / 48 | yes | 0.247 | 0.122 vs 0.236 |',
         test=_BLIND_TEST, tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim='| `newcomer-20mm-3d-foundation-spline-tilt` (slices + correction) | moment, tilted | 48 / 48 | yes | 0.335 | 0.220 vs 0.226 |',
         test=_BLIND_TEST, tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim='| published `newcomer-20mm-3d-foundation-spline` (slices) | moment, tilted | 0 / 48 | no | 13.480 | 13.480 vs 0.560 |',
         test=_BLIND_TEST, tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim='**Blind sample, seed 206384725: the committed law with its tilt correction is within the target at every point, force and moment (102 of 102 checks).**',
         test=_BLIND_TEST, tier="default"),
    dict(report="reports/published/law-tilt-correction.md",
         claim='Largest error over its bound: force, zero tilt 0.33; force, tilted 0.52; moment, tilted 0.97.',
         test=_BLIND_TEST, tier="default"),
    dict(report="reports/published/law-tilt-correction.md", claim="| 14.08 | 6.402 | +0.056 | 0.203 | -0.220 | 0.226 | yes |",
         test="tests/reports/test_tilt_correction_report.py::test_three_blind_points_re_solved_on_the_cached_levels_are_the_kept_ones",
         tier="slow"),

    # fem2d-adaptive.md (issue 37: error-driven levels on the cast-iron pair; its times are wall times)
    dict(report="reports/published/fem2d-adaptive.md",
         claim="Within the bar: 5 of 5 penetrations; the largest bar 0.017%.",
         test="tests/fem_reference/plane/test_adaptive.py::test_cast_iron_pair_within_its_bar_at_every_penetration",
         tier="slow"),

    # fem2d-paper-setup.md
    dict(report="reports/published/fem2d-paper-setup.md", claim="(paper: 6.77; the closed-form conformal law: 5.70)",
         test="tests/test_published_fem.py::test_paper_implied_loads_and_the_clamped_rings_stiffness_ratio",
         tier="default"),
    dict(report="reports/published/fem2d-paper-setup.md",
         claim="Kinematically driven rings (rigid inner surface, support clamped) are 4–10× too stiff",
         test="tests/test_published_fem.py::test_paper_implied_loads_and_the_clamped_rings_stiffness_ratio",
         tier="default"),
    dict(report="reports/published/fem2d-paper-setup.md",
         claim="0 of 20 come within 5 % of the paper at all five points",
         test="tests/test_published_fem.py::test_paper_implied_loads_and_the_clamped_rings_stiffness_ratio",
         tier="default"),

    # fem2d-reference.md
    dict(report="reports/published/fem2d-reference.md",
         claim="Largest estimated force error 8.5e-04 (12/12 points ≤ 0.1 %)",
         test="tests/test_published_fem.py::test_fem2d_reference_tables_are_what_the_builder_writes", tier="default"),
    dict(report="reports/published/fem2d-reference.md",
         claim="Within 10°–70°: largest |FE/law − 1| = 0.67% over 9 points",
         test="tests/fem_reference/plane/test_fem_solver.py::test_persson_load_vs_measured_angle_within_one_percent",
         tier="default"),
    dict(report="reports/published/fem2d-reference.md", claim="| P2 | strain | 2 | 3.60711 | 3.60712 | -3.5e-06 |",
         test="tests/test_published_fem.py::test_lame_ring_p2_within_the_published_error", tier="default"),
    dict(report="reports/published/fem2d-reference.md",
         claim="Δr = 0.01 mm: compliance Δr/F vs ln(R_o/R_b): slope 0.0546 µm/kN per unit ln, R² = 0.9959.",
         test="tests/fem_reference/plane/test_fem_solver.py::test_persson_load_vs_penetration_falls_as_the_plate_grows",
         tier="default"),

    # fem3d-perf.md (its times are wall times)
    dict(report="reports/published/fem3d-perf.md",
         claim="Committed value of this point (`fem3d-reference.json`, levels Q0, Q1, Q2): 1193.37 kN, -2.1005 kN·m",
         test="tests/test_published_fem.py::test_fem3d_perf_point_is_the_committed_one", tier="default"),

    # fem3d-reference.md
    dict(report="reports/published/fem3d-reference.md",
         claim="Largest stated error: force 1.51 %, moment 0.61 % (acceptance: 2 %)",
         test="tests/test_published_fem.py::test_fem3d_reference_point_table_is_what_the_builder_writes",
         tier="default"),
    dict(report="reports/published/fem3d-reference.md",
         claim="At the 15 Table 3 points (0.5′, 1′, 2′ × 0.01–0.05 mm): force 0.23 % (must show ≤ 0.3 %), moment 0.44 % (must show ≤ 0.5 %)",
         test="tests/fem_reference/solid/test_fem3d_dataset.py::test_table3_points_meet_the_stated_accuracy",
         tier="default"),
    dict(report="reports/published/fem3d-reference.md",
         claim="Every stated error bounds the difference to the finer check level: **yes**",
         test="tests/fem_reference/solid/test_fem3d_dataset.py::test_stated_errors_bound_the_finer_solve",
         tier="default"),
    dict(report="reports/published/fem3d-reference.md", claim="Largest moment difference: 0.59 % (must show: within 1 %).",
         test="tests/fem_reference/solid/test_fem3d_solver.py::test_tilted_moments_agree_with_the_hexahedral_model",
         tier="slow"),
    dict(report="reports/published/fem3d-reference.md", claim="about 12 % below plane strain",
         test="tests/fem_reference/solid/test_fem3d_solver.py::test_free_ends_between_plane_stress_and_plane_strain",
         tier="default"),

    # perf-branch-switches.md (a 40-minute run: its summary against its published data)
    dict(report="reports/published/perf-branch-switches.md", claim="| orbits | 788 |",
         test="tests/test_published_studies.py::test_branch_reports_agree_with_the_published_branch_data",
         tier="default"),
    dict(report="reports/published/perf-branch-switches.md", claim="| stable / unstable orbits | 644 / 144 |",
         test="tests/test_published_studies.py::test_branch_reports_agree_with_the_published_branch_data",
         tier="default"),

    # perf-friction-events.md
    dict(report="reports/published/perf-friction-events.md",
         claim="| non-stop | 0.1 | 50 | 800 | 3.78e-04 | 9.85e-06 | 2.03 |",
         test="tests/rotor/dynamics/test_friction_events.py::test_den_hartog_non_stop_amplitude_converges_at_second_order",
         tier="default"),
    dict(report="reports/published/perf-friction-events.md",
         claim="| stick-slip | 0.1 | 25 | 3200 | 3.35e-04 | 7.06e-07 | 2.03 |",
         test="tests/rotor/dynamics/test_friction_events.py::test_den_hartog_stick_slip_amplitude_converges_at_second_order",
         tier="default"),
    dict(report="reports/published/perf-friction-events.md", claim="| 50 | 100 | 6.7436e-04 | 2.77e-05 | 2.90e-16 |",
         test="tests/rotor/dynamics/test_friction_events.py::test_undamped_den_hartog_reaches_a_periodic_state",
         tier="default"),

    # perf-hb.md: the benchmark's rotor is the conformal default of test_branch_through_folds (every orbit within
    # 1e-10 of the continuous closed form, each turning point within 0.1 %, over a wider range)
    dict(report="reports/published/perf-hb.md", claim="its largest error is 6.1e-14, the Newton tolerance",
         test="tests/rotor/periodic/test_harmonic_balance.py::test_branch_through_folds_matches_the_closed_form",
         tier="default"),
    dict(report="reports/published/perf-hb.md",
         claim="the closed form's fold and grazing fold (374.736083, 446.448723 rad/s)",
         test="tests/rotor/periodic/test_harmonic_balance.py::test_branch_through_folds_matches_the_closed_form",
         tier="default"),

    # perf-hb-scenes.md: the family of the run's seed; the slow test checks every orbit within 1e-10 of the continuous
    # closed form and the end reached on ten rotors of the commit's seed (the default run: one)
    dict(report="reports/published/perf-hb-scenes.md", claim="| HB | 10 | 1442 | 3.57e-14 | 0.00e+00 |",
         test="tests/rotor/periodic/test_hb_scenes.py::test_hb_branches_of_ten_random_scenes_are_the_continuous_closed_form",
         tier="slow"),
    dict(report="reports/published/perf-hb-scenes.md", claim="Every HB stop: ['end reached']",
         test="tests/rotor/periodic/test_hb_scenes.py::test_hb_branch_of_one_random_scene_is_the_continuous_closed_form",
         tier="default"),

    # perf-grazing-family.md: the family of the run's seed; the slow test checks the same bounds on the commit's seed
    dict(report="reports/published/perf-grazing-family.md", claim="no restart, the end reached): **20 of 20**.",
         test="tests/rotor/studies/test_grazing_family.py::test_ten_random_rotors_both_ways", tier="slow"),
    dict(report="reports/published/perf-grazing-family.md", claim="every middle-branch orbit unstable, every orbit within 1e-6",
         test="tests/rotor/studies/test_grazing_family.py::test_one_random_rotor_one_way_through_every_corner_and_fold",
         tier="default"),
    # perf-grazing.md
    dict(report="reports/published/perf-grazing.md",
         claim="Closed form (warped): grazing 279.570680 rad/s, grazing fold 374.300780 rad/s, fold 445.873221 rad/s.",
         test="tests/rotor/periodic/test_grazing.py::test_grazings_and_fold_match_the_warped_closed_form",
         tier="default"),
    dict(report="reports/published/perf-grazing.md", claim="| down | plain | step below ds_min | 16 | 0 |",
         test="tests/rotor/periodic/test_grazing.py::test_plain_continuation_stops_at_the_grazing_fold", tier="default"),
    dict(report="reports/published/perf-grazing.md", claim="| down | grazing | end reached | 63 | 0 | 200.0000 |",
         test="tests/rotor/periodic/test_grazing.py::test_both_sweeps_pass_every_corner_without_restart", tier="default"),
    dict(report="reports/published/perf-grazing.md",
         claim="grazing_fold 374.300780 (2.9e-11); fold 445.873216 (1.3e-08); grazing 279.570680 (1.5e-10) | 7.5e-10 |",
         test="tests/rotor/periodic/test_grazing.py::test_whole_curve_within_1e_6_of_the_warped_closed_form",
         tier="default"),

    # perf-integrators.md
    dict(report="reports/published/perf-integrators.md",
         claim="max over time of ‖q_ref − q_prod‖₂ / max ‖q_prod − Δq_m‖₂ = **8.29e-07**",
         test="tests/rotor/dynamics/test_dynamics_constraints.py::test_paper_and_production_scheme_agree",
         tier="default"),
    dict(report="reports/published/perf-integrators.md",
         claim="| clearance 0.001 mm | q = 0 | 0 / 0 | 2 / 87 | 0 / 0 | 1 / 86 |",
         test="tests/rotor/dynamics/test_dynamics_constraints.py::test_the_two_fixes_are_what_remove_chatter_and_stalls",
         tier="default"),

    # perf-law-vs-fem.md
    dict(report="reports/published/perf-law-vs-fem.md", claim="at a maximum error of 0.27 % (fine FEM: 0.0034 %)",
         test="tests/docs/test_gallery.py::test_calibrated_law", tier="default"),

    # perf-located-monodromy.md: the errors at 8 400 / 10 500 / 12 000 rpm, each checked below 1e-6 in the default run
    dict(report="reports/published/perf-located-monodromy.md", claim="| 8.8e-08 | 3.5e-07 | 0.980533 / 0.980533 |",
         test="tests/rotor/dynamics/test_period_map_events.py::test_table4_located_monodromy_through_stick_releases_and_contact_onsets",
         tier="default"),
    dict(report="reports/published/perf-located-monodromy.md", claim="| 5.3e-08 | 2.1e-07 | 0.981604 / 0.981604 |",
         test="tests/rotor/dynamics/test_period_map_events.py::test_table4_located_monodromy_through_stick_releases_and_contact_onsets",
         tier="default"),
    dict(report="reports/published/perf-located-monodromy.md", claim="| 4.2e-08 | 4.1e-08 | 0.987026 / 0.987026 |",
         test="tests/rotor/dynamics/test_period_map_events.py::test_table4_located_monodromy_through_stick_releases_and_contact_onsets",
         tier="default"),

    # perf-monodromy-ladder.md: each state's errors (both routes within 1e-6, the level-by-level one within the whole's
    # + 1e-7, fewer replays), checked by the ladder tests at T/256 (default) and T/2240 (slow)
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 7000 | 256 | 25424 / 18888 | 6.0e-08 | 6.4e-08 | 4.1e-09 | 1.1e-07 |",
         test="tests/rotor/dynamics/test_period_map_events.py::test_ladder_level_by_level_is_as_accurate_as_the_whole_ladder",
         tier="default"),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 7000 | 2240 | 26012 / 19692 | 1.6e-07 | 1.6e-07 | 3.1e-09 | 3.1e-07 |",
         test="tests/rotor/dynamics/test_period_map_events.py::test_ladder_level_by_level_is_as_accurate_as_the_whole_ladder_at_2240_steps",
         tier="slow"),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 9000 | 256 | 9772 / 8328 | 4.2e-08 | 4.2e-08 | 7.8e-10 | 1.4e-07 |",
         test="tests/rotor/dynamics/test_period_map_events.py::test_ladder_level_by_level_is_as_accurate_as_the_whole_ladder",
         tier="default"),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 9000 | 2240 | 9338 / 7806 | 1.4e-07 | 1.4e-07 | 2.8e-11 | 3.0e-07 |",
         test="tests/rotor/dynamics/test_period_map_events.py::test_ladder_level_by_level_is_as_accurate_as_the_whole_ladder_at_2240_steps",
         tier="slow"),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 12000 | 256 | 12712 / 9532 | 4.2e-08 | 4.2e-08 | 5.1e-09 | 8.6e-08 |",
         test="tests/rotor/dynamics/test_period_map_events.py::test_ladder_level_by_level_is_as_accurate_as_the_whole_ladder",
         tier="default"),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 12000 | 2240 | 15666 / 12404 | 7.3e-08 | 7.3e-08 | 2.1e-09 | 1.2e-07 |",
         test="tests/rotor/dynamics/test_period_map_events.py::test_ladder_level_by_level_is_as_accurate_as_the_whole_ladder_at_2240_steps",
         tier="slow"),

    # perf-period-map.md
    dict(report="reports/published/perf-period-map.md",
         claim="differs from the exact one by 1.2e-06 of its largest entry in those scaled coordinates, through the revolution's 4 stick/slip switches",
         test="tests/rotor/dynamics/test_period_map.py::test_table4_monodromy_through_stick_slip_switches_equals_finite_differences",
         tier="default"),

    # perf-richardson.md
    dict(report="reports/published/perf-richardson.md",
         claim="with 128 then 256 steps it is within 1e-6 everywhere on the curve, folds included",
         test="tests/rotor/periodic/test_richardson.py::test_extrapolated_orbits_within_1e_6_of_the_continuous_time_closed_form",
         tier="default"),

    # perf-shooting.md
    dict(report="reports/published/perf-shooting.md",
         claim="**1X–5X within 1e-4 of the transient: holds** (2.3e-05; from the transient's end state 2.3e-05)",
         test="tests/rotor/studies/test_orbit.py::test_shooting_from_the_transient_state_reproduces_its_harmonics",
         tier="default"),
    dict(report="reports/published/perf-shooting.md",
         claim="2 neutral multipliers (a face stuck through the orbit: a continuum of orbits",
         test="tests/rotor/studies/test_orbit.py::test_a_stuck_face_makes_a_continuum_and_the_cold_orbit_is_the_transients_member",
         tier="default"),

    # rotor-mesh.md
    dict(report="reports/published/rotor-mesh.md",
         claim="puts the third forward critical speed at 9608 rpm, +9.9 % from the converged 8744 rpm",
         test="tests/test_published_rotor.py::test_paper_mesh_puts_the_third_critical_speed_ten_percent_high",
         tier="default"),
    dict(report="reports/published/rotor-mesh.md",
         claim="2 elements per segment bring every critical speed within 1 % (0.63 % worst)",
         test="tests/test_published_rotor.py::test_paper_mesh_puts_the_third_critical_speed_ten_percent_high",
         tier="default"),
    dict(report="reports/published/rotor-mesh.md", claim="(16 elements: all four modes within 0.1 %)",
         test="tests/rotor/linear/test_rotor_closed_forms.py::test_pinned_pinned_euler_bernoulli_first_four_modes",
         tier="default"),
    dict(report="reports/published/rotor-mesh.md", claim="48 elements bring mode 4 within 0.1 %",
         test="tests/rotor/linear/test_rotor_closed_forms.py::test_pinned_pinned_timoshenko_first_four_modes",
         tier="default"),

    # rotor-misalignment.md
    dict(report="reports/published/rotor-misalignment.md",
         claim="| 2F on the joint, to ground through the bearings (like an unbalance force) | 0.0152 | 0.1621 | 0.3368 |",
         test="tests/test_published_rotor.py::test_rotor_misalignment_report_is_what_the_builder_writes_now",
         tier="default"),
    dict(report="reports/published/rotor-misalignment.md",
         claim="only the moment pair acts (on the angular spring) | 0.0046 | 0.0404 | 0.1020 |",
         test="tests/test_published_rotor.py::test_rotor_misalignment_report_is_what_the_builder_writes_now",
         tier="default"),

    # rotor-table4.md
    dict(report="reports/published/rotor-table4.md", claim="| 1 | 40.54 | 2433 |",
         test="tests/test_published_rotor.py::test_rotor_table4_report_is_what_the_builder_writes_now", tier="default"),
    dict(report="reports/published/rotor-table4.md", claim="| 1X | 9608 | 160.14 | forward |",
         test="tests/test_published_rotor.py::test_rotor_table4_report_is_what_the_builder_writes_now", tier="default"),
    dict(report="reports/published/rotor-table4.md", claim="2441 rpm (disk1 0%, disk2 52%, s (support) 41%)",
         test="tests/test_published_rotor.py::test_rotor_table4_report_is_what_the_builder_writes_now", tier="default"),

    # rotor-testrig.md
    dict(report="reports/published/rotor-testrig.md",
         claim="| 1: localized at disk 2 | 3319 | 2596 (-21.8%) | 3317 (-0.1%) | 3221 (-2.9%) |",
         test="tests/test_published_rotor.py::test_testrig_critical_speeds_under_the_three_readings", tier="default"),
    dict(report="reports/published/rotor-testrig.md",
         claim="| 2: localized at disk 1 | 5184 | 7405 (+42.8%) | 7208 (+39.0%) | 5184 (fitted) |",
         test="tests/test_published_rotor.py::test_testrig_critical_speeds_under_the_three_readings", tier="default"),

    # section5-readings.md (the comparison protocol, reports/protocols/section5-readings.toml)
    dict(report="reports/published/section5-readings.md",
         claim="`opposed-at-joint-long-sleeve` scores highest under the primary weighting (equal: 15), the scene's reading.",
         test="tests/reports/test_readings_protocol.py::test_published_scores_are_the_protocols_on_the_published_verdicts",
         tier="default"),
    dict(report="reports/published/section5-readings.md",
         claim="scores highest under 4 (point B x2, A1-A3 one symptom (tied), paper's mesh only, converged mesh only) "
               "and not under 2: point B only (`inertial-at-joint-long-sleeve`); rows the control fails "
               "(`inertial-at-joint-long-sleeve`).",
         test="tests/reports/test_readings_protocol.py::test_published_scores_are_the_protocols_on_the_published_verdicts",
         tier="default"),
    dict(report="reports/published/section5-readings.md",
         claim="The no-excitation control scores 8 under the primary weighting.",
         test="tests/reports/test_readings_protocol.py::test_published_scores_are_the_protocols_on_the_published_verdicts",
         tier="default"),
    dict(report="reports/published/section5-readings.md",
         claim="Rows left unscored (met by every reading and the control on both meshes): B4.",
         test="tests/reports/test_readings_protocol.py::test_published_scores_are_the_protocols_on_the_published_verdicts",
         tier="default"),
    dict(report="reports/published/section5-readings.md",
         claim="(contact 45 %, r1 and r2 cross δ0: B1 and B2 met)",
         test="tests/reports/test_readings_protocol.py::test_every_case_recomputed_gives_the_published_verdicts",
         tier="slow"),
    dict(report="reports/published/section5-readings.md",
         claim="`inertial-at-joint-long-sleeve` scores 9 against 7",
         test="tests/reports/test_readings_protocol.py::test_published_scores_are_the_protocols_on_the_published_verdicts",
         tier="default"),

    # study-bifurcation.md (a 40-minute run: its reading against its published data)
    dict(report="reports/published/study-bifurcation.md", claim="It reached 18 000 rpm (788 orbits, 1 911 s",
         test="tests/test_published_studies.py::test_branch_reports_agree_with_the_published_branch_data",
         tier="default"),
    dict(report="reports/published/study-bifurcation.md", claim="peaks at 148 mm/s at 4 291 rpm",
         test="tests/test_published_studies.py::test_branch_reports_agree_with_the_published_branch_data",
         tier="default"),
    dict(report="reports/published/study-bifurcation.md", claim="**Restarts: 18, each reported",
         test="tests/test_published_studies.py::test_branch_reports_agree_with_the_published_branch_data",
         tier="default"),
    dict(report="reports/published/study-bifurcation.md", claim="at 82 mm/s at 2 443 rpm",
         test="tests/test_published_studies.py::test_branch_reports_agree_with_the_published_branch_data",
         tier="default"),

    # study-cascade.md
    dict(report="reports/published/study-cascade.md",
         claim="1X is 79.2 % (median over speeds and locations) of the 1X–5X sum; lowest 25.0 %",
         test="tests/test_published_studies.py::test_cascade_statements_follow_from_its_committed_csv",
         tier="default"),
    dict(report="reports/published/study-cascade.md",
         claim="**Loose-support regime by speed:** 0–5100 rpm stick; 5400–6000 rpm contact; 6300–18000 rpm impact.",
         test="tests/test_published_studies.py::test_cascade_statements_follow_from_its_committed_csv",
         tier="default"),
    dict(report="reports/published/study-cascade.md",
         claim="sum 3X–5X ≥ 9 000 rpm, ratio to disk 1: disk 2 median 11.6, support median 15.2",
         test="tests/rotor/studies/test_study_slow.py::test_figure12_cascade_61_speeds_two_processes", tier="slow"),
    dict(report="reports/published/study-cascade.md",
         claim="2X/1X below 9 000 rpm: disk 1 median 0.0534, disk 2 0.113, support 0.115",
         test="tests/rotor/studies/test_study_slow.py::test_figure12_cascade_61_speeds_two_processes", tier="slow"),

    # study-findings.md
    dict(report="reports/published/study-findings.md",
         claim="Point A (Fig. 13, 4 500 rpm), paper's mesh: agrees: 2X/1X disk 1 0.005, disk 2 0.040, support 0.101",
         test="tests/test_published_studies.py::test_findings_points_a_and_b_on_the_paper_mesh", tier="default"),
    dict(report="reports/published/study-findings.md", claim="| paper | 10500 | impact (56 % contact, 0 % stuck) |",
         test="tests/test_published_studies.py::test_findings_points_a_and_b_on_the_paper_mesh", tier="default"),
    dict(report="reports/published/study-findings.md", claim="| 2/segment | 10500 | impact (46 % contact, 0 % stuck) |",
         test="tests/test_published_studies.py::test_findings_points_a_and_b_on_the_converged_mesh", tier="default"),
    dict(report="reports/published/study-findings.md",
         claim="2 elements per segment 2441, 4269, 8799 (third +9.2 % on the paper's mesh)",
         test="tests/test_published_rotor.py::test_paper_mesh_puts_the_third_critical_speed_ten_percent_high",
         tier="default"),
    dict(report="reports/published/study-findings.md",
         claim="| §5.3.1 (1): below 9 000 rpm no relative displacement between bearing and support (faces stuck) | paper | agrees (15 agree, 0 no effect, 0 disagree; 15 of 15 periodic) | disagrees (2 agree, 0 no effect, 12 disagree; 14 of 14 periodic) |",
         test="tests/test_published_studies.py::test_findings_verdicts_follow_from_the_committed_study_tables",
         tier="default"),
    dict(report="reports/published/study-findings.md",
         claim="5400 disagrees: effect -100.0 % (threshold 0.0 %); stuck 0 %, contact 100 %",
         test="tests/rotor/studies/test_study_paper.py::test_finding_as_published_at_a_few_speeds", tier="default"),
    dict(report="reports/published/study-findings.md",
         claim="9000 disagrees: effect -0.9 % (threshold 0.8 %); 2X disk 2",
         test="tests/rotor/studies/test_study_paper.py::test_finding_as_published_at_a_few_speeds", tier="default"),
    dict(report="reports/published/study-findings.md",
         claim="| §5.2 (Fig. 16): ignoring the tilt markedly (≥ 30 %) reduces 3X–5X at disk 2 and the support | paper | — | — | agrees (11 agree, 0 no effect, 0 disagree; 9 of 11 periodic) | no effect (0 agree, 7 no effect, 3 disagree; 1 of 10 periodic) |",
         test="tests/rotor/studies/test_study_paper.py::test_finding_as_published_in_every_band", tier="slow"),
    dict(report="reports/published/study-findings.md",
         claim="differ by less than 0.1 of it, 5 µm) at 13 of 22: 5400–12600 rpm",
         test="tests/test_published_studies.py::test_clearance_geometry_follows_from_its_committed_csv", tier="default"),
    dict(report="reports/published/study-findings.md",
         claim="differ by less than 0.1 of it, 5 µm) at 12 of 22: 5400–12000 rpm",
         test="tests/test_published_studies.py::test_clearance_geometry_follows_from_its_committed_csv", tier="default"),
    dict(report="reports/published/study-findings.md",
         claim="the contact force's 2X changes between -25 % and +336 % (57 / 92 / 92 N at 9000 rpm), the support's 2X displacement between -1.4 % and +4.0 %",
         test="tests/test_published_studies.py::test_clearance_geometry_follows_from_its_committed_csv", tier="default"),
    dict(report="reports/published/study-findings.md",
         claim="the contact force's 2X changes between -27 % and +110 % (148 / 104 / 300 N at 9000 rpm), the support's 2X displacement between -0.2 % and +3.0 %",
         test="tests/test_published_studies.py::test_clearance_geometry_follows_from_its_committed_csv", tier="default"),
    dict(report="reports/published/study-findings.md",
         claim="went from 18 to 40 periodic speeds of 61",
         test="tests/test_published_studies.py::test_findings_reading_counts_of_periodic_speeds_are_the_cascades",
         tier="default"),

    # study-map.md
    dict(report="reports/published/study-map.md",
         claim="Counts: beyond law 2, contact 9, impact 43, stick 11 of 65 points; 27 without a periodic steady state.",
         test="tests/test_published_studies.py::test_study_map_counts_follow_from_its_committed_csv", tier="default"),

    # study-params.md
    dict(report="reports/published/study-params.md",
         claim="2X decreases, 3X does not decrease → does not agree",
         test="tests/test_published_studies.py::test_params_statements_follow_from_its_committed_csv", tier="default"),
    dict(report="reports/published/study-params.md", claim="1X varies by at most 5.4 % across δ",
         test="tests/test_published_studies.py::test_params_statements_follow_from_its_committed_csv", tier="default"),

    # study-point.md (rebuilt whole)
    dict(report="reports/published/study-point.md",
         claim="| 4500 | stick | 0 | True (1) | 4.60e-03 | 1.01e-01 | 1.73e-06 | 1.42e-04 | 9.94e-05 | 0.443 |",
         test="tests/test_published_studies.py::test_study_point_report_is_what_points_a_and_b_give_now",
         tier="default"),
    dict(report="reports/published/study-point.md",
         claim="| 10500 | impact | 56 | True (1) | 1.89e-02 | 6.11e-01 | 7.79e-03 | 6.18e-02 | 8.01e-02 | 1.015 |",
         test="tests/test_published_studies.py::test_study_point_report_is_what_points_a_and_b_give_now",
         tier="default"),

    # study-runup.md
    dict(report="reports/published/study-runup.md", claim="1536340 steps of 13.0 µs",
         test="tests/reports/test_budget.py::test_the_runup_estimate_counts_the_steps_the_runup_takes", tier="default"),
    dict(report="reports/published/study-runup.md", claim="- disk 1: largest 1X 82.2 mm/s at 4296 rpm.",
         test="tests/rotor/studies/test_study_slow.py::test_runup_passes_the_critical_speeds_with_continuous_phase",
         tier="slow"),

    # study-sensitivity.md
    dict(report="reports/published/study-sensitivity.md",
         claim="2X fell with δ0 in 18/67 and 3X in 16/67; 2X rose with δ in 65/66 and 3X in 29/66; Σ3X–5X was ≥ 30 % lower without tilt in 58/66.",
         test="tests/test_published_studies.py::test_sensitivity_trend_counts_follow_from_the_committed_points",
         tier="default"),
    dict(report="reports/published/study-sensitivity.md",
         claim="| base | I I I | no 1/3 (collision 1/3; all pts 1/3); 3X ratio 1.02 |",
         test="tests/rotor/studies/test_study_sensitivity.py::test_reduced_study_through_the_sweep_reproduces_the_published_base_numbers",
         tier="slow"),

    dict(report="README.md", claim="(end-face demand at most 0.378 of μN at 10 000 N)",
         test="tests/rotor/studies/test_section6.py::test_the_largest_demand_at_the_papers_steps_is_the_published_one",
         tier="default"),
    dict(report="README.md", claim="hits its bore there with δ0 0.01 mm (contact 57 % at 3 220 rpm)",
         test="tests/rotor/studies/test_section6.py::test_the_fitted_rig_reaches_its_bore_with_the_smaller_clearance",
         tier="slow"),
    # study-testrig.md (Section 6: the rig's points, the statements judged, the stick-margin scan)
    dict(report="reports/published/study-testrig.md",
         claim="| `paper-table5-testrig` | 3600 | 0.01 | 2 | stick | 0 | 100 |",
         test="tests/test_published_studies.py::test_testrig_points_reproduce_the_published_table", tier="slow"),
    dict(report="reports/published/study-testrig.md",
         claim="| yes | 0.1197 | 0.03308 |",
         test="tests/test_published_studies.py::test_testrig_points_reproduce_the_published_table", tier="slow"),
    dict(report="reports/published/study-testrig.md",
         claim="| `paper-table5-testrig-C` | 3220 | 0.01 | 2 | impact | 57 | 0 | 1.15 | yes | 1.638 | 4.657 |",
         test="tests/rotor/studies/test_section6.py::test_the_fitted_rig_reaches_its_bore_with_the_smaller_clearance",
         tier="slow"),
    dict(report="reports/published/study-testrig.md",
         claim="| `paper-table5-testrig-C` | 3220 | 0.05 | 2 | slip | 0 | 0 | 0.499 |",
         test="tests/rotor/studies/test_section6.py::test_the_fitted_rig_reaches_its_bore_with_the_smaller_clearance",
         tier="slow"),
    dict(report="reports/published/study-testrig.md", claim="Verdicts: 4 agree, 2 no effect, 6 disagree.",
         test="tests/rotor/studies/test_section6.py::test_published_rig_verdicts_follow_from_their_effect_and_threshold",
         tier="default"),
    dict(report="reports/published/study-testrig.md", claim="the largest demand there is 0.378 of μN",
         test="tests/rotor/studies/test_section6.py::test_the_largest_demand_at_the_papers_steps_is_the_published_one",
         tier="default"),
    dict(report="reports/published/study-testrig.md",
         claim="| B frame still | 2.05 (3320 rpm: opposed-at-centring-surfaces, sleeve x2.8, δ 3 mm) | 3250–3390 rpm in 18 of 18 cases |",
         test="tests/rotor/studies/test_section6.py::test_the_scan_reproduces_the_published_summary", tier="slow"),
    dict(report="reports/published/study-testrig.md",
         claim="| C criticals fitted | 1.84 (3220 rpm: opposed-at-centring-surfaces, sleeve x2.8, δ 3 mm) | 3170–3280 rpm in 18 of 18 cases |",
         test="tests/rotor/studies/test_section6.py::test_the_scan_reproduces_the_published_summary", tier="slow"),
    dict(report="reports/published/study-testrig.md", claim="the largest demand there is 0.385 or 0.379 of μN",
         test="tests/rotor/studies/test_section6.py::test_the_largest_demand_at_the_papers_steps_is_the_published_one",
         tier="default"),
    dict(report="reports/published/study-testrig.md", claim="at 3 600 rpm 174.5 N against 177.4 N peak",
         test="tests/rotor/studies/test_section6.py::test_stick_margin_is_the_nonlinear_stuck_records_face_force",
         tier="slow"),
)

#: Markdown reports of reports/published/ without a registered claim: (file, reason)
NOT_CLAIMS = (
    ("reports/published/claims.md", "this registry's own listing, generated by benchmarks/list_claims.py"),
    ("reports/published/perf-compile.md", "wall times only (compile vs cache load); tests never assert wall times"),
    ("reports/published/perf-cold-compile.md", "wall and compile times of a first simulate and orbit in an empty numba "
     "cache, against the same jobs warm; tests never assert wall times"),
    ("reports/published/perf-estimates.md", "estimated against measured wall times of orbit and branch, and their "
     "ratios: a wall-time ratio moves with the machine's load and cannot be asserted by a test (the orbit-count model "
     "is tested: tests/reports/test_budget_orbits.py)"),
    ("reports/published/perf-dask.md", "wall-time throughput only; the README's 0.999× is checked against it"),
    ("reports/published/perf-laws.md", "evaluations per second only; tests never assert wall times"),
    ("reports/published/perf-step-loop.md", "µs per step against commit 291495d's code, which the tree no longer has"),
    ("reports/published/perf-test-suite.md", "wall times and load of the test command's runs; their pass or fail is "
                                             "the suite itself"),
    ("reports/published/perf-monodromy-random-steel-in-aluminium.md",
     "one benchmark sample of 20 speeds (seed 1224269704, at 6cadf64, differenced blocks along the carried "
     "sensitivities): 19 of 19 orbits within 1e-6 of the derivative of their map's piece (largest 5.3e-7, at "
     "10 504.7 rpm against a reference converged to 6.4e-7) and one (9 063.3 rpm) whose reference did not converge; "
     "the draws before: seed 41420051 (80e59d2, by components) 20 of 20 (largest 6.1e-7), seed 3613193897 (ddbf938) 16 of 16 where the reference converged and 4 orbits (6 105.5, 7 784.0, "
     "8 203.9, 9 026.5 rpm) where none did (the map jumps within 1e-7 of the state: at 8 203.9 rpm seven columns "
     "at every step from 3e-8 to 1e-6), seed 4269954154 (1b1a63c) 20 of 20, seed 2376377958 one miss (1.15e-6 "
     "against a reference converged to 4.8e-7) and one unresolved; a sample, not a claim: each run draws a new "
     "seed, and the default run checks one random speed of this scene (test_monodromy_random_speeds.py)"),
    ("reports/published/perf-branch-switches-projection.md",
     "one run of the Table 4 branch with the friction solved by projection (5ece314, load 1.7-2.0): end reached, 504 "
     "orbits, 328 s, 21 restarts (8 transient, 13 cold; 20 in stuck faces' continua at 2 411-2 440, 4 223-4 292 and "
     "5 058-5 184 rpm, one face at its friction limit), 445 rpm no orbit covers (5 184.5-5 630.0 rpm); every "
     "verified point's residual below 5e-10; a benchmark sample of one run, not a claim (its wall time moves with "
     "the load)"),
    ("reports/published/perf-branch-switches-projection-centred-back-fill.md",
     "one run of the Table 4 branch with the friction solved by projection, each friction-held family's centred "
     "member and far restarts followed back (7b59abc, load 1.8 at start, 1.0 at end, tests running beside it part of the time): end "
     "reached, 629 orbits, 510 s, 9 restarts (3 secant, 1 transient, 4 cold, 1 step-grid; two of them the jumps "
     "past the folds at 5 196 and 16 929 rpm), 17.4 rpm no orbit covers; every verified point's residual below "
     "5e-10; a benchmark sample of one run, not a claim (its wall time moves with the load); the slow test "
     "test_family_centre.py::test_table4_past_the_stuck_family_end_restarts_land_within_50_rpm checks the stretch "
     "past the stuck family's end"),
    ("reports/published/perf-monodromy-random-projection.md",
     "one benchmark sample of 20 speeds with the friction solved by projection (seed 1344113174, at 6579e29): 20 of "
     "20 orbits within 1e-6 of central differences of their map (largest 1.6e-7; one orbit, 16 609.8 rpm, from a "
     "neighbouring speed's); a sample, not a claim: each run draws a new seed, and the default run checks 3 other "
     "random speeds (test_friction_projection.py)"),
    ("reports/published/perf-monodromy-random-projection-steel-in-aluminium.md",
     "one benchmark sample of 20 speeds with the friction solved by projection (seed 1025849640, at 7794a84): 18 of "
     "18 orbits within 1e-6 where the central differences converged (largest 1.6e-7); at 9 007.9 and 12 288.2 rpm "
     "they did not (3.2e-2, 1.1e-6: a face at the disk's edge within the stencil, a kink of the map); a sample, "
     "not a claim: the default run checks 2 other random speeds (test_friction_projection.py)"),
    ("reports/published/perf-monodromy-random.md",
     "one benchmark sample of 20 speeds (seed 2272336857, at d1eafe5, consecutive differenced steps one block): 20 of "
     "20 orbits within 1e-6 of the derivative of their map's piece (largest 7.7e-7, the period-4 orbit at "
     "12 168.3 rpm against a reference converged to 8.9e-7; at 6 503.2 rpm one column from one-sided differences "
     "at 1e-8); the sample before (seed 3815215491, b5a1b37) 20 of 20, largest 2.3e-7; the earlier sample's "
     "unresolved speeds (seed 2426071970: 11 805.3 and 9 294.0 rpm) have a slow test; a sample, not a claim: each "
     "run draws a new seed, and the default run checks 3 other random speeds "
     "(test_monodromy_random_speeds.py)"),
)

#: numbers still stated that no test guards: dict(report=, claim=, reason=) each (the README's stale §5 findings
#: were rewritten from study-findings.md and are guarded, its unpublished wall times and sizes removed)
_CPU_RATIO = ("a CPU-time ratio of one benchmark run on a shared machine (it moves with the load); tests never assert "
              "timings, the benchmark measures them")
_LADDER_TIME = ("wall times of the period map with its monodromy, the whole ladder against level by level, and their "
                "ratio, from one benchmark run on a shared machine (they move with the load); tests never assert "
                "timings (the replay counts beside the errors are checked by the ladder tests)")
_GENERATED_SAMPLE = ("one benchmark sample of generated ring pairs, drawn with a new seed each run (printed in the "
                     "report); no test draws all 30, so the count is not reproduced by the suite (the slow tests of "
                     "tests/fem_reference/plane/test_generated_bars.py re-solve pairs of the seed published before, "
                     "2988782516: the first three, and 20, 22 and 29, whose misses the bulk-refined levels fixed; and 1928108429's "
                     "pair 27 and 627535865's pair 18, whose misses a fifth reference level settled)")
UNGUARDED = (
    dict(report="reports/published/law-tilt-correction.md",
         claim="Largest ratio of the tilt-corrected law to today's foundation law: 1.95 (target: at most 2).",
         reason="a ratio of wall times of the compiled kernel, measured on a shared machine (the load is printed)"),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 7000 | 256 | 0.500 | 0.398 | 1.26× |", reason=_LADDER_TIME),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 7000 | 2240 | 0.556 | 0.460 | 1.21× |", reason=_LADDER_TIME),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 9000 | 256 | 0.259 | 0.232 | 1.12× |", reason=_LADDER_TIME),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 9000 | 2240 | 0.246 | 0.222 | 1.11× |", reason=_LADDER_TIME),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 12000 | 256 | 0.316 | 0.255 | 1.24× |", reason=_LADDER_TIME),
    dict(report="reports/published/perf-monodromy-ladder.md", claim="| 12000 | 2240 | 0.364 | 0.313 | 1.16× |", reason=_LADDER_TIME),
    dict(report="reports/published/fem2d-adaptive.md",
         claim='Points: 60 (30 pairs); with a bar: 60 (100%); outside their bar: 1 of 60 (1.7%); refused (no bar): 0.',
         reason=_GENERATED_SAMPLE),
    dict(report="reports/published/fem2d-adaptive.md",
         claim='References whose own uncertainty exceeds half the bar they check: 19 of 60;',
         reason=_GENERATED_SAMPLE),
    dict(report="reports/published/fem2d-adaptive.md",
         claim="points outside their bar plus the reference's own uncertainty: 0 of 60.",
         reason=_GENERATED_SAMPLE),
    dict(report="reports/published/study-findings.md", claim="29 of the 513 speed verdicts and six band verdicts change",
         reason="a sensitivity of the verdicts to the spectral floor's definition (root mean square instead of the "
                "largest value), computed once from the study directories' spectra, which are not committed; no "
                "test has the spectra to recompute it"),
    dict(report="reports/published/study-findings.md",
         claim="moved by at most 7.8e-6 of their station's largest harmonic",
         reason="the former run's amplitudes against this run's, at the 10 speeds whose detection moved (commit "
                "e299cad's study-cascade*.csv against this commit's); a comparison of two runs, not a property of one"),
    dict(report="reports/published/perf-hb.md", claim="HB took 0.318 times pyHarm-os's CPU on the same branch",
         reason=_CPU_RATIO),
    dict(report="reports/published/perf-hb-scenes.md", claim="| 1.69 | 0.291 (on 8) |", reason=_CPU_RATIO),
    dict(report="reports/published/perf-hb-scenes.md", claim="HB / pyHarm-os CPU per rotor: 0.23 to 0.37",
         reason=_CPU_RATIO),
    dict(report="reports/published/perf-hb-scenes.md", claim="| shooting N | 3 | 190 | 1.34e-04 |",
         reason="the step's distance from the CONTINUOUS closed form, measured by the benchmark only (the tests "
                "bound shooting against the scheme-consistent closed form: tests/rotor/studies/test_grazing_family.py)"),
    dict(report="reports/published/perf-hb-scenes.md", claim="| 15000 | 256, 12.8, False, 1.0 | 32 | True | 1.72 | "
                                                              "2.1e-08 | 2.6e-04 | 2.4e-08 |",
         reason="Table 4 HB against shooting and Richardson at one speed: 13-78 s of shooting per speed, run by "
                "the benchmark only; no test runs it"),
)
