//! What every viewer's page shares in its play: the arrow keys a page holds
//! down and the pace of real time.

use serde::Deserialize;

/// Simulation steps per second at speed 1 ("real time").
pub(crate) const REAL_TIME_STEPS: f64 = 30.0;

/// Arrow keys held down (as a page's `keys` message says them; both
/// viewers take it).
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Keys {
    pub up: bool,
    pub down: bool,
    pub left: bool,
    pub right: bool,
}

impl Keys {
    /// Wheel commands `[L, R]` for the keys held, as ViVAE's keyboard controller.
    pub(crate) fn controls(self) -> [f64; 2] {
        let forward = f64::from(i8::from(self.up) - i8::from(self.down));
        let turn = f64::from(i8::from(self.right) - i8::from(self.left));
        if forward == 0.0 {
            [0.6 * turn, -0.6 * turn]
        } else {
            let f = forward;
            [
                (f + 0.7 * turn).clamp(-1.0, 1.0),
                (f - 0.7 * turn).clamp(-1.0, 1.0),
            ]
        }
    }
}
