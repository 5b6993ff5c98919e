//! Runs `STEPS` world steps of roads.svg (5 robots) reading `RINGSxANGLES`
//! surface sensors, for measuring CPU time per robot-step with `perf stat`
//! when the machine is too busy for wall-clock benchmarks.
//! Usage: `cargo run --release --example steps -- STEPS [RINGS ANGLES] [scalar|avx2|avx512]`
//! (the last argument forces the simulator's SIMD level; the default is the best detected).

use vivae_sim::simd::{SimdLevel, set_level};
use vivae_sim::{LoadOptions, PhysicsParams, Scenario, Sensor, SurfaceSensors, World};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    // An optional last argument forces the simulator's SIMD level.
    let level = match args.last().map(String::as_str) {
        Some("scalar") => Some(SimdLevel::Scalar),
        Some("avx2") => Some(SimdLevel::Avx2),
        Some("avx512") => Some(SimdLevel::Avx512),
        _ => None,
    };
    if let Some(l) = level {
        args.pop();
        eprintln!("SIMD level {:?}", set_level(l));
    }
    let args: Vec<usize> = args.iter().map(|a| a.parse()).collect::<Result<_, _>>()?;
    let steps = args.first().copied().unwrap_or(1_000_000);
    let (rings, angles) = (
        args.get(1).copied().unwrap_or(3),
        args.get(2).copied().unwrap_or(5),
    );
    let sc = Scenario::from_svg(vivae_sim::ROADS_SVG, "roads.svg", &LoadOptions::default())?;
    let mut world = World::new(&sc, &PhysicsParams::default())?;
    let grid = SurfaceSensors {
        rings,
        angles,
        ..Default::default()
    }
    .grid();
    let n = world.robots().len();
    let mut buf = vec![0.0; grid.len()];
    let mut controls = vec![[0.0; 2]; n];
    for _ in 0..steps {
        for (i, c) in controls.iter_mut().enumerate() {
            grid.read(&world, i, &mut buf);
            let half = buf.len() / 2;
            let (left, right) = (lane_sum(&buf[..half]), lane_sum(&buf[half..]));
            *c = [
                0.2 + 0.8 * (right > left) as u8 as f64,
                0.2 + 0.8 * (left >= right) as u8 as f64,
            ];
        }
        world.step(&controls);
    }
    let odo: f64 = world.robots().iter().map(|r| r.odometer).sum();
    println!("{} robot-steps, total odometer {odo:.1}", steps * n);
    Ok(())
}

/// Sum in eight independent lanes: the one-chain sum of 1,200 readings took
/// as long as reading them, hiding the sensors' cost.
fn lane_sum(v: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let mut chunks = v.chunks_exact(8);
    for c in &mut chunks {
        for (a, x) in acc.iter_mut().zip(c) {
            *a += x;
        }
    }
    acc.iter().sum::<f64>() + chunks.remainder().iter().sum::<f64>()
}
