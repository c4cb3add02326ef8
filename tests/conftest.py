"""Settings shared by every test: no test depends on how fast the machine is.

* Hypothesis's default per-example deadline (200 ms) and its "too slow" health check measure wall time, so they
  fail on a loaded machine (CI runs two workers on two cores, often beside other jobs): both are off for every
  ``@given`` test (the ``timeless`` profile, loaded here).
* Progress lines (:mod:`qcpp.cli.progress`) appear after a second of work on a pipe, so whether a command printed one
  depends on the machine's load: they are off (``QCPP_PROGRESS=off``, inherited by subprocesses); the tests of
  progress itself turn them on with ``QCPP_PROGRESS_INTERVAL=0`` (a line at every step, no clock involved).
* The README's test command has a time budget (four minutes on two cores beside a CPU-bound job), so the default
  tests that each take about a CPU-second or more run with the heavy step instead (:data:`SLOW_DEFAULT`: CI
  runs both steps, so every assertion still runs on every change); each behaviour they check keeps faster tests
  in the default run (other parameters of the same test, or the unit tests of the same module).
* At the session's end pytest collects garbage five times over (to report exceptions raised in finalizers); with
  the session's caches of compiled circuits alive that re-scanned millions of objects five times. One collection
  here finds today's garbage; :func:`gc.freeze` then moves what survived it (live objects) out of the collector's
  sight, so pytest's collections scan only what finalizers left behind; the freeze ends at exit, so that the
  interpreter frees the survivors as usual (:mod:`tests.shutdown`: else nanobind extensions report them as leaks).
* pyqasm sets ``sys.tracebacklimit = 0`` for the whole process whenever it raises; every later traceback in that
  worker is then empty, and Hypothesis's ``find`` fails with an ``IndexError`` reading it. Every test leaves
  ``sys.tracebacklimit`` as it found it (:func:`_keep_the_traceback_limit`).
* Bytecode is cached (``sys.dont_write_bytecode = False``) even where ``PYTHONDONTWRITEBYTECODE`` is set, as it
  is on CI's image: otherwise every worker compiles the sources of qcpp and of the tests again (half of a
  collection's CPU time) and so does every ``python -m qcpp`` a test starts; with the caches written (in the
  ``__pycache__`` folders git ignores) the subprocesses and later runs read them. Subprocesses keep the variable
  as they found it: they read the caches the workers wrote.
* pytest-xdist hands tests to its workers in collection order, so a test of minutes that is collected last keeps
  one worker busy while the other has nothing left. The longest tests (:data:`LONGEST_FIRST`, the heavy step's
  largest CPU costs by ``benchmarks/cpu_durations.py``) are moved to the front, longest first; every other test
  keeps its place. CI's heavy step hands tests out one at a time (``--maxschedchunk 1``: by default xdist's first
  hand-out is a block of consecutive tests per worker, which would give one worker all the long ones), so each
  worker takes the next long test when it is free.
* The README's test command distributes by groups (``--dist loadgroup``): the tests of one
  ``pytest.mark.xdist_group`` run on one worker, the others one by one as before. Tests that run quimb are in the
  group ``quimb``: on a fresh install numba compiles quimb's kernels the first time a process imports or runs them
  (about 70 CPU-seconds), so the group keeps that cost on one worker, and no test module imports quimb at collection
  (``tensor_test.py`` checks it). Modules whose tests share a costly module fixture (a compile for a named device)
  are a group each, so the fixture is built once. ``python benchmarks/suite_under_load.py --cold`` measures the
  fresh-install case. The heavy step keeps one-at-a-time hand-out (``--maxschedchunk 1``, below), where the groups
  do not apply.
* On pytest-xdist's workers Qiskit's Rust passes (SABRE, the O3 passes) run on one thread
  (``RAYON_NUM_THREADS=1``, inherited by subprocesses, unless already set): the workers keep every core busy
  already, and a thread pool per worker would only compete with the other worker for the same cores. Results do
  not depend on it (SABRE's trials are seeded); ``python benchmarks/worker_threads.py`` measures the time it saves.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator

import pytest
from hypothesis import HealthCheck, settings

from tests.collection_imports import QUIMB_AT_COLLECTION
from tests.shutdown import freeze_survivors

sys.dont_write_bytecode = False  # before qcpp and the test modules are imported: see the module docstring

settings.register_profile("timeless", deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("timeless")

os.environ["QCPP_PROGRESS"] = "off"
if os.environ.get("PYTEST_XDIST_WORKER"):  # before Qiskit starts its thread pool: see the module docstring
    os.environ.setdefault("RAYON_NUM_THREADS", "1")


@pytest.fixture(autouse=True)
def _keep_the_traceback_limit() -> Iterator[None]:
    """Undo a library's process-wide ``sys.tracebacklimit`` (pyqasm sets it to 0 when it raises)."""
    had, limit = hasattr(sys, "tracebacklimit"), getattr(sys, "tracebacklimit", None)
    yield
    if had:
        sys.tracebacklimit = limit
    elif hasattr(sys, "tracebacklimit"):
        del sys.tracebacklimit

