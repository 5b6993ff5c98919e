//! Simulator speed: world steps with sensor reads (robot-steps/s), scenario loading.

use divan::{Bencher, black_box, counter::ItemsCount};
use vivae_sim::{
    DistanceSensors, LoadOptions, PhysicsParams, Scenario, Sensor, SurfaceGrid, SurfaceSensors,
    World,
};

fn main() {
    // `VIVAE_SIMD=scalar|avx2|avx512` benchmarks that level (the program's
    // switch, read here because the library does no environment I/O).
    if let Ok(v) = std::env::var("VIVAE_SIMD") {
        let wanted =
            vivae_sim::simd::SimdLevel::from_name(&v).expect("VIVAE_SIMD: scalar, avx2 or avx512");
        eprintln!("VIVAE_SIMD: {:?}", vivae_sim::simd::set_level(wanted));
    }
    divan::main();
}

fn roads_world() -> World {
    let sc =
        Scenario::from_svg(vivae_sim::ROADS_SVG, "roads.svg", &LoadOptions::default()).unwrap();
    World::new(&sc, &PhysicsParams::default()).unwrap()
}

/// One world step of the 5 robots of roads.svg, each reading `rings × angles`
/// surface sensors; the controls are a fixed function of the readings (no network).
fn surface_steps(bencher: Bencher, rings: usize, angles: usize) {
    let mut world = roads_world();
    let grid = SurfaceSensors {
        rings,
        angles,
        ..Default::default()
    }
    .grid();
    let n = world.robots().len();
    let mut buf = vec![0.0; grid.len()];
    let mut controls = vec![[0.0; 2]; n];
    bencher.counter(ItemsCount::new(n)).bench_local(|| {
        for (i, c) in controls.iter_mut().enumerate() {
            grid.read(&world, i, &mut buf);
            let half = buf.len() / 2;
            let (left, right) = (lane_sum(&buf[..half]), lane_sum(&buf[half..]));
            *c = [
                0.2 + 0.8 * (right > left) as u8 as f64,
                0.2 + 0.8 * (left >= right) as u8 as f64,
            ];
        }
        world.step(black_box(&controls));
    });
    black_box(world.robots()[0].odometer);
}

#[divan::bench]
fn step_5_robots_3x5_surface_sensors(bencher: Bencher) {
    surface_steps(bencher, 3, 5);
}

#[divan::bench]
fn step_5_robots_20x60_surface_sensors(bencher: Bencher) {
    surface_steps(bencher, 20, 60);
}

/// roads.svg at 16 moments of a run whose robots turn more and more slowly.
fn driven_worlds() -> Vec<World> {
    let mut world = roads_world();
    let n = world.robots().len();
    let mut worlds = Vec::new();
    for k in 0..16 * 50 {
        if k % 50 == 0 {
            worlds.push(world.clone());
        }
        world.step(&vec![[1.0, 0.3 + 0.05 * (k / 50) as f64]; n]);
    }
    worlds
}

/// Surface sensors alone (no step): the 5 robots' `rings × angles` sensors
/// read by `read(grid, world, robots, buffer)` into a buffer of `T` (f64
/// for `SurfaceGrid::read`, f32 for `read_single`, the fast precision's)
/// holding every robot's readings, at poses taken from 16 moments of a
/// driven run so that the look-ups are not all the same cells.
fn surface_reads_with<T: Copy + Default>(
    bencher: Bencher,
    rings: usize,
    angles: usize,
    read: impl Fn(&SurfaceGrid, &World, usize, &mut [T]),
) {
    let grid = SurfaceSensors {
        rings,
        angles,
        ..Default::default()
    }
    .grid();
    let worlds = driven_worlds();
    let n = worlds[0].robots().len();
    let mut buf = vec![T::default(); n * grid.len()];
    let mut k = 0;
    bencher.counter(ItemsCount::new(n)).bench_local(|| {
        let w = &worlds[k % worlds.len()];
        k += 1;
        read(&grid, black_box(w), n, &mut buf);
        black_box(&mut buf);
    });
}

/// `SurfaceGrid::read` (f64) of `rings × angles` sensors for each of 5
/// robots, one call per robot.
fn surface_reads(bencher: Bencher, rings: usize, angles: usize) {
    surface_reads_with(bencher, rings, angles, |g, w, n, out: &mut [f64]| {
        for (i, out) in out.chunks_exact_mut(g.len()).take(n).enumerate() {
            g.read(w, i, out);
            black_box(out);
        }
    });
}

/// [`surface_reads`] in single precision (`SurfaceGrid::read_single`, the
/// fast precision's read): twice the lanes per vector.
fn surface_reads_single(bencher: Bencher, rings: usize, angles: usize) {
    surface_reads_with(bencher, rings, angles, |g, w, n, out: &mut [f32]| {
        for (i, out) in out.chunks_exact_mut(g.len()).take(n).enumerate() {
            g.read_single(w, i, out);
            black_box(out);
        }
    });
}

