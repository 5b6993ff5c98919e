//! The small differential robot of Lehman & Stanley's navigation
//! experiments, in our physics, for any task that drives it (the maze, the
//! predator–prey arena): its physics, its six rangefinders, how a network's
//! two outputs (turn, forward) drive its wheels, and the plain-NEAT genome
//! layout of its controller.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use vivae_neat::GenomeSpec;
use vivae_sim::PhysicsParams;

/// Reach of the rangefinders from the robot's centre, px.
pub const RANGE: f64 = 100.0;
/// Network inputs: 6 rangefinders, 4 radar slices, a bias.
pub const INPUTS: usize = 11;
/// Network outputs: turn, forward.
pub const OUTPUTS: usize = 2;

/// The paper's robot in our physics: radius 8, top speed 3 px/step,
/// ±0.5 px/step² from the forward output, no friction drag (Lehman's
/// robot keeps its speed), turning up to 0.1 rad/step at standstill.
pub fn physics() -> PhysicsParams {
    PhysicsParams {
        robot_radius: 8.0,
        v_max: 3.0,
        a_max: 0.5,
        omega_max: 0.1,
        k: 0.0,
        ..PhysicsParams::default()
    }
}

/// The rangefinders' angles, radians from ahead (negative = left): the
/// paper's −90°, −45°, 0°, 45°, 90° and 180° (behind).
pub fn rangefinder_angles() -> [f64; 6] {
    [-FRAC_PI_2, -FRAC_PI_4, 0.0, FRAC_PI_4, FRAC_PI_2, PI]
}

/// The genome layout: [`INPUTS`] inputs, [`OUTPUTS`] sigmoid outputs,
/// recurrent links allowed (as in Lehman's NEAT).
pub fn spec() -> GenomeSpec {
    GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::plain(INPUTS, OUTPUTS)
    }
}

/// The wheel commands `[L, R]` for the network's outputs `turn` and
/// `forward` in [0, 1]: with `v = 2·forward − 1` and `w = 2·turn − 1`,
/// `L = v + w` and `R = v − w` (the world clips each to [−1, 1]).
///
/// Why: our robot accelerates by `a_max·(L+R)/2 = a_max·v` and turns by
/// `omega_max·(L−R)/2 = omega_max·w` (less at speed), so with `a_max = 0.5`
/// the forward output changes the speed by `forward − 0.5` per step, as in
/// Lehman's simulator, and `turn > 0.5` turns right (clockwise on screen),
/// as there.
#[inline]
pub fn wheels(turn: f64, forward: f64) -> [f64; 2] {
    let v = 2.0 * forward - 1.0;
    let w = 2.0 * turn - 1.0;
    [v + w, v - w]
}