SLOW_DEFAULT = frozenset(
    {
        "tests/api/interrupt_cache_test.py::test_an_interrupted_estimate_leaves_the_caches_sound[40]",
        "tests/api/cli_equality_test.py::test_routed_layouts_are_the_cli_s",
        "tests/api/validate_api_test.py::test_validate_s_plan_options_are_the_cli_s_plan_flags",
        "tests/api/validate_api_test.py::test_plan_options_are_validated_against_the_subspace_simulator"
        "[target=ft,initial=local_search,first_phase=False,phase=whole-space]",
        "tests/cli/compile_cli_test.py::test_default_qasm3_loads_in_qiskit_and_gives_our_state",
        "tests/cli/device_cli_test.py::test_estimate_device_adds_routed_fields_equal_to_compile",
        "tests/cli/device_cli_test.py::test_estimate_device_too_small_and_bound",
        "tests/cli/device_file_cli_test.py::test_a_device_file_routes_as_the_device_it_copies",
        "tests/cli/estimate_cli_test.py::test_formula",
        "tests/cli/inline_scenario_cli_test.py::test_formulas_come_as_latex_too",
        "tests/cli/guard_peaks_test.py::test_a_guards_memory_prediction_is_within_1_5x_of_the_measured_peak[simulate-default-4x5x2]",
        "tests/cli/guard_peaks_test.py::test_a_guards_memory_prediction_is_within_1_5x_of_the_measured_peak[validate-default-paper_3x3.toml]",
        "tests/cli/help_and_noise_test.py::test_an_unusable_cache_folder_is_named_once_and_the_run_proceeds[env0]",
        "tests/cli/help_and_noise_test.py::test_qcec_prints_nothing_of_its_own_and_claims_no_tolerance",
        "tests/cli/robustness_test.py::test_a_scenario_file_over_the_size_limit_is_refused_unread",
        "tests/cli/robustness_test.py::test_an_address_space_limit_below_the_need_is_refused_before_the_work",
        "tests/cli/robustness_test.py::test_four_concurrent_writers_of_one_file_leave_one_whole_output",
        "tests/cli/robustness_test.py::test_no_color_and_a_dumb_terminal_print_no_escape_codes",
        "tests/cli/robustness_test.py::test_no_home_and_an_unusable_cache_folder",
        "tests/cli/robustness_test.py::test_the_c_locale_with_non_ascii_paths",
        "tests/cli/startup_imports_test.py::test_the_probe_sees_a_heavy_import",
        "tests/cli/table_records_test.py::test_estimate_table_never_cuts_a_number",
        "tests/cli/table_width_test.py::test_no_table_line_is_wider_than_the_width",
        "tests/cli/table_width_test.py::test_the_issue_command_fits_100_columns",
        "tests/cli/table_width_test.py::test_wider_terminals_show_at_least_as_many_columns",
        "tests/compiler/call_graph_test.py::test_classes_list_the_planned_kinds_for_any_endpoints",
        "tests/compiler/device_file_test.py::test_a_file_with_ibm_fez_s_figures_compiles_as_ibm_fez",
        "tests/compiler/gadgets_test.py::test_every_partial_mixer_kind_is_exact_on_every_feasible_local_input",
        "tests/compiler/gadgets_test.py::test_reported_cost_equals_lowered_count_for_every_kind",
        "tests/compiler/junction_test.py::test_qiskit_o3_never_beats_our_lowering[3x3/1]",
        "tests/compiler/lowering_test.py::test_peephole_keeps_unitary_and_never_increases_counts",
        "tests/compiler/medial_test.py::test_estimate_device_grid_equals_compile",
        "tests/compiler/mixer_test.py::test_lowered_full_mixer_equals_high_level_on_basis_states[5-5-robots3]",
        "tests/compiler/phase_locality_test.py::test_device_compiles_default_to_the_spatial_layout",
        "tests/compiler/placement_search_test.py::test_heavy_hex_one_robot_meets_the_ratio_goal_exactly_as_estimated",
        "tests/compiler/routing_test.py::test_ibm_snapshot_matches_qiskit_ibm_runtime",
        "tests/compiler/qcec_test.py::test_every_partial_mixer_kind_is_proven_equivalent_to_its_lowering",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[3x3/3 p1]",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[3x4/2 pooled]",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[4x4 soft interior p2 depth]",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[4x4/2 budget 0]",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[4x4/2 p2]",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile_on_random_scenarios",
        "tests/compiler/window_classes_test.py::test_the_allocation_search_answers_by_its_cache_key"
        "[4x4 interior, 3x4/2]",
        "tests/compiler/window_classes_test.py::test_windows_of_one_class_share_one_routing",
        "tests/compiler/window_memo_test.py::test_a_window_routed_after_its_translation_routes_as_from_a_cold_memo",
        "tests/doctests_test.py::test_docstring_examples[qcpp.pipeline.device_compile]",
        "tests/docs_examples_test.py::test_the_page_s_python_examples_run_and_print_what_they_claim[README.md]",
        "tests/docs_examples_test.py::test_the_page_s_python_examples_run_and_print_what_they_claim"
        "[docs/getting-started.md]",
        "tests/docs_examples_test.py::test_the_page_s_python_examples_run_and_print_what_they_claim"
        "[docs/guide/compile.md]",
        "tests/docs_examples_test.py::test_the_page_s_python_examples_run_and_print_what_they_claim"
        "[docs/guide/hardware.md]",
        "tests/estimators/formulas_test.py::test_every_published_quantity_has_a_formula",
        "tests/estimators/formulas_test.py::test_structured_and_explicit_forms_agree",
        "tests/estimators/routed_test.py::test_the_window_sum_gives_compiles_counts_and_esp[4x5/2]",
        "tests/problem/cpsat_test.py::test_equals_dfs_on_random_scenarios",
        "tests/problem/explorability_test.py::test_hard_obstacle_components[3-4]",
        "tests/problem/explorability_test.py::test_hard_obstacle_components[4-4]",
        "tests/problem/qubo_solve_test.py::test_qubo_method_returns_the_proven_optimum[two_robots_5x5.toml]",
        "tests/problem/sbf_test.py::test_exact_sound_and_complete_with_hard_obstacles",
        "tests/problem/scenario_test.py::test_round_trip",
        "tests/simulate/ensemble_intervals_test.py::test_ensembles_md_pastes_the_script_s_tables",
        "tests/simulate/ensemble_intervals_test.py::test_the_readme_qaoa_table_holds_the_script_s_medians[README.md]",
        "tests/simulate/ensemble_intervals_test.py::test_the_readme_qaoa_table_holds_the_script_s_medians[docs/index.md]",
        "tests/simulate/experiments_test.py::test_script_quick_mode[qaoa_3x3-figures0]",
        "tests/simulate/experiments_test.py::test_script_quick_mode[qaoa_two_robots-figures2]",
        "tests/training/layerwise_test.py::test_mixer_warm_option_adds_one_start_per_level_and_counts_it",
        "tests/simulate/results_freshness_test.py::test_device_rows_match_the_router[3x3/1]",
        "tests/simulate/sparse_test.py::test_sparse_agrees_with_statevector",
        "tests/simulate/statevector_test.py::test_twenty_qubits",
        "tests/simulate/tensor_test.py::test_collapsed_ancilla_blocks_and_open_qubits_give_the_dense_amplitudes",
        "tests/api/bad_input_test.py::test_openqasm_2_of_an_unbound_circuit_names_the_symbols",
        "tests/cli/closed_stdout_test.py::test_broken_pipe_exits_quietly[estimate-json]",
        "tests/cli/closed_stdout_test.py::test_closed_stdout_exits_quietly[solve]",
        "tests/cli/estimate_cli_test.py::test_plot_is_written_atomically",
        "tests/cli/export_cli_test.py::test_solve_qubo_finds_the_optimum_of_two_robots_4x4",
        "tests/cli/guard_peaks_test.py::test_a_guards_memory_prediction_is_within_1_5x_of_the_measured_peak"
        "[compile--p 2-paper_3x3.toml]",
        "tests/cli/guard_peaks_test.py::test_a_guards_memory_prediction_is_within_1_5x_of_the_measured_peak"
        "[solve--m dfs-3x5x3]",
        "tests/io/caches_test.py::test_a_read_only_install_and_home_still_load_the_kernels",
        "tests/cli/device_cli_test.py::test_compile_zero_start_says_so_in_json_and_text",
        "tests/api/hardware_run_test.py::test_zero_start_off_offers_only_unitary_keeping_candidates_and_on_offers_and_chooses_cheaper_ones"
        "[twoq]",
        "tests/api/hardware_run_test.py::test_zero_start_off_offers_only_unitary_keeping_candidates_and_on_offers_and_chooses_cheaper_ones"
        "[esp]",
        "tests/api/hardware_run_test.py::test_a_zero_start_compile_decodes_to_feasible_paths_at_the_ideal_p_optimum",
        "tests/verify/verify_report_test.py::test_the_gadget_method_agrees_with_the_state_method_on_every_one_robot_3x3_field",
        "tests/compiler/first_phase_test.py::test_gamma_0_is_a_global_phase_on_a_basis_state[initial_path-2]",
        "tests/compiler/first_phase_test.py::test_gamma_0_is_a_global_phase_on_a_basis_state[local_search-1]",
        "tests/compiler/first_phase_test.py::test_a_superposition_of_paths_sees_gamma_0",
        "tests/compiler/first_phase_test.py::test_the_subspace_simulator_gives_the_state_of_the_circuit_without_it"
        "[3x3/1 local_search]",
        "tests/compiler/qasm_profiles_test.py::test_clients_load_the_unbound_circuit_without_the_first_phase_separator",
        "tests/compiler/prefetch_test.py::test_a_compile_routing_its_balance_window_ahead_is_the_compile_without"
        "[shape0-heavy-hex]",
        "tests/cli/estimate_cli_test.py::test_output_fits_80_columns",
        "tests/compiler/routing_qcec_test.py::test_qcec_proves_the_cells_placed_on_an_ibm_device_equal_to_their_logical_circuit",
        "tests/cli/inline_scenario_cli_test.py::test_robots_given_one_by_one_are_the_scenario_the_api_builds[verify]",
        "tests/compiler/routing_qcec_test.py::test_qcec_proves_the_native_circuit_a_named_device_gets_equal_to_its_logical_circuit"
        "[google_willow]",
        "tests/problem/explorability_test.py::test_smallest_split_is_documented",
        "tests/compiler/prefetch_test.py::test_a_compile_routing_its_balance_window_ahead_is_the_compile_without"
        "[shape1-grid]",
        "tests/verify/verify_report_test.py::test_every_line_of_the_report_fits_80_columns_and_nothing_is_cut[exact]",
        "tests/api/cli_equality_test.py::test_an_estimate_with_a_device_has_the_routed_columns_of_the_cli",
        "tests/api/noisy_api_test.py::test_a_run_predicted_to_take_hours_is_refused_and_a_small_one_runs_with_progress",
        "tests/estimators/routed_test.py::test_off_the_geometric_layout_the_bound_is_at_least_what_compile_routes"
        "[2x3/1-ibm_fez]",
        "tests/problem/explorability_test.py::test_component_count_is_symmetric[3x4]",
        "tests/compiler/toolchains_test.py::test_a_routed_native_circuit_keeps_its_two_qubit_gates",
        "tests/cli/stdin_scenario_test.py::test_a_pipeline_of_two_commands",
        "tests/cli/locale_output_test.py::test_json_names_a_non_ascii_file_in_the_c_locale",
        "tests/estimators/routed_test.py::test_the_layout_bound_is_at_least_what_compile_device_routes[2-3x3x1-grid]",
        "tests/compiler/routed_mixers_test.py::test_compile_writes_the_chosen_circuit_and_routes_it_to_fewer",
        "tests/compiler/known_state_test.py::test_same_state_from_zero_and_never_more_cx",
        "tests/cli/device_cli_test.py::test_compile_medial_on_an_ibm_device_places_the_cells_or_says_they_do_not_embed",
        "tests/compiler/routing_qcec_test.py::test_qcec_proves_routed_equal_to_unrouted[heavy-hex:5]",
        "tests/cli/interrupt_test.py::test_interrupting_a_single_process_command[15]",
        "tests/cli/interrupt_test.py::test_interrupting_a_single_process_command[2]",
        "tests/cli/interrupt_test.py::test_signal_stops_a_streaming_sweep_with_whole_rows[15]",
        "tests/cli/interrupt_test.py::test_signal_stops_a_streaming_sweep_with_whole_rows[2]",
        "tests/cli/interrupt_test.py::test_the_ready_line_is_off_by_default",
        "tests/cli/progress_test.py::test_validate_picks_a_backend_that_fits",
        "tests/cli/robustness_test.py::test_duplicated_obstacles_are_refused_by_name",
        "tests/cli/robustness_test.py::test_output_in_a_read_only_mount_is_one_line",
        "tests/cli/robustness_test.py::test_output_under_proc_is_one_line_before_any_work[/proc/qcpp-out.qasm]",
        "tests/cli/robustness_test.py::test_output_under_proc_is_one_line_before_any_work[/proc/self/qcpp/out.qasm]",
        "tests/cli/startup_imports_test.py::test_cpsat_loads_ortools_only_when_used",
        "tests/cli/startup_imports_test.py::test_start_up_loads_no_heavy_library[args1]",
        "tests/cli/test_extras_test.py::test_no_production_module_imports_a_test_only_library",
        "tests/compiler/gadget_examples_test.py::test_every_gadget_class_a_plan_emits_is_registered",
        "tests/compiler/junction_test.py::test_fused_circuit_matches_the_subspace_simulator[3x3/2]",
        "tests/compiler/lowering_test.py::test_lower_equals_original_on_clean_work_subspace",
        "tests/compiler/medial_test.py::test_auto_keeps_the_fewer_two_qubit_gates_on_small_circuits[shape2]",
        "tests/compiler/phase_classes_test.py::test_random_scenarios_and_plan_options_equal_the_plan",
        "tests/compiler/phase_locality_test.py::test_placed_sums_gadget_cost_and_exactness",
        "tests/compiler/phase_test.py::test_sums_gadget_cost_and_exactness",
        "tests/compiler/qasm_test.py::test_every_gate_against_qiskit_high_level_and_lowered",
        "tests/compiler/qasm_test.py::test_pytket_reads_lowered_qasm2_with_same_counts_and_state",
        "tests/compiler/qasm_test.py::test_random_circuits_against_qiskit",
        "tests/compiler/qcec_test.py::test_validate_cli_qcec_backend",
        "tests/compiler/routing_qcec_test.py::test_qcec_proves_routed_equal_to_unrouted[google_willow]",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[3x3/1 paper rule]",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[3x3/2 p1]",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[3x4 interior p1]",
        "tests/compiler/window_classes_test.py::test_windows_sharing_a_class_route_as_compile_routes_each[3x10/1]",
        "tests/estimators/formulas_test.py::test_phase_terms_are_the_call_graphs_counting_run_symbolically[5-5]",
        "tests/estimators/routed_test.py::test_the_bound_counts_the_circuit_the_device_compile_routes[3x4/2]",
        "tests/estimators/routed_test.py::test_the_bound_is_at_least_what_compile_routes[3x4/2-grid]",
        "tests/estimators/routed_test.py::test_the_bound_is_at_least_what_compile_routes[4x4/1-grid]",
        "tests/problem/cost_test.py::test_evaluators_agree_on_random_bits",
        "tests/problem/explorability_test.py::test_exact_rule_reaches_every_path_from_the_initial_path[4-4]",
        "tests/problem/explorability_test.py::test_paper_rule_restricted_to_feasible_moves_is_connected_too[4-4]",
        "tests/problem/qubo_solve_test.py::test_qubo_method_returns_the_proven_optimum[two_robots_4x4.toml]",
        "tests/problem/qubo_test.py::test_the_rule_holds_on_random_objectives",
        "tests/problem/sbf_test.py::test_exact_is_sound[4-4]",
        "tests/problem/sbf_test.py::test_rules_ignore_the_direction",
        "tests/simulate/experiments_test.py::test_script_quick_mode[annealing_two_robots-figures1]",
        "tests/training/multi_angle_test.py::test_the_solver_answers_with_the_product_state_and_bindings_of_t"
        "he_compiled_circuit",
        "tests/simulate/results_freshness_test.py::test_ensemble_derived_columns[ensembles-5x5/1]",
        "tests/simulate/experiments_test.py::test_ensemble_devices_bad_input_is_refused_with_its_reason",
        "tests/simulate/tensor_test.py::test_validate_cli_json_and_exit_codes",
        "tests/compiler/routing_qcec_test.py::test_qcec_proves_both_circuits_routed_on_a_calibrated_device_equal_to_"
        "their_logical_circuits",
        "tests/cli/device_cli_test.py::test_compile_device_writes_physical_qubits_on_couplings[ibm_torino-False]",
        # a CPU-second or more each (idle 2-core machine, pytest --durations=0)
        "tests/estimators/formulas_test.py::test_formulas_equal_exact_counts[small]",
        "tests/problem/explorability_test.py::test_bundled_hard_example_has_the_worst_case_split",
        "tests/doctests_test.py::test_docstring_examples[qcpp.estimators.formulas]",
        "tests/doctests_test.py::test_docstring_examples[qcpp.estimators.report]",
        "tests/simulate/results_freshness_test.py::test_ensemble_device_rows_of_the_first_instance_match_the_rout"
        "er",
        "tests/simulate/results_freshness_test.py::test_ensemble_rows_are_the_generators_instances[ensembles]",
        "tests/cli/device_cli_test.py::test_compile_device_writes_physical_qubits_on_couplings[heavy-hex:5-False]",
        "tests/simulate/experiments_test.py::test_ensembles_reuse_takes_over_an_earlier_runs_records",
        "tests/compiler/routing_qcec_test.py::test_qcec_proves_routed_equal_to_unrouted[grid:6x6]",
        "tests/cli/locale_output_test.py::test_estimate_draws_its_table_in_ascii[physical-PYTHONIOENCODING=ascii]",
        "tests/compiler/routing_qcec_test.py::test_qcec_catches_a_wrong_circuit",
        "tests/doctests_test.py::test_docstring_examples[qcpp.estimators.routed]",
        "tests/estimators/routed_test.py::test_small_rows_are_compiled_and_exact_everywhere",
        "tests/cli/locale_output_test.py::test_estimate_draws_its_table_in_ascii[physical-C locale]",
        "tests/compiler/routing_test.py::test_compile_for_device_reports_layouts_and_fits_the_device",
        "tests/verify/verify_report_test.py::test_a_junction_subject_is_never_cut_mid_list",
        "tests/cli/compile_cli_test.py::test_errors_are_one_line_and_exit_2[args1-give them with --bind NAME=VALU"
        "E]",
        "tests/api/qubo_api_test.py::test_solve_passes_the_sampler_and_its_answer_is_feasible",
        "tests/estimators/routed_test.py::test_charging_one_step_less_per_gate_falls_below_compile",
        "tests/estimators/routed_test.py::test_the_layout_bound_is_at_least_what_compile_device_routes[1-3x3x1-gr"
        "id]",
        "tests/api/interrupt_cache_test.py::test_an_interrupted_estimate_leaves_the_caches_sound[1]",
        "tests/cli/device_cli_test.py::test_compile_device_writes_physical_qubits_on_couplings[grid-True]",
        "tests/doctests_test.py::test_docstring_examples[qcpp.api.noisy]",
        "tests/compiler/commuting_test.py::test_the_balance_windows_route_to_fewer_cx_with_the_commuting_router",
        "tests/compiler/medial_test.py::test_too_small_or_irregular_devices_fall_back_to_greedy",
        "tests/compiler/routing_test.py::test_routed_equals_unrouted_up_to_layouts[3x3/1-grid:4x4]",
        "tests/cli/device_cli_test.py::test_compile_layout_choice_is_reported",
        "tests/benchmark_help_test.py::test_help_prints_the_usage_and_runs_nothing[noisy_verdict.py]",
        "tests/benchmark_help_test.py::test_help_prints_the_usage_and_runs_nothing[ensemble_fresh_draw.py]",
        "tests/api/hardware_run_test.py::test_lowered_routed_keeps_cx_and_rx",
        "tests/benchmark_help_test.py::test_help_prints_the_usage_and_runs_nothing[ensemble_intervals.py]",
        "tests/cli/export_cli_test.py::test_solve_qubo_with_simulated_annealing_answers_feasible_paths",
        "tests/cli/interrupt_test.py::test_a_signal_that_lands_in_a_finaliser_still_stops_without_a_traceback",
        "tests/api/noisy_api_test.py::test_progress_true_writes_the_shot_runs_on_stderr",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[4x4 hard interior p1]",
        "tests/api/validate_api_test.py::test_seeded_report_equals_the_cli_json[qcec]",
        "tests/compiler/medial_test.py::test_auto_keeps_the_fewer_two_qubit_gates_on_small_circuits[shape1]",
        "tests/cli/locale_output_test.py::test_estimate_draws_its_table_in_ascii[logical-C locale]",
        "tests/verify/verify_report_test.py::test_the_command_exits_3_when_not_certified_and_says_what_decides",
        "tests/docs_history_test.py::test_docs_and_source_tell_no_history",
        "tests/compiler/prefetch_test.py::test_an_interrupted_compile_stops_the_process_routing_ahead",
        "tests/api/noisy_api_test.py::test_the_device_s_noise_costs_probability_and_idling_costs_more",
        "tests/problem/sbf_test.py::test_soft_obstacles_change_neither_paths_nor_rules",
        "tests/compiler/noise_aware_test.py::test_qiskit_optimized_merges_the_one_qubit_gates_of_a_routing",
        "tests/cli/solve_qaoa_test.py::test_the_objective_line_fits_the_terminal_and_keeps_its_first_and_last_val"
        "ues",
        "tests/cli/locale_output_test.py::test_estimate_draws_its_table_in_ascii[logical-PYTHONIOENCODING=ascii]",
        "tests/cli/input_limits_test.py::test_weights_outside_the_exact_range_are_one_line_everywhere[edge_length"
        "s = [[[0, 0], [0, 1], 1e154]]-objective.edge_lengths[0]]",
        "tests/benchmark_help_test.py::test_help_prints_the_usage_and_runs_nothing[interop.py]",
        "tests/compiler/junction_test.py::test_fused_lowered_mixer_equals_unfused_on_feasible_inputs[3x3/2]",
        "tests/training/layerwise_test.py::test_each_level_is_at_least_as_good_as_the_last[gibbs]",
        "tests/compiler/prefetch_test.py::test_a_window_routed_ahead_is_the_window_routed_here",
        "tests/compiler/medial_test.py::test_the_balance_window_gets_the_large_window_search[4x4/2-hard-obstacle]",
        "tests/cli/interrupt_test.py::test_the_start_up_hold_is_off_by_default",
        "tests/cli/robustness_test.py::test_five_thousand_robots_on_a_3x3_grid[solve]",
        "tests/verify/verify_test.py::test_cli_exit_codes_and_json",
        "tests/compiler/phase_sums_selection_test.py::test_thinned_lattices_get_the_old_adders[1-edges]",
        "tests/io/stdout_names_test.py::test_dev_stdout_redirected_to_a_file_gets_the_output[args1-OPENQASM 3.0;]",
        "tests/api/simulate_client_test.py::test_the_client_reaches_the_tensor_backend_and_the_figures_are_the_su"
        "bspace_simulator_s",
        "tests/problem/coverage_semantics_test.py::test_the_optimum_need_not_cover_every_node_nor_keep_the_robots"
        "_apart",
        "tests/compiler/call_graph_test.py::test_classes_list_the_planned_kinds_default_scenarios[5-6-exact/nisq/"
        "initial_path/fuse=True0]",
        "tests/cli/solve_qaoa_test.py::test_mixer_warm_start_is_the_trainers_and_is_reported",
        "tests/cli/render_test.py::test_plot_trace",
        "tests/problem/explorability_test.py::test_exact_rule_reaches_every_path_from_the_initial_path[3-4]",
        "tests/estimators/layout_bound_test.py::test_the_kind_sum_is_the_placement_of_every_section_on_random_sce"
        "narios",
        "tests/simulate/results_freshness_test.py::test_ensemble_derived_columns[ensembles-3x3/1]",
        "tests/compiler/mixer_test.py::test_lowered_partial_mixer_is_one_sbf_rotation_or_identity",
        "tests/compiler/qasm_profiles_test.py::test_pyqasm_validates_and_unrolls_every_bound_profile[portable]",
        "tests/compiler/visit_batch_test.py::test_every_feasible_assignment_of_3x3_2_gets_its_phase",
        "tests/cli/stdin_scenario_test.py::test_process_substitution_is_a_pipe_without_a_suffix",
        "tests/estimators/depth_compose_test.py::test_bound_is_above_exact_and_exact_at_p0[PlanOptions(rule='exac"
        "t', initial='initial_path', target='nisq', phase='whole-space', optimize='cx', ancilla_budget=None, fuse"
        "=True, phase_layout='auto', angles='layer', first_phase=True)]",
        "tests/api/progress_api_test.py::test_solve_qubo_reports_its_three_steps",
        "tests/cli/stdin_scenario_test.py::test_bad_standard_input_is_one_line[[grid]\\nrows = \\n-fragments2]",
        "tests/cli/robustness_test.py::test_no_color_on_a_terminal_prints_no_colour",
        "tests/problem/cpsat_test.py::test_time_limit_returns_feasible_paths_and_a_valid_bound",
        "tests/cli/bad_input_test.py::test_standard_output_on_a_full_disk_is_one_line",
        "tests/compiler/medial_test.py::test_auto_keeps_the_fewer_two_qubit_gates_on_small_circuits[shape0]",
        "tests/cli/stdin_scenario_test.py::test_a_piped_scenario_is_read_in_either_format[json-/dev/stdin]",
        "tests/compiler/toolchains_test.py::test_random_gate_sequences_have_the_reference_unitary_phase_included",
        "tests/problem/solvers_test.py::test_seeds_reproduce_traces_exactly",
        "tests/simulate/statevector_test.py::test_matches_reference",
        "tests/compiler/qasm_test.py::test_write_qasm_failure_leaves_destination_untouched",
        "tests/estimators/depth_compose_test.py::test_anchored_profiles_equal_each_gadgets_own[PlanOptions(rule='"
        "paper', initial='initial_path', target='nisq', phase='feasible', optimize='cx', ancilla_budget=None, fus"
        "e=True, phase_layout='auto', angles='layer', first_phase=True)]",
        "tests/cli/stdin_scenario_test.py::test_a_piped_scenario_is_read_in_either_format[json--]",
        "tests/problem/cpsat_test.py::test_bound_is_below_the_optimum",
        "tests/cli/decode_cli_test.py::test_the_help_example_file_decodes",
        "tests/cli/stdin_scenario_test.py::test_a_piped_scenario_is_read_in_either_format[toml-/dev/stdin]",
        "tests/api/hardware_run_test.py::test_ibm_to_qiskit_writes_sx_with_the_same_unitary_and_the_counts_esp_ch"
        "arges",
        "tests/cli/stdin_scenario_test.py::test_bad_standard_input_is_one_line[{\"grid\": {\"rows\": 3, \"cols\":"
        " 3}, \"robots\": []}-fragments4]",
        "tests/cli/help_and_noise_test.py::test_help_examples_run[verify]",
        "tests/cli/solve_qaoa_test.py::test_restarts_and_gibbs_scale_are_the_trainers",
        "tests/problem/qubo_test.py::test_paper_energy_equals_the_cost_on_random_bits",
        "tests/problem/cpsat_test.py::test_default_placements_with_and_without_symmetry_breaking[4-2-7]",
        "tests/cli/progress_test.py::test_an_estimate_table_shows_progress_before_the_table",
        "tests/cli/probe_combinations_test.py::test_qaoa_training_too_big_for_memory_is_refused_before_enumeratin"
        "g",
        "tests/compiler/medial_test.py::test_the_balance_window_gets_the_large_window_search[3x4/2]",
        "tests/cli/cli_test.py::test_python_dash_m_entry_point",
        "tests/compiler/balance_fold_test.py::test_the_folded_phase_is_exact_on_every_feasible_assignment",
        "tests/benchmark_help_test.py::test_help_prints_the_usage_and_runs_nothing[solvers_speed.py]",
        "tests/compiler/qasm_test.py::test_mcx_definitions_are_exact[3]",
        "tests/cli/estimate_cli_test.py::test_phase_separator_options",
        "tests/problem/cost_test.py::test_separable_cost_agrees",
        "tests/problem/sbf_test.py::test_exact_is_complete_except_opposite_edges[4-4]",
        "tests/compiler/junction_test.py::test_every_junction_kind_reports_its_lowered_count",
        "tests/compiler/call_graph_test.py::test_the_call_graph_sums_to_the_lowered_circuits_counts[options2]",
        "tests/compiler/commuting_test.py::test_windows_with_commuting_middles_stay_exact_and_never_route_to_more",
        "tests/benchmark_help_test.py::test_help_prints_the_usage_and_runs_nothing[qubo_study.py]",
        "tests/compiler/routing_test.py::test_window_cx_equals_its_reference",
        "tests/cli/help_and_noise_test.py::test_help_examples_run[decode]",
        "tests/cli/help_and_noise_test.py::test_every_choice_key_names_a_real_option",
        "tests/cli/cli_test.py::test_plot_writes_png_and_no_temp_file",
        "tests/cli/robustness_test.py::test_a_1x40_strip[solve]",
        "tests/cli/table_records_test.py::test_any_rich_table_keeps_every_cell_whole",
        "tests/io/stdout_names_test.py::test_dev_stdout_redirected_to_a_file_gets_the_output[args0-name = \"defau"
        "lt 2x2, 1 robot(s)\"]",
        "tests/cli/stdin_scenario_test.py::test_a_terminal_is_refused_at_once",
        "tests/compiler/phase_locality_test.py::test_spatial_phase_separator_is_exact_on_feasible_states[5x5/2 sa"
        "mple]",
        "tests/cli/stdin_scenario_test.py::test_bad_standard_input_is_one_line[-fragments0]",
        "tests/api/hardware_run_test.py::test_measure_true_loads_with_the_data_register_on_the_final_layout",
        "tests/api/qubo_api_test.py::test_the_file_is_the_one_export_writes[per-robot-None-qubo]",
        "tests/cli/stdin_scenario_test.py::test_bad_standard_input_is_one_line[  \\n-fragments1]",
        "tests/simulate/results_freshness_test.py::test_exhaustive_search_and_seeded_annealing_rows",
        "tests/compiler/phase_test.py::test_sums_register_gadget",
        "tests/cli/solve_qaoa_test.py::test_plot_files_are_written_whole",
        "tests/cli/stdin_scenario_test.py::test_bad_standard_input_is_one_line[\\xff\\xfe[grid]-fragments5]",
        "tests/cli/progress_test.py::test_cpsat_counts_its_improving_solutions_without_a_total",
        "tests/cli/stdin_scenario_test.py::test_bad_standard_input_is_one_line[{\"grid\": {\"rows\": 3-fragments3"
        "]",
        "tests/compiler/routing_qcec_test.py::test_qcec_proves_a_sibling_devices_search_placed_on_an_ibm_device_e"
        "qual_to_its_logical_circuit",
        "tests/problem/feasible_cost_test.py::test_random_scenarios",
        "tests/compiler/bridge_test.py::test_qcec_proves_a_relayed_two_robot_compile_equal_to_the_compiled_circui"
        "t",
        "tests/api/validate_api_test.py::test_plan_options_are_validated_against_the_subspace_simulator[target=ft"
        "]",
        "tests/compiler/mixer_test.py::test_lowered_full_mixer_equals_high_level_on_basis_states[4-5-robots2]",
        "tests/cli/stdin_scenario_test.py::test_a_piped_scenario_is_read_in_either_format[toml--]",
        "tests/cli/stdin_scenario_test.py::test_a_slow_writer_in_a_pipeline_is_waited_for[-]",
        "tests/compiler/qcec_test.py::test_whole_circuits_are_proven_equivalent_section_by_section[3-3-2-2]",
        "tests/cli/startup_imports_test.py::test_start_up_loads_no_heavy_library[args0]",
        "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile[3x3/2 p3 no first phase]",
        "tests/benchmark_help_test.py::test_help_prints_the_usage_and_runs_nothing[estimate_speed.py]",
        "tests/verify/verify_report_test.py::test_every_line_of_the_report_fits_80_columns_and_nothing_is_cut[pap"
        "er]",
        "tests/cli/table_records_test.py::test_command_tables_never_cut[45]",
        "tests/verify/verify_test.py::test_both_methods_hold_for_other_constructions[ft]",
        "tests/problem/qubo_test.py::test_per_robot_energy_is_cost_plus_penalty",
        "tests/compiler/balance_fold_test.py::test_the_class_count_folds_where_the_plan_does[40-shape5]",
        "tests/estimators/tables_test.py::test_plot_is_written_atomically",
        "tests/cli/table_records_test.py::test_command_tables_never_cut[30]",
        "tests/compiler/junction_test.py::test_fused_lowered_mixer_equals_unfused_on_feasible_inputs[3x4/1_0]",
        "tests/cli/stdin_scenario_test.py::test_a_slow_writer_in_a_pipeline_is_waited_for[fd]",
        "tests/compiler/routing_qcec_test.py::test_qcec_proves_a_reordered_register_phase_equal_to_the_written_on"
        "e",
        "tests/problem/descent_test.py::test_random_scenarios_end_in_a_local_minimum",
        "tests/api/solve_json_test.py::test_the_api_object_is_the_cli_json[anneal-options2-flags2]",
        "tests/cli/startup_imports_test.py::test_start_up_loads_no_heavy_library[args2]",
        "tests/simulate/results_freshness_test.py::test_training_restarts_rows_match_their_reference_and_angles",
        "tests/compiler/phase_test.py::test_sweep_sampled[4x4-3-soft-chain-ft]",
        "tests/cli/stdin_scenario_test.py::test_a_slow_writer_in_a_pipeline_is_waited_for[/dev/stdin]",
        "tests/problem/qubo_test.py::test_per_robot_energy_at_the_proven_optimum_is_the_optimum[two_robots_5x5.to"
        "ml]",
        "tests/compiler/noise_aware_test.py::test_qiskit_optimized_keeps_a_routed_circuit_and_its_layouts",
        "tests/estimators/routed_test.py::test_an_exact_rows_log10_esp_is_the_log_of_its_esp",
    }
)
"""Tests (node ids) that run with ``-m heavy`` although their functions carry no marker: see the module docstring."""