#[divan::bench]
fn read_5_robots_3x5_surface_sensors(bencher: Bencher) {
    surface_reads(bencher, 3, 5);
}

/// The 5 robots' 3×5 surface sensors read in one call (f64), as a rollout reads them.
#[divan::bench]
fn read_5_robots_3x5_surface_sensors_batched(bencher: Bencher) {
    surface_reads_with(bencher, 3, 5, |g, w, n, out: &mut [f64]| {
        g.read_robots(w, n, out, g.len())
    });
}

/// As `read_5_robots_3x5_surface_sensors_batched`, in single precision.
#[divan::bench]
fn read_5_robots_3x5_surface_sensors_batched_f32(bencher: Bencher) {
    surface_reads_with(bencher, 3, 5, |g, w, n, out: &mut [f32]| {
        g.read_robots_f32(w, n, out, g.len(), &mut [])
    });
}

#[divan::bench]
fn read_5_robots_20x60_surface_sensors(bencher: Bencher) {
    surface_reads(bencher, 20, 60);
}

#[divan::bench]
fn read_5_robots_32x96_surface_sensors(bencher: Bencher) {
    surface_reads(bencher, 32, 96);
}

#[divan::bench]
fn read_5_robots_3x5_surface_sensors_f32(bencher: Bencher) {
    surface_reads_single(bencher, 3, 5);
}

#[divan::bench]
fn read_5_robots_32x96_surface_sensors_f32(bencher: Bencher) {
    surface_reads_single(bencher, 32, 96);
}

/// The 5 robots' 8 distance rays alone (no step), at the same 16 moments' poses.
#[divan::bench]
fn read_5_robots_8_distance_sensors(bencher: Bencher) {
    let grid = DistanceSensors {
        rays: 8,
        ..Default::default()
    }
    .grid();
    let worlds = driven_worlds();
    let n = worlds[0].robots().len();
    let mut buf = vec![0.0; grid.len()];
    let mut k = 0;
    bencher.counter(ItemsCount::new(n)).bench_local(|| {
        let w = &worlds[k % worlds.len()];
        k += 1;
        for i in 0..n {
            grid.read(black_box(w), i, &mut buf);
            black_box(&mut buf);
        }
    });
}

#[divan::bench]
fn step_5_robots_no_sensors(bencher: Bencher) {
    let mut world = roads_world();
    let controls = vec![[1.0, 0.9]; world.robots().len()];
    bencher
        .counter(ItemsCount::new(controls.len()))
        .bench_local(|| world.step(black_box(&controls)));
}

#[divan::bench]
fn step_5_robots_3x5_surface_and_8_distance_sensors(bencher: Bencher) {
    let mut world = roads_world();
    let sgrid = SurfaceSensors::default().grid();
    let dgrid = DistanceSensors {
        rays: 8,
        ..Default::default()
    }
    .grid();
    let n = world.robots().len();
    let mut s = vec![0.0; sgrid.len()];
    let mut d = vec![0.0; dgrid.len()];
    let mut controls = vec![[0.0; 2]; n];
    bencher.counter(ItemsCount::new(n)).bench_local(|| {
        for (i, c) in controls.iter_mut().enumerate() {
            sgrid.read(&world, i, &mut s);
            dgrid.read(&world, i, &mut d);
            *c = [1.0 - d[7] + s[0], 1.0 - d[0] + s[4]];
        }
        world.step(black_box(&controls));
    });
}

const CORPUS: &[&str] = &[
    "arena1.svg",
    "arena2.svg",
    "arena3_h.svg",
    "minimal1.svg",
    "minimal2.svg",
    "minimal3.svg",
    "oval1_h.svg",
    "oval2_h.svg",
    "scenar1_01.svg",
    "scenar2_01.svg",
    "scenario2.svg",
    "ushape.svg",
    "roads.svg",
];

/// Loading (parse, geometry, 1 px raster) of every corpus file and the default scenario.
#[divan::bench(args = CORPUS)]
fn load_scenario(bencher: Bencher, name: &str) {
    let text = if name == "roads.svg" {
        Some(vivae_sim::ROADS_SVG.to_string())
    } else {
        std::fs::read_to_string(format!(
            "{}/../../../shared/vivae-scenarios/{name}",
            env!("CARGO_MANIFEST_DIR")
        ))
        .ok()
    };
    let Some(text) = text else {
        eprintln!("corpus file {name} absent; skipped");
        return;
    };
    bencher.bench(|| Scenario::from_svg(black_box(&text), name, &LoadOptions::default()).unwrap());
}

/// Cloning a loaded world (one per parallel episode).
#[divan::bench]
fn clone_world(bencher: Bencher) {
    let world = roads_world();
    bencher.bench(|| black_box(&world).clone());
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
