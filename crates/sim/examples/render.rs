//! Renders a scenario (default: the embedded roads.svg) to PNG, optionally after
//! driving every robot forward for some steps so that trajectories show.
//! Usage: `cargo run --example render -- [IN.svg|-] OUT.png [STEPS]`

use vivae_sim::{
    DrawOptions, LoadOptions, PhysicsParams, Scenario, SurfaceSensors, World, render_png,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (input, out) = match args.as_slice() {
        [i, o, ..] => (i.clone(), o.clone()),
        _ => return Err("usage: render IN.svg|- OUT.png [STEPS]".into()),
    };
    let steps: usize = args.get(2).map(|s| s.parse()).transpose()?.unwrap_or(0);
    let text = if input == "-" {
        vivae_sim::ROADS_SVG.to_string()
    } else {
        std::fs::read_to_string(&input)?
    };
    let sc = Scenario::from_svg(&text, &input, &LoadOptions::default())?;
    for w in &sc.warnings {
        eprintln!("warning: {w}");
    }
    let mut world = World::new(&sc, &PhysicsParams::default())?;
    world.record_trajectories(steps);
    let controls: Vec<[f64; 2]> = (0..world.robots().len())
        .map(|i| if i % 2 == 0 { [1.0, 0.9] } else { [0.9, 1.0] })
        .collect();
    for _ in 0..steps {
        world.step(&controls);
    }
    let opts = DrawOptions {
        title: Some(format!("{} after {steps} steps", sc.source)),
        surface_sensors: Some(SurfaceSensors::default()),
        ..Default::default()
    };
    std::fs::write(&out, render_png(&world, &opts)?)?;
    Ok(())
}