LONGEST_FIRST = (
    "tests/simulate/results_freshness_test.py::test_device_rows_match_the_router[4x4/2]",
    "tests/compiler/call_graph_test.py::test_classes_list_the_planned_kinds_everywhere",
    "tests/simulate/experiments_test.py::test_ensemble_devices_quick_mode",
    "tests/simulate/tensor_test.py::test_compiled_circuit_matches_subspace_simulator[3-4-2-1-None]",
    "tests/compiler/phase_classes_test.py::test_every_default_scenario_up_to_16x16_equals_the_plan",
    "tests/compiler/routing_qcec_test.py::test_qcec_proves_both_circuits_routed_on_a_calibrated_device_equal_to_their_lo"
    "gical_circuits",
    "tests/compiler/noise_aware_test.py::test_searches_on_the_other_ibm_device_are_offered_only_for_twoq",
    "tests/simulate/results_freshness_test.py::test_ensemble_device_rows_match_the_router[3x3/1#1]",
    "tests/compiler/window_memo_test.py::test_the_memos_change_no_choice[4x4/3-heavy-hex]",
    "tests/cli/device_cli_test.py::test_compile_device_writes_physical_qubits_on_couplings[ibm_torino-False]",
    "tests/simulate/results_freshness_test.py::test_ensemble_device_rows_match_the_router[3x3/2#0]",
    "tests/io/caches_test.py::test_a_read_only_install_and_home_still_load_the_kernels",
    "tests/compiler/noise_aware_test.py::test_the_searches_on_defect_free_lattices_are_placed_on_an_ibm_device",
    "tests/simulate/results_freshness_test.py::test_ensemble_device_rows_match_the_router[3x3/1#0]",
    "tests/compiler/window_classes_test.py::test_routed_sum_equals_compile_on_more_random_scenarios",
    "tests/simulate/results_freshness_test.py::test_device_rows_match_the_router[3x3/2 +obst]",
    "tests/compiler/phase_sums_selection_test.py::test_a_16x16_8_medial_phase_layer_is_the_old_one",
    "tests/simulate/results_freshness_test.py::test_device_rows_match_the_router[5x5/1 +obst]",
    "tests/simulate/results_freshness_test.py::test_ensemble_device_rows_match_the_router[4x4/1#0]",
    "tests/simulate/results_freshness_test.py::test_ensemble_device_rows_match_the_router[4x4/1#1]",
    "tests/simulate/results_freshness_test.py::test_ensemble_recorded_angles_and_circuits[ensembles-4x4/2-every_row]",
    "tests/cli/guard_peaks_test.py::test_a_guards_memory_prediction_is_within_1_5x_of_the_measured_peak_on_large_work[si"
    "mulate-default-two_robots_5x5.toml]",
)
"""Node-id prefixes of the longest tests, longest first (the module docstring): an order, so a stale entry costs
wall time, never a result."""


