//! The command line's integration tests, one file per subject or finding, built as one test binary
//! (each binary links the library and its dependencies again). They run the `ddirac` binary in
//! temporary directories of their own, so they share nothing else.

#[path = "../common/mod.rs"]
mod common;

mod bench;
mod check;
mod cli;
mod compare;
mod convergence;
mod energy_drift_warns;
mod ensemble;
mod equilibria;
mod exact_solution_figures;
mod examples;
mod issue_11_angle_not_periodic;
mod issue_11_auto_weighs_program_size;
mod issue_11_column_name_collision;
mod issue_11_compare_labels;
mod issue_11_convergence_owns_its_directory;
mod issue_11_convergence_without_bias;
mod issue_11_degenerate_off_constraint_runs;
mod issue_11_double_star_hint;
mod issue_11_exit_codes;
mod issue_11_figures_anti_aliased;
mod issue_11_figures_break_at_angle_wraps;
mod issue_11_huge_step_counts;
mod issue_11_invariance_shifted_by_constant;
mod issue_11_invariance_undefined_samples;
mod issue_11_io_errors_name_the_file;
mod issue_11_long_flat_sum;
mod issue_11_numerical_failure_located;
mod issue_11_out_names_a_file;
mod issue_11_rerun_replaces_outputs;
mod issue_11_set_value_hint;
mod issue_11_short_round_trip_numbers;
mod issue_11_signal_leaves_no_partial_files;
mod issue_11_singular_potential_crossed;
mod issue_11_suggestion_case;
mod issue_11_two_runs_one_directory;
mod issue_11_unchecked_reduction_warns;
mod issue_12_seventeen_and_73_coordinates_in_a_spec;
mod issue_13_charts_in_a_spec;
mod issue_30_check_examines_charts;
mod issue_30_compare_csv_number_format;
mod issue_30_merge_verifies_shards;
mod issue_30_messages_that_mislead;
mod issue_30_top_crossing_upright_in_euler_angles_warns;
mod issue_33_sensitivity_lost_warns;
mod issue_35_kepler_example_reports_its_error;
mod issue_35_momentum_drift_has_a_scale;
mod issue_35_time_override_states_the_step;
mod library_errors_located;
mod memory;
mod npy;
mod pendulum_chain;
mod plots;
mod rigid_body;
mod rigid_body_figures;
mod rigid_ensemble;
mod rigid_examples;
mod sensitivities;
mod slurm_example;
mod specs;
mod undetermined_motion_is_refused;
