//! vivae-lab's integration tests, in one binary. Each module is named for
//! the behaviour it guards.

mod maze_scenarios_and_controllers;
