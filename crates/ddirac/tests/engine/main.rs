//! The library's integration tests, one file per subject or finding, built as one test binary: each
//! binary compiles the engine once more for every system type it runs, and links the library once
//! more, so forty binaries compiled the same copies forty times. The tests that count something of the
//! whole process (allocations, native compilations) are binaries of their own (`tests/allocations.rs`,
//! `tests/composition_compiles_once.rs`, `tests/issue_12_convergence_compiles_once.rs`).

#[path = "../common/chain_text.rs"]
mod chain_text;
#[path = "../common/mod.rs"]
mod common;
#[path = "../common/pendulum_text.rs"]
mod pendulum_text;
#[path = "../common/spherical_pendulum_text.rs"]
mod spherical_pendulum_text;

mod atlas;
mod baselines;
mod built_in_systems_are_built_by_the_library;
mod chart_watch;
mod charts;
mod check;
mod closed_form;
mod compiled;
mod composition;
mod conservation;
mod convergence;
mod dimensions;
mod errors;
mod expression;
mod expression_round_trips;
mod hand_derivatives;
mod invariance_is_shift_and_scale_free;
mod issue_11_definition_chain_order;
mod issue_11_long_flat_sum;
mod issue_12_large_systems_on_small_stacks;
mod issue_12_min_max_compiled;
mod issue_12_min_max_untaken_branch;
mod issue_12_systems_in_a_dynamic_dimension;
mod issue_12_text_systems_of_24_and_50_coordinates;
mod issue_12_text_systems_of_any_size_up_to_100;
mod issue_13_pole_passage_is_named;
mod issue_13_pole_passages_switch_charts;
mod issue_14_failed_steps_are_subdivided;
mod issue_14_long_step_leaves_the_chart;
mod issue_30_atlas_error_regular_in_h;
mod issue_30_atlas_never_used_is_refused;
mod issue_30_chart_maps_not_inverse_are_refused;
mod issue_30_check_and_run_agree_on_charts;
mod issue_30_energy_watch_spans_chart_switches;
mod issue_30_high_orders_keep_their_order_in_an_atlas;
mod issue_30_loose_tolerance_never_accepts_the_predictor;
mod issue_30_pi_is_not_a_name;
mod issue_30_unresolved_pole_passage_warns;
mod issue_31_error_fields_are_typed;
mod kepler_and_top;
mod legendre_velocity_stops_at_round_off;
mod minus_variant;
mod newton;
mod newton_residual_test_at_an_electrons_mass;
mod pendulum_chain;
mod published_values;
mod reduction_consistency;
mod rigid_body;
mod rigid_principal_axes;
mod stepper;
mod tangent_map;
mod undetermined_motion_is_refused;
