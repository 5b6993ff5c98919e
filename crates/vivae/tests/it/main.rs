//! The vivae program's integration tests, in one binary (one link of the
//! whole program instead of one per file). Each module is one former test
//! file, named for the behaviour it checks; `common` holds the helpers (and
//! `common::browser`, the headless-Chromium driver). The MPI tests are the
//! separate `mpi` binary (`tests/mpi/`, built only with `--features mpi`).
//!
//! Run one file's tests with a filter: `cargo test --release -p vivae --test it
//! short_run_matches_pinned_hash`.

mod a_training_map_given_twice_is_warned_about;
mod a_viewer_step_message_is_bounded_by_its_cost;
mod bad_inputs_exit_2_with_one_line;
mod best_genomes_are_recorded_every_generation_and_resume_identically;
mod cli_end_to_end;
mod common;
mod compare_refuses_an_impossible_wall_time;
mod compare_summarises_runs_by_group;
mod corrupt_checkpoint_is_refused;
mod es_hyperneat_runs_resume_identically_and_refuse_bad_keys;
mod es_network_figure_draws_hidden_neurons_where_they_are;
mod evaluation_is_thread_count_independent;
mod every_strategy_resumes_bit_identical;
mod export_runs_as_vivae_does;
mod finished_run_and_retrain_neurons_only;
mod first_hour_output_says_what_to_do_next;
mod force_replaces_only_a_run;
mod forged_checkpoint_is_refused_before_anything_changes;
mod frames_from_the_simulator_drive_as_its_sensors_do;
mod idle_viewer_pages_free_their_slots;
mod inconsistent_checkpoint_population_is_refused;
mod interrupt_checkpoints_and_exits_130;
mod killed_run_resumes_bit_identical;
mod lateral_free_controller_resamples_exactly;
mod library_has_no_program_dependencies;
mod maze_runs_from_the_cli_and_resumes_identically;
mod missing_corpus_skips_unless_required;
mod multi_map_evolution_is_reproducible;
mod multi_map_fitness_is_the_mean_over_maps;
mod multi_resolution_evolution_is_reproducible;
mod network_figure_stays_small_at_camera_resolution;
mod non_regular_input_files_are_refused;
mod output_path_mistakes_exit_2_with_one_line;
mod predator_prey_report_and_viewer_show_both_teams;
mod predator_prey_runs_from_the_cli_and_resumes_identically;
mod random_placements_are_seeded_and_replayable;
mod replay_from_champion_file_matches_run_dir;
mod replay_of_an_elite_or_front_member;
mod report_draws_the_archive_and_the_front;
mod report_html_is_self_contained;
mod report_plots_keep_the_legend_off_the_curves;
mod report_refuses_damaged_run_files;
mod report_shows_each_training_map;
mod reproduce_packs_print_and_write_their_table;
mod resume_matches_uninterrupted_run;
mod resume_redraws_a_stale_report;
mod resume_removes_stale_temporaries;
mod robots_flag_fits_a_one_robot_scenario;
mod runs_too_big_to_start_are_refused;
mod same_bits_at_every_simd_level;
mod same_bits_on_older_cpu_code_paths;
mod scenario_render_bounds_its_sensors;
mod second_writer_of_a_run_is_refused;
mod several_placements_per_genome_are_seeded_and_resume_identically;
mod shipped_scenarios_run_by_name;
mod short_run_matches_pinned_hash;
mod sigterm_checkpoints_and_exits_130;
mod special_run_files_are_refused_not_waited_on;
mod viewer_and_report_in_a_real_browser;
mod viewer_draws_the_es_network_where_its_neurons_are;
mod viewer_drives_any_elite_or_front_member;
mod viewer_follows_a_running_evolution;
mod viewer_keeps_fast_trails_and_says_what_drives;
mod viewer_refuses_foreign_host_names;
mod viewer_refuses_run_file_links_and_special_files;
mod viewer_serves_only_its_own_files;
mod workspace_structure;
