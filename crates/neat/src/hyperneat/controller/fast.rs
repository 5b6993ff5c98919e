//! The fast precision of the controller: an f32 copy of the weights and
//! biases in the same panelled layout (columns padded to 16 lanes, panels of
//! 32 neurons), f32 neuron states, and the f32 step around the kernel.
//!
//! Inputs arrive as f32 (the sensors' single-precision read) or as f64,
//! rounded to f32 once per step; the new states are widened back to f64 for the outputs. Rounding and
//! widening are exact IEEE conversions, the kernel the same f32 operations
//! in the same order at every level, so fast runs give the same bits on
//! every CPU.

use super::step::{Element, Kernel};
use crate::simd::SimdLevel;

/// The f32 weights and biases of a controller in fast precision.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Fast {
    /// Inputs per robot.
    ni: usize,
    /// Neurons.
    n: usize,
    /// `n` rounded up to a multiple of f32's [`Element::PAD`].
    pub(super) stride: usize,
    /// Biases rounded to f32, padded to `stride`.
    bias: Vec<f32>,
    /// Weights rounded to f32, panelled as the f64 ones but with f32's panel width.
    weights: Vec<f32>,
    /// The neuron states of the [`Network`](crate::network::Network) interface.
    pub(super) own: FastStates,
}

/// Where the weight from source `j` to neuron `i` lies in a panelled matrix
/// of `m` sources and columns of `stride` lanes cut into panels of `panel`.
pub(super) fn panel_index(panel: usize, stride: usize, m: usize, j: usize, i: usize) -> usize {
    let p0 = i / panel * panel;
    let width = panel.min(stride - p0);
    p0 * m + j * width + (i - p0)
}

impl Fast {
    /// The f32 copy of `n` neurons' `bias` (rounded to nearest), its
    /// weights all zero until [`Fast::set_column`] fills them.
    pub(super) fn zeroed(ni: usize, n: usize, bias: &[f64]) -> Fast {
        let stride = n.next_multiple_of(<f32 as Element>::PAD);
        let mut b = vec![0.0f32; stride];
        for (b, &v) in b.iter_mut().zip(bias) {
            *b = v as f32;
        }
        Fast {
            ni,
            n,
            stride,
            bias: b,
            weights: super::pages::zeroed((ni + n) * stride),
            own: FastStates::new(1, ni, stride),
        }
    }

    /// Sets the weights from source `j` (of `ni + n`) to every neuron to
    /// `column` (`n` values) rounded to the nearest f32, a panel's run at a time.
    pub(super) fn set_column(&mut self, j: usize, column: &[f64]) {
        let panel = <f32 as Element>::PANEL;
        let m = self.ni + self.n;
        for (p0, src) in (0..).step_by(panel).zip(column[..self.n].chunks(panel)) {
            let at = panel_index(panel, self.stride, m, j, p0);
            for (d, &s) in self.weights[at..at + src.len()].iter_mut().zip(src) {
                *d = s as f32;
            }
        }
    }

    /// Where the weight from source `j` to neuron `i` lies.
    fn at(&self, j: usize, i: usize) -> usize {
        panel_index(<f32 as Element>::PANEL, self.stride, self.ni + self.n, j, i)
    }

    /// Sets the weight from source `j` to neuron `i` to `w` rounded to f32
    /// (what [`Fast::set_column`] would give it).
    pub(super) fn set_weight(&mut self, j: usize, i: usize, w: f64) {
        let at = self.at(j, i);
        self.weights[at] = w as f32;
    }

    /// The weight from source `j` to neuron `i`.
    pub(super) fn weight(&self, j: usize, i: usize) -> f32 {
        self.weights[self.at(j, i)]
    }

    /// The biases (padded with zeros).
    pub(super) fn biases(&self) -> &[f32] {
        &self.bias
    }

    /// Number of non-zero weights.
    pub(super) fn expressed(&self) -> usize {
        self.weights.iter().filter(|w| **w != 0.0).count()
    }

    fn kernel(&self) -> Kernel<'_, f32> {
        Kernel {
            ni: self.ni,
            n: self.n,
            stride: self.stride,
            bias: &self.bias,
            weights: &self.weights,
        }
    }

    /// One synchronous update of `states.robots()` robots reading f64
    /// `inputs` (robot after robot): the f32 states advance, and each
    /// robot's new states are widened into `wide[r * wide_stride..][..n]`.
    pub(super) fn step(
        &self,
        level: SimdLevel,
        states: &mut FastStates,
        inputs: &[f64],
        wide: &mut [f64],
        wide_stride: usize,
    ) {
        for (x, &v) in states.x.iter_mut().zip(inputs) {
            *x = v as f32;
        }
        let FastStates {
            robots,
            x,
            state,
            acc,
        } = states;
        self.kernel().step(level, *robots, x, state, acc);
        self.widen(states, wide, wide_stride);
    }

    /// [`Fast::step`] with inputs already in f32 (the sensors' single-precision read).
    pub(super) fn step_single(
        &self,
        level: SimdLevel,
        states: &mut FastStates,
        inputs: &[f32],
        wide: &mut [f64],
        wide_stride: usize,
    ) {
        self.kernel().step(
            level,
            states.robots,
            inputs,
            &mut states.state,
            &mut states.acc,
        );
        self.widen(states, wide, wide_stride);
    }

    /// Each robot's new f32 states widened into `wide[r * wide_stride..][..n]`.
    fn widen(&self, states: &FastStates, wide: &mut [f64], wide_stride: usize) {
        if self.n > 0 {
            for (w, y) in wide
                .chunks_exact_mut(wide_stride)
                .zip(states.state.chunks_exact(self.stride))
            {
                for (w, &y) in w[..self.n].iter_mut().zip(&y[..self.n]) {
                    *w = f64::from(y);
                }
            }
        }
    }
}

/// The f32 neuron states of several robots in fast precision, and the
/// buffers of their step.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct FastStates {
    /// Number of robots.
    robots: usize,
    /// Inputs rounded to f32, robot after robot.
    x: Vec<f32>,
    /// `y(t)` of robot `r` at `state[r * stride..]` (padding lanes stay 0).
    state: Vec<f32>,
    /// Scratch of the synchronous update, laid out as `state`.
    acc: Vec<f32>,
}

impl FastStates {
    /// Zero states of `robots` robots with `ni` inputs and columns of `stride`.
    pub(super) fn new(robots: usize, ni: usize, stride: usize) -> FastStates {
        FastStates {
            robots,
            x: vec![0.0; robots * ni],
            state: vec![0.0; robots * stride],
            acc: vec![0.0; robots * stride],
        }
    }

    /// Every state back to zero.
    pub(super) fn reset(&mut self) {
        self.state.fill(0.0);
    }
}