def _longest_first_rank(item: pytest.Item) -> int:
    """The place of the first :data:`LONGEST_FIRST` prefix ``item`` starts with (after them all: none)."""
    return next((i for i, prefix in enumerate(LONGEST_FIRST) if item.nodeid.startswith(prefix)), len(LONGEST_FIRST))


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark the tests of :data:`SLOW_DEFAULT` heavy (before ``-m`` selects), and refuse entries that name no test
    when the whole suite is collected, so the list cannot rot; then move the :data:`LONGEST_FIRST` tests to the
    front (a stable sort: every other test keeps its order)."""
    found = set()
    for item in items:
        if item.nodeid in SLOW_DEFAULT:
            item.add_marker(pytest.mark.heavy)
            found.add(item.nodeid)
    whole_suite = not config.args or [os.path.normpath(a) for a in config.args] == ["tests"]
    if whole_suite and not config.option.keyword and found != SLOW_DEFAULT:
        raise pytest.UsageError(f"SLOW_DEFAULT names no collected test: {sorted(SLOW_DEFAULT - found)}")
    if whole_suite and not config.option.keyword:
        missing = [p for p in LONGEST_FIRST if not any(item.nodeid.startswith(p) for item in items)]
        if missing:
            raise pytest.UsageError(f"LONGEST_FIRST names no collected test: {missing}")
    items.sort(key=_longest_first_rank)


def pytest_collection_finish(session: pytest.Session) -> None:
    """Record whether collection imported quimb (a test checks that none did: see the module docstring)."""
    session.config.stash[QUIMB_AT_COLLECTION] = "quimb.tensor" in sys.modules


def pytest_sessionfinish(session: pytest.Session, exitstatus: int) -> None:
    """Collect once, then freeze the survivors until exit (see the module docstring)."""
    freeze_survivors()
