//! The ViVAE robot simulator: SVG scenarios, physics, sensors, snapshots and drawing.
//!
//! Data flows `scenario.svg text → Scenario → World`; the world steps robots
//! driven by two numbers (L, R) each and answers sensor queries. Nothing here
//! touches the file system or knows about neural networks.
//!
//! ```
//! use vivae_sim::{LoadOptions, PhysicsParams, Scenario, Sensor, SurfaceSensors, World};
//!
//! let scenario = Scenario::from_svg(vivae_sim::ROADS_SVG, "roads.svg", &LoadOptions::default())?;
//! let mut world = World::new(&scenario, &PhysicsParams::default())?;
//! let eyes = SurfaceSensors::default().grid(); // the paper's 3×5 polar grid
//! let mut seen = vec![0.0; eyes.len()];
//! for _ in 0..100 {
//!     eyes.read(&world, 0, &mut seen); // road reads 1, grass 0
//!     let controls = vec![[1.0, 1.0]; world.robots().len()]; // full throttle, straight
//!     world.step(&controls);
//! }
//! assert!(world.robots()[0].odometer > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod draw;
mod draw_traffic;
pub mod geometry;
pub mod physics;
pub mod raster;
pub mod scenario;
pub mod sensors;
pub mod simd;
mod snapshot;
mod style;
pub mod world;

pub use draw::{DrawError, DrawOptions, render_png, render_svg};
pub use glam::DVec2;
pub use physics::{FrictionTable, ParamError, PhysicsParams};
pub use scenario::{
    LoadOptions, Mark, Obstacle, ObstacleRegion, Puck, PuckKind, RobotStart, Route, Scenario,
    ScenarioError, ScenarioSummary, Surface, SurfaceKind, TrafficStart,
};
pub use sensors::{
    DistanceGrid, DistanceSensors, GoalRadar, OpponentRadar, Sensor, SensorPlace, SurfaceGrid,
    SurfaceSensors, spread,
};
pub use style::surface_color;
pub use world::{MovableState, PuckState, Robot, SurfaceHere, TeamContact, World, wrap_angle};

/// The default scenario (`scenarios/roads.svg`): a road network with 5 robots.
pub const ROADS_SVG: &str = include_str!("../../../scenarios/roads.svg");
