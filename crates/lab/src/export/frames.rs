//! Frames rendered from the simulator: what a robot's downward (or
//! unwarped omnidirectional) camera would see of a scenario's ground, and
//! recorded episodes to compare an exported controller with.

use vivae_sim::{DVec2, DrawOptions, World};

use super::image::{Camera, Image};
use crate::controller::es::RobotController;
use crate::error::Result;
use crate::io::bad_input;
pub use crate::tasks::substrate::Recording;
use crate::tasks::substrate::SubstrateEpisode;

/// The ground of `world`'s scenario as an SVG picture, one pixel per
/// scenario px: surfaces, marks and obstacles, no robots, title or legend;
/// `crisp`: without anti-aliasing, so that a pixel has the colour of the
/// surface under its centre, as the simulator's raster does.
pub fn ground_svg(world: &World, crisp: bool) -> Result<String> {
    let mut scenario = world.scenario().clone();
    scenario.robots.clear();
    let ground = World::new(&scenario, world.params())
        .map_err(|e| bad_input(format!("cannot draw the ground: {e}")))?;
    let opts = DrawOptions {
        title: None,
        trajectories: false,
        surface_sensors: None,
        distance_sensors: None,
        scale: 1.0,
        legend: false,
    };
    let svg = vivae_sim::render_svg(&ground, &opts);
    if !crisp {
        return Ok(svg);
    }
    let (w, h) = (world.scenario().width(), world.scenario().height());
    Ok(format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\
         <g shape-rendering=\"crispEdges\">{svg}</g></svg>"
    ))
}

/// A robot-centred frame of `ground` (from [`ground_svg`]): `size` × `size`
/// pixels, `scale` pixels per scenario px, the robot at `pos` in the middle
/// facing up; with the [`Camera`] that reads it (radius: half the frame).
pub fn robot_view(
    ground: &str,
    pos: DVec2,
    heading: f64,
    size: u32,
    scale: f64,
) -> (String, Camera) {
    let c = f64::from(size) / 2.0;
    let svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{size}\" height=\"{size}\" viewBox=\"0 0 {size} {size}\">\
         <g transform=\"translate({c} {c}) scale({scale}) rotate({}) translate({} {})\">{ground}</g></svg>",
        -heading.to_degrees(),
        -pos.x,
        -pos.y
    );
    let camera = Camera {
        centre: [c, c],
        scale,
        heading: 0.0,
        radius: Some(c),
    };
    (svg, camera)
}

/// An SVG picture as an [`Image`].
pub fn rasterize(svg: &str) -> Result<Image> {
    let png = vivae_sim::draw::svg_to_png(svg, 1.0)
        .map_err(|e| bad_input(format!("cannot draw a frame: {e}")))?;
    Image::from_png(&png, "a rendered frame")
}

/// Runs `steps` steps of `episode` driven by `controller` (every robot, as
/// evolution does) and records robot `robot` (a fast controller's f32
/// readings widened to f64, exactly).
pub fn record(
    episode: &dyn SubstrateEpisode,
    controller: &RobotController,
    robot: usize,
    steps: u32,
) -> Result<Recording> {
    episode.record(controller, robot, steps)
}
