//! vivae-sim's integration tests, in one binary (one link instead of one per
//! file). Each module is one former test file, named for the behaviour it checks.

mod bad_scenarios_give_typed_errors;
mod common;
mod corpus_loads_with_expected_counts;
mod elements_without_or_with_repeated_ids_load_where_drawn;
mod physics_follows_design;
mod raster_and_contacts_properties;
mod scenario_features_load;
mod sensors_see_roads_and_walls;
mod snapshot_reloads_same_objects_and_poses;
mod teams_load_and_report_contacts;
