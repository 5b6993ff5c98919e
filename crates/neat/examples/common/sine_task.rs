//! SharpNEAT 4's generative sinewave (`GenerativeFnRegressionEvaluationScheme`
//! with `generative-sinewave.config.json`): a recurrent network whose only
//! input is a bias of 1 is activated 3 times to warm up, then 80 times; the
//! k-th output `y` gives `(y - 0.5) * scale + mid`, compared with sin(x_k) for
//! 80 points x_k evenly over [0, 25.13274123] (8π). Fitness is
//! `20 / (0.1 * mse(y) + 0.9 * mse(gradient) + 0.02)`, so a perfect network
//! scores 1,000; gradients are central differences (one-sided at the ends).

use vivae_neat::{Network, RecurrentLanes, math};

/// Samples of the function.
pub const SINE_SAMPLES: usize = 80;
const X_MAX: f64 = 25.132_741_23;
const GRADIENT_WEIGHT: f64 = 0.9;
/// Activations before the samples are read.
const WARM_UP: usize = 3;
/// The most networks [`Sine::fitness_lanes`] steps side by side.
pub const MAX_LANES: usize = 8;

/// The targets, their gradients, and the probe's `mid` and `scale`.
#[derive(Clone)]
pub struct Sine {
    y: [f64; SINE_SAMPLES],
    dy: [f64; SINE_SAMPLES],
    /// The x spans of the gradients, computed once (the same bits as each time).
    spans: [f64; SINE_SAMPLES],
    /// Middle of the target's range.
    pub mid: f64,
    /// The target's range over 0.8 (the logistic function's useful range).
    pub scale: f64,
}

fn x(k: usize) -> f64 {
    X_MAX / (SINE_SAMPLES - 1) as f64 * k as f64
}

/// The denominators of [`gradients`]: the x spans of each sample's difference.
fn spans() -> [f64; SINE_SAMPLES] {
    let n = SINE_SAMPLES - 1;
    std::array::from_fn(|k| match k {
        0 => x(1) - x(0),
        k if k == n => x(n) - x(n - 1),
        k => x(k + 1) - x(k - 1),
    })
}

/// Central differences of `y` over `spans` (one-sided at the ends).
fn gradients(y: &[f64; SINE_SAMPLES], spans: &[f64; SINE_SAMPLES], dy: &mut [f64; SINE_SAMPLES]) {
    let n = SINE_SAMPLES - 1;
    dy[0] = (y[1] - y[0]) / spans[0];
    for k in 1..n {
        dy[k] = (y[k + 1] - y[k - 1]) / spans[k];
    }
    dy[n] = (y[n] - y[n - 1]) / spans[n];
}

impl Default for Sine {
    fn default() -> Sine {
        Sine::new()
    }
}

impl Sine {
    /// sin over [0, 8π], with portable sine (same bits on every machine).
    pub fn new() -> Sine {
        let mut y = [0.0; SINE_SAMPLES];
        for (k, v) in y.iter_mut().enumerate() {
            *v = math::sin(x(k));
        }
        let spans = spans();
        let mut dy = [0.0; SINE_SAMPLES];
        gradients(&y, &spans, &mut dy);
        let (lo, hi) = y
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
        Sine {
            y,
            dy,
            spans,
            mid: (lo + hi) / 2.0,
            scale: (hi - lo) / 0.8,
        }
    }

    /// The fitness of `net` (1 input, 1 output), in (0, 1000]; 0 when not finite.
    pub fn fitness(&self, net: &mut impl Network) -> f64 {
        let mut got = [0.0; SINE_SAMPLES];
        let mut out = [0.0];
        net.reset();
        for _ in 0..WARM_UP {
            net.activate(&[1.0], &mut out);
        }
        for g in got.iter_mut() {
            net.activate(&[1.0], &mut out);
            *g = (out[0] - 0.5) * self.scale + self.mid;
        }
        self.score(&got)
    }

    /// The fitness of every network in `lanes` (as [`Sine::fitness`] of
    /// each, the same bits), stepped side by side, pushed onto `out`.
    #[allow(dead_code)]
    pub fn fitness_lanes(&self, lanes: &mut RecurrentLanes, out: &mut Vec<f64>) {
        let n = lanes.lanes();
        assert!(n <= MAX_LANES, "at most {MAX_LANES} lanes");
        let mut got = [[0.0; SINE_SAMPLES]; MAX_LANES];
        let mut o = [[0.0]; MAX_LANES];
        let inputs = [&[1.0][..]; MAX_LANES];
        lanes.reset();
        for t in 0..WARM_UP + SINE_SAMPLES {
            let mut outs: [&mut [f64]; MAX_LANES] = o.each_mut().map(|o| &mut o[..]);
            lanes.activate(&inputs[..n], &mut outs[..n]);
            if let Some(k) = t.checked_sub(WARM_UP) {
                for (g, o) in got.iter_mut().zip(&o).take(n) {
                    g[k] = (o[0] - 0.5) * self.scale + self.mid;
                }
            }
        }
        out.extend(got[..n].iter().map(|g| self.score(g)));
    }

    /// The fitness of the outputs `got`.
    fn score(&self, got: &[f64; SINE_SAMPLES]) -> f64 {
        if got.iter().any(|v| !v.is_finite()) {
            return 0.0;
        }
        let mut dgot = [0.0; SINE_SAMPLES];
        gradients(got, &self.spans, &mut dgot);
        let mse = |a: &[f64], b: &[f64]| {
            a.iter().zip(b).map(|(p, q)| (p - q) * (p - q)).sum::<f64>() / SINE_SAMPLES as f64
        };
        let e =
            (1.0 - GRADIENT_WEIGHT) * mse(got, &self.y) + GRADIENT_WEIGHT * mse(&dgot, &self.dy);
        20.0 / (e + 0.02)
    }
}
